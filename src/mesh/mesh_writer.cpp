#include "volspline/mesh/mesh_writer.h"

#include <algorithm>
#include <bit>
#include <cctype>
#include <charconv>
#include <cstdint>
#include <cstring>
#include <limits>
#include <map>
#include <vector>

#include <Eigen/Geometry>

#include "volspline/core/error.h"
#include "volspline/io/atomic_file.h"
#include "volspline/mesh/mesh_checks.h"

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

}  // namespace

MeshFormat mesh_format_from_path(const std::filesystem::path& path) {
  const std::string extension = lowercase_extension(path);
  if (extension == ".ply") return MeshFormat::Ply;
  if (extension == ".obj") return MeshFormat::Obj;
  if (extension == ".stl") return MeshFormat::Stl;
  throw InvalidInput("cannot tell the mesh format of '" + path.string() +
                     "': expected the extension .ply, .obj or .stl");
}

std::string ply_bytes(const TriangleMesh& mesh, bool ascii) {
  validate_mesh(mesh);
  std::string out;
  out += "ply\n";
  out += ascii ? "format ascii 1.0\n" : "format binary_little_endian 1.0\n";
  out += "comment volspline boundary mesh: (u, v, w) are the parameters of each vertex\n";
  out += "comment part: 0..5 = faces u=min, u=max, v=min, v=max, w=min, w=max; 6 = det J = 0\n";
  out += "element vertex " + std::to_string(mesh.num_vertices()) + "\n";
  for (const char* name : {"x", "y", "z", "u", "v", "w"}) {
    out += "property double ";
    out += name;
    out += '\n';
  }
  out += "element face " + std::to_string(mesh.num_triangles()) + "\n";
  out += "property list uchar int vertex_indices\n";
  out += "property int part\n";
  out += "end_header\n";

  if (ascii) {
    for (std::size_t v = 0; v < mesh.num_vertices(); ++v) {
      append_numbers(out, mesh.positions[v]);
      out += ' ';
      append_numbers(out, mesh.parameters[v]);
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

  out.reserve(out.size() + 48 * mesh.num_vertices() + 17 * mesh.num_triangles());
  for (std::size_t v = 0; v < mesh.num_vertices(); ++v) {
    for (int i = 0; i < 3; ++i) append_little_endian(out, mesh.positions[v][i]);
    for (int i = 0; i < 3; ++i) append_little_endian(out, mesh.parameters[v][i]);
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

std::string mesh_bytes(const TriangleMesh& mesh, MeshFormat format,
                       const MeshWriteOptions& options) {
  switch (format) {
    case MeshFormat::Ply:
      return ply_bytes(mesh, options.ascii);
    case MeshFormat::Obj:
      return obj_bytes(mesh);
    case MeshFormat::Stl:
      return stl_bytes(mesh, options.ascii);
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

void write_mesh(const TriangleMesh& mesh, const std::filesystem::path& path,
                const MeshWriteOptions& options) {
  write_file_atomically(path, mesh_bytes(mesh, mesh_format_from_path(path), options));
}

}  // namespace volspline
