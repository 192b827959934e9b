#include "volspline/mesh/mesh_writer.h"

#include <algorithm>
#include <bit>
#include <cctype>
#include <charconv>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <limits>
#include <map>
#include <vector>

#include <Eigen/Geometry>
#include <sstream>
#if VOLSPLINE_WITH_GLTF
#include <tiny_gltf.h>
#endif

#include "volspline/core/error.h"
#include "volspline/io/atomic_file.h"
#include "volspline/mesh/mesh_checks.h"
#include "volspline/mesh/parts.h"

namespace volspline {

namespace {

// 17 significant digits is the least that makes every double survive a text round trip.
// to_chars is used rather than streams because it ignores the global locale, which could
// otherwise turn the decimal point into a comma.
void append_number(std::string& out, double value) {
  char buffer[40];
  const auto result =
      std::to_chars(buffer, buffer + sizeof buffer, value, std::chars_format::general, 17);
  out.append(buffer, result.ptr);
}

void append_number(std::string& out, long long value) {
  char buffer[24];
  const auto result = std::to_chars(buffer, buffer + sizeof buffer, value);
  out.append(buffer, result.ptr);
}

void append_numbers(std::string& out, const Eigen::Vector3d& p) {
  append_number(out, p.x());
  out += ' ';
  append_number(out, p.y());
  out += ' ';
  append_number(out, p.z());
}

// Binary PLY and STL are little-endian by definition, whatever the host is.
template <class T>
void append_little_endian(std::string& out, T value) {
  char bytes[sizeof(T)];
  std::memcpy(bytes, &value, sizeof(T));
  if constexpr (std::endian::native == std::endian::big) std::reverse(bytes, bytes + sizeof(T));
  out.append(bytes, sizeof(T));
}

Eigen::Vector3d unit_normal(const TriangleMesh& mesh, const std::array<int, 3>& t) {
  const Eigen::Vector3d& a = mesh.positions[t[0]];
  const Eigen::Vector3d n = (mesh.positions[t[1]] - a).cross(mesh.positions[t[2]] - a);
  const double length = n.norm();
  // A degenerate triangle has no normal; STL readers accept zero and recompute it.
  return length > 0 ? Eigen::Vector3d(n / length) : Eigen::Vector3d::Zero();
}

std::string lowercase_extension(const std::filesystem::path& path) {
  std::string extension = path.extension().string();
  std::transform(extension.begin(), extension.end(), extension.begin(),
                 [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  return extension;
}

// What the face property `part` means, from the part table: "comment part: 0 = u_min, ...".
std::string ply_part_comment() {
  std::string out = "comment part:";
  for (const PartInfo& info : kParts) {
    out += ' ' + std::to_string(part_number(info.part)) + " = ";
    out += info.name;
    if (&info != &kParts.back()) out += ',';
  }
  return out + '\n';
}

}  // namespace

MeshFormat mesh_format_from_path(const std::filesystem::path& path) {
  const std::string extension = lowercase_extension(path);
  if (extension == ".ply") return MeshFormat::Ply;
  if (extension == ".obj") return MeshFormat::Obj;
  if (extension == ".stl") return MeshFormat::Stl;
  if (extension == ".glb") return MeshFormat::Glb;
  throw InvalidInput("cannot tell the mesh format of '" + path.string() +
                     "': expected the extension .ply, .obj, .stl or .glb");
}

bool is_ply_property_name(const std::string& name) {
  return !name.empty() && std::all_of(name.begin(), name.end(), [](char c) {
    return std::isalnum(static_cast<unsigned char>(c)) || c == '_' || c == '-' || c == '.';
  });
}

std::string ply_bytes(const TriangleMesh& mesh, bool ascii, const std::vector<double>& scalars,
                      const std::string& scalar_name) {
  std::vector<PlyVertexProperty> properties;
  if (!scalars.empty()) properties.push_back({scalar_name, scalars, false});
  return ply_bytes(mesh, ascii, properties);
}

std::string ply_bytes(const TriangleMesh& mesh, bool ascii, const std::vector<PlyVertexProperty>& properties) {
  validate_mesh(mesh);
  std::vector<std::string> names{"x", "y", "z", "u", "v", "w"};
  for (const PlyVertexProperty& p : properties) {
    if (p.values.size() != mesh.num_vertices())
      throw InvalidInput("the PLY property '" + p.name + "' needs one value per vertex: " + std::to_string(mesh.num_vertices()) +
                         " vertices, " + std::to_string(p.values.size()) + " values");
    if (!is_ply_property_name(p.name)) throw InvalidInput("a PLY property name must be letters, digits, '_', '-' or '.', got '" + p.name + "'");
    if (std::find(names.begin(), names.end(), p.name) != names.end()) throw InvalidInput("two PLY vertex properties are named '" + p.name + "'");
    names.push_back(p.name);
    if (p.integer)
      for (double value : p.values)
        if (!(std::abs(value) < 2147483647.0))
          throw InvalidInput("the PLY property '" + p.name + "' is an int; got " + std::to_string(value));
  }
  auto as_int = [](double value) { return static_cast<std::int32_t>(std::lround(value)); };
  std::string out;
  out += "ply\n";
  out += ascii ? "format ascii 1.0\n" : "format binary_little_endian 1.0\n";
  out += "comment volspline boundary mesh: (u, v, w) are the parameters of each vertex\n";
  out += ply_part_comment();
  out += "element vertex " + std::to_string(mesh.num_vertices()) + "\n";
  for (const char* name : {"x", "y", "z", "u", "v", "w"}) {
    out += "property double ";
    out += name;
    out += '\n';
  }
  for (const PlyVertexProperty& p : properties) out += std::string("property ") + (p.integer ? "int " : "double ") + p.name + "\n";
  out += "element face " + std::to_string(mesh.num_triangles()) + "\n";
  out += "property list uchar int vertex_indices\n";
  out += "property int part\n";
  out += "end_header\n";

  if (ascii) {
    for (std::size_t v = 0; v < mesh.num_vertices(); ++v) {
      append_numbers(out, mesh.positions[v]);
      out += ' ';
      append_numbers(out, mesh.parameters[v]);
      for (const PlyVertexProperty& p : properties) {
        out += ' ';
        if (p.integer) append_number(out, static_cast<long long>(as_int(p.values[v])));
        else append_number(out, p.values[v]);
      }
      out += '\n';
    }
    for (std::size_t t = 0; t < mesh.num_triangles(); ++t) {
      out += '3';
      for (const int index : mesh.triangles[t]) {
        out += ' ';
        append_number(out, static_cast<long long>(index));
      }
      out += ' ';
      append_number(out, static_cast<long long>(mesh.parts[t]));
      out += '\n';
    }
    return out;
  }

  out.reserve(out.size() + (48 + 8 * properties.size()) * mesh.num_vertices() + 17 * mesh.num_triangles());
  for (std::size_t v = 0; v < mesh.num_vertices(); ++v) {
    for (int i = 0; i < 3; ++i) append_little_endian(out, mesh.positions[v][i]);
    for (int i = 0; i < 3; ++i) append_little_endian(out, mesh.parameters[v][i]);
    for (const PlyVertexProperty& p : properties) {
      if (p.integer) append_little_endian(out, as_int(p.values[v]));
      else append_little_endian(out, p.values[v]);
    }
  }
  for (std::size_t t = 0; t < mesh.num_triangles(); ++t) {
    append_little_endian(out, std::uint8_t{3});
    for (const int index : mesh.triangles[t]) append_little_endian(out, std::int32_t{index});
    append_little_endian(out, std::int32_t{mesh.parts[t]});
  }
  return out;
}

// OBJ has no place for per-vertex parameters (vt is two-dimensional and meant for textures), so
// they are lost; write PLY to keep them.
std::string obj_bytes(const TriangleMesh& mesh) {
  validate_mesh(mesh);
  std::string out =
      "# volspline boundary mesh; groups part_N are the parts (see PLY for the "
      "parameters, which OBJ cannot hold)\n";
  for (const auto& p : mesh.positions) {
    out += "v ";
    append_numbers(out, p);
    out += '\n';
  }
  // Viewers list groups, so each part is written as one contiguous group rather than switching
  // groups whenever the part changes between consecutive triangles.
  std::map<int, std::vector<std::size_t>> by_part;
  for (std::size_t t = 0; t < mesh.num_triangles(); ++t) by_part[mesh.parts[t]].push_back(t);
  for (const auto& [part, triangles] : by_part) {
    out += "g part_" + std::to_string(part) + "\n";
    for (const std::size_t t : triangles) {
      out += 'f';
      for (const int index : mesh.triangles[t]) {
        out += ' ';
        append_number(out, static_cast<long long>(index) + 1);
      }
      out += '\n';
    }
  }
  return out;
}

std::string stl_bytes(const TriangleMesh& mesh, bool ascii) {
  validate_mesh(mesh);
  std::string out;
  if (ascii) {
    out += "solid volspline\n";
    for (const auto& t : mesh.triangles) {
      out += "  facet normal ";
      append_numbers(out, unit_normal(mesh, t));
      out += "\n    outer loop\n";
      for (const int index : t) {
        out += "      vertex ";
        append_numbers(out, mesh.positions[index]);
        out += '\n';
      }
      out += "    endloop\n  endfacet\n";
    }
    out += "endsolid volspline\n";
    return out;
  }

  if (mesh.num_triangles() > std::numeric_limits<std::uint32_t>::max()) {
    throw InvalidInput("binary STL holds at most 2^32 - 1 triangles, the mesh has " +
                       std::to_string(mesh.num_triangles()));
  }
  // Some readers take a file whose header starts with "solid" for ASCII STL, so it must not.
  std::string header = "volspline binary STL";
  header.resize(80, ' ');
  out.reserve(84 + 50 * mesh.num_triangles());
  out += header;
  append_little_endian(out, static_cast<std::uint32_t>(mesh.num_triangles()));
  for (const auto& t : mesh.triangles) {
    const Eigen::Vector3d n = unit_normal(mesh, t);
    for (int i = 0; i < 3; ++i) append_little_endian(out, static_cast<float>(n[i]));
    for (const int index : t) {
      for (int i = 0; i < 3; ++i) {
        append_little_endian(out, static_cast<float>(mesh.positions[index][i]));
      }
    }
    append_little_endian(out, std::uint16_t{0});  // "attribute byte count", unused
  }
  return out;
}

#if VOLSPLINE_WITH_GLTF
namespace {

/// glTF colours are linear (glTF 2.0, "Meshes": COLOR_0), part_color's are sRGB (mesh/parts.h).
double linear_from_srgb(double c) {
  return c <= 0.04045 ? c / 12.92 : std::pow((c + 0.055) / 1.055, 2.4);
}

template <class T>
void append_raw(std::vector<unsigned char>& out, T value) {
  const std::size_t at = out.size();
  out.resize(at + sizeof(T));
  std::memcpy(out.data() + at, &value, sizeof(T));
  if constexpr (std::endian::native == std::endian::big) std::reverse(out.begin() + static_cast<std::ptrdiff_t>(at), out.end());
}

int add_view(tinygltf::Model& model, std::size_t offset, std::size_t length, int target) {
  tinygltf::BufferView view;
  view.buffer = 0;
  view.byteOffset = offset;
  view.byteLength = length;
  view.target = target;
  model.bufferViews.push_back(view);
  return static_cast<int>(model.bufferViews.size()) - 1;
}

int add_accessor(tinygltf::Model& model, int view, int component, std::size_t count, int type) {
  tinygltf::Accessor accessor;
  accessor.bufferView = view;
  accessor.componentType = component;
  accessor.count = count;
  accessor.type = type;
  model.accessors.push_back(accessor);
  return static_cast<int>(model.accessors.size()) - 1;
}

}  // namespace
#endif

// tinygltf is optional in volspline::core (VOLSPLINE_WITH_GLTF, docs/using-volspline.md): without
// it every other format is written and .glb is refused.
std::string glb_bytes(const TriangleMesh& mesh, const std::vector<Eigen::Vector3d>& vertex_colors) {
#if !VOLSPLINE_WITH_GLTF
  (void)mesh;
  (void)vertex_colors;
  throw InvalidInput("writing glTF (.glb) needs tinygltf: this volspline was built with VOLSPLINE_WITH_GLTF=OFF");
#else
  validate_mesh(mesh);
  if (!vertex_colors.empty()) {
    if (vertex_colors.size() != mesh.num_vertices())
      throw InvalidInput("glTF vertex colours: " + std::to_string(mesh.num_vertices()) + " vertices, " +
                         std::to_string(vertex_colors.size()) + " colours");
    for (std::size_t v = 0; v < vertex_colors.size(); ++v)
      if (!vertex_colors[v].allFinite() || vertex_colors[v].minCoeff() < 0 || vertex_colors[v].maxCoeff() > 1)
        throw InvalidInput("glTF vertex colour " + std::to_string(v) + " has a component outside [0, 1]");
  }
  if (mesh.num_triangles() * 3 > std::numeric_limits<std::uint32_t>::max()) {
    throw InvalidInput("glTF indices are 32-bit: the mesh has too many triangles (" + std::to_string(mesh.num_triangles()) + ")");
  }
  // One glTF vertex per (vertex, part): colours and normals belong to a part.
  std::map<std::pair<int, int>, std::uint32_t> split;
  std::vector<int> source;
  std::vector<int> part_of;
  std::vector<std::uint32_t> indices;
  indices.reserve(3 * mesh.num_triangles());
  for (std::size_t t = 0; t < mesh.num_triangles(); ++t) {
    for (const int v : mesh.triangles[t]) {
      const auto [it, added] = split.try_emplace({v, mesh.parts[t]}, static_cast<std::uint32_t>(source.size()));
      if (added) {
        source.push_back(v);
        part_of.push_back(mesh.parts[t]);
      }
      indices.push_back(it->second);
    }
  }
  std::vector<Eigen::Vector3d> normals(source.size(), Eigen::Vector3d::Zero());
  for (std::size_t t = 0; t < mesh.num_triangles(); ++t) {
    const auto& tri = mesh.triangles[t];
    // The cross product's length is twice the area: an area-weighted sum.
    const Eigen::Vector3d n = (mesh.positions[tri[1]] - mesh.positions[tri[0]]).cross(mesh.positions[tri[2]] - mesh.positions[tri[0]]);
    for (int c = 0; c < 3; ++c) normals[indices[3 * t + static_cast<std::size_t>(c)]] += n;
  }
  std::vector<unsigned char> bytes;
  Eigen::Vector3d low = Eigen::Vector3d::Constant(std::numeric_limits<double>::infinity());
  Eigen::Vector3d high = -low;
  for (const int v : source) {
    for (int i = 0; i < 3; ++i) append_raw(bytes, static_cast<float>(mesh.positions[v][i]));
    low = low.cwiseMin(mesh.positions[v].cast<float>().cast<double>());
    high = high.cwiseMax(mesh.positions[v].cast<float>().cast<double>());
  }
  const std::size_t normals_at = bytes.size();
  for (const Eigen::Vector3d& n : normals) {
    // glTF requires unit normals; a vertex of degenerate triangles only gets an arbitrary one.
    const Eigen::Vector3d unit = n.norm() > 0 ? Eigen::Vector3d(n.normalized()) : Eigen::Vector3d::UnitZ();
    for (int i = 0; i < 3; ++i) append_raw(bytes, static_cast<float>(unit[i]));
  }
  const std::size_t colors_at = bytes.size();
  for (std::size_t k = 0; k < part_of.size(); ++k) {
    const Eigen::Vector3d srgb =
        vertex_colors.empty() ? part_color(part_of[k]) : vertex_colors[static_cast<std::size_t>(source[k])];
    for (int i = 0; i < 3; ++i) append_raw(bytes, static_cast<float>(linear_from_srgb(srgb[i])));
  }
  const std::size_t indices_at = bytes.size();
  for (const std::uint32_t index : indices) append_raw(bytes, index);

  tinygltf::Model model;
  model.asset.version = "2.0";
  model.asset.generator = "volspline";
  tinygltf::Buffer buffer;
  buffer.data = std::move(bytes);
  const std::size_t total = buffer.data.size();
  model.buffers.push_back(std::move(buffer));
  const std::size_t n = source.size();
  const int positions = add_accessor(model, add_view(model, 0, normals_at, TINYGLTF_TARGET_ARRAY_BUFFER),
                                     TINYGLTF_COMPONENT_TYPE_FLOAT, n, TINYGLTF_TYPE_VEC3);
  if (n > 0) {
    model.accessors[static_cast<std::size_t>(positions)].minValues = {low.x(), low.y(), low.z()};
    model.accessors[static_cast<std::size_t>(positions)].maxValues = {high.x(), high.y(), high.z()};
  }
  const int normal = add_accessor(model, add_view(model, normals_at, colors_at - normals_at, TINYGLTF_TARGET_ARRAY_BUFFER),
                                  TINYGLTF_COMPONENT_TYPE_FLOAT, n, TINYGLTF_TYPE_VEC3);
  const int color = add_accessor(model, add_view(model, colors_at, indices_at - colors_at, TINYGLTF_TARGET_ARRAY_BUFFER),
                                 TINYGLTF_COMPONENT_TYPE_FLOAT, n, TINYGLTF_TYPE_VEC3);
  const int index = add_accessor(model, add_view(model, indices_at, total - indices_at, TINYGLTF_TARGET_ELEMENT_ARRAY_BUFFER),
                                 TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT, indices.size(), TINYGLTF_TYPE_SCALAR);

  tinygltf::Material material;
  material.name = "volspline parts";
  material.pbrMetallicRoughness.baseColorFactor = {1.0, 1.0, 1.0, 1.0};
  material.pbrMetallicRoughness.metallicFactor = 0.0;
  material.pbrMetallicRoughness.roughnessFactor = 0.6;
  // Boundary meshes of folded solids are not always consistently oriented.
  material.doubleSided = true;
  model.materials.push_back(material);

  tinygltf::Primitive primitive;
  primitive.attributes["POSITION"] = positions;
  primitive.attributes["NORMAL"] = normal;
  primitive.attributes["COLOR_0"] = color;
  primitive.indices = index;
  primitive.material = 0;
  primitive.mode = TINYGLTF_MODE_TRIANGLES;
  tinygltf::Mesh gltf_mesh;
  gltf_mesh.name = "volspline boundary";
  gltf_mesh.primitives.push_back(primitive);
  model.meshes.push_back(gltf_mesh);
  tinygltf::Node node;
  node.mesh = 0;
  model.nodes.push_back(node);
  tinygltf::Scene scene;
  scene.nodes.push_back(0);
  model.scenes.push_back(scene);
  model.defaultScene = 0;

  std::ostringstream out(std::ios::binary);
  tinygltf::TinyGLTF writer;
  if (!writer.WriteGltfSceneToStream(&model, out, false, true)) throw Error("tinygltf could not write the glTF model");
  return out.str();
#endif
}

std::string mesh_bytes(const TriangleMesh& mesh, MeshFormat format,
                       const MeshWriteOptions& options) {
  switch (format) {
    case MeshFormat::Ply:
    {
      std::vector<PlyVertexProperty> properties;
      if (!options.vertex_scalars.empty()) properties.push_back({options.scalar_name, options.vertex_scalars, false});
      properties.insert(properties.end(), options.vertex_properties.begin(), options.vertex_properties.end());
      return ply_bytes(mesh, options.ascii, properties);
    }
    case MeshFormat::Obj:
      return obj_bytes(mesh);
    case MeshFormat::Stl:
      return stl_bytes(mesh, options.ascii);
    case MeshFormat::Glb:
      return glb_bytes(mesh, options.vertex_colors);
  }
  throw InvalidInput("unknown mesh format");
}

void write_ply(const TriangleMesh& mesh, const std::filesystem::path& path, bool ascii) {
  write_file_atomically(path, ply_bytes(mesh, ascii));
}

void write_obj(const TriangleMesh& mesh, const std::filesystem::path& path) {
  write_file_atomically(path, obj_bytes(mesh));
}

void write_stl(const TriangleMesh& mesh, const std::filesystem::path& path, bool ascii) {
  write_file_atomically(path, stl_bytes(mesh, ascii));
}

void write_glb(const TriangleMesh& mesh, const std::filesystem::path& path) {
  write_file_atomically(path, glb_bytes(mesh));
}

void write_mesh(const TriangleMesh& mesh, const std::filesystem::path& path,
                const MeshWriteOptions& options) {
  write_file_atomically(path, mesh_bytes(mesh, mesh_format_from_path(path), options));
}

}  // namespace volspline
