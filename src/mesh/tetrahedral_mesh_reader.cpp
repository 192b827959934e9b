#include "volspline/mesh/tetrahedral_mesh_reader.h"

#include <algorithm>
#include <cctype>
#include <charconv>
#include <cmath>
#include <fstream>
#include <functional>
#include <optional>
#include <string>
#include <string_view>
#include <type_traits>
#include <vector>

#include <vtkCallbackCommand.h>
#include <vtkCellType.h>
#include <vtkCommand.h>
#include <vtkExecutive.h>
#include <vtkIdList.h>
#include <vtkNew.h>
#include <vtkPoints.h>
#include <vtkSmartPointer.h>
#include <vtkUnstructuredGrid.h>
#include <vtkUnstructuredGridReader.h>
#include <vtkXMLUnstructuredGridReader.h>

#include "vtk_reader_errors.h"
#include "volspline/core/coordinate_range.h"
#include "volspline/core/error.h"
#include "volspline/io/atomic_file.h"

namespace volspline {
namespace {

// Where each tetrahedron and point came from, so that the errors of orient_positively and
// validate_tetrahedral_mesh (located at "tetrahedra[i]" / "points[i]") can name the file's
// place instead.
struct Origins {
  std::string tetrahedra_file;
  std::string points_file;
  std::string unit;  // "line" or "cell" / "point"
  std::string point_unit;
  std::vector<std::size_t> tetrahedron_place;
  std::vector<std::size_t> point_place;
};

TetrahedralMesh checked(TetrahedralMesh mesh, const Origins& origins) {
  // The range of coordinates (core/coordinate_range.h), located at the point's place in its file.
  if (!mesh.points.empty()) {
    check_point_coordinate_range(
        mesh.points.front().data(), mesh.points.size(), 3, 3,
        [&](std::size_t i, std::size_t c) {
          const std::string place = i < origins.point_place.size() ? " " + std::to_string(origins.point_place[i]) : "";
          const std::string index = origins.point_unit == "point" ? "" : " (point " + std::to_string(i) + ")";
          return origins.points_file + ": " + origins.point_unit + place + index + ", " + std::string(1, "xyz"[c]);
        },
        origins.points_file, "points", "docs/formats.md");
  }
  try {
    orient_positively(mesh);
    validate_tetrahedral_mesh(mesh);
  } catch (const InvalidInput& e) {
    const auto index_of = [&](std::string_view prefix) -> std::optional<std::size_t> {
      if (e.where().rfind(prefix, 0) != 0) return std::nullopt;
      return std::stoul(e.where().substr(prefix.size()));
    };
    if (const auto t = index_of("tetrahedra["); t && *t < origins.tetrahedron_place.size()) {
      throw InvalidInput("tetrahedron " + std::to_string(*t) + ": " + e.message(),
                         origins.tetrahedra_file + ": " + origins.unit + " " +
                             std::to_string(origins.tetrahedron_place[*t]));
    }
    if (const auto p = index_of("points["); p && *p < origins.point_place.size()) {
      throw InvalidInput("point " + std::to_string(*p) + ": " + e.message(),
                         origins.points_file + ": " + origins.point_unit + " " + std::to_string(origins.point_place[*p]));
    }
    throw InvalidInput(e.message(), origins.tetrahedra_file);
  }
  return mesh;
}

// ---------------------------------------------------------------------------------------------
// Text formats: whitespace-separated tokens with their line numbers; `#` starts a comment.

struct Token {
  std::string_view text;
  std::size_t line;
};

std::vector<Token> tokenize(std::string_view text) {
  std::vector<Token> tokens;
  std::size_t line = 1;
  std::size_t i = 0;
  while (i < text.size()) {
    const char c = text[i];
    if (c == '\n') {
      ++line;
      ++i;
    } else if (c == '#') {
      while (i < text.size() && text[i] != '\n') ++i;
    } else if (std::isspace(static_cast<unsigned char>(c))) {
      ++i;
    } else {
      const std::size_t start = i;
      while (i < text.size() && !std::isspace(static_cast<unsigned char>(text[i])) && text[i] != '#') ++i;
      tokens.push_back({text.substr(start, i - start), line});
    }
  }
  return tokens;
}

std::string printable(std::string_view token) {
  std::string out = "'";
  for (const char c : token.substr(0, 40)) out += (c >= 32 && c < 127) ? c : '?';
  if (token.size() > 40) out += "...";
  return out + "'";
}

// Reads tokens in order; every failure names the file and the line.
class TokenReader {
 public:
  TokenReader(std::string source, std::string_view text) : source_(std::move(source)), tokens_(tokenize(text)) {
    last_line_ = std::count(text.begin(), text.end(), '\n') + 1;
  }
  bool done() const { return next_ >= tokens_.size(); }
  std::size_t line() const { return done() ? last_line_ : tokens_[next_].line; }
  const Token& peek() const { return tokens_[next_]; }
  [[noreturn]] void fail(const std::string& message, std::optional<std::size_t> at = std::nullopt) const {
    throw InvalidInput(message, source_ + ": line " + std::to_string(at ? *at : line()));
  }
  const Token& take(const std::string& what) {
    if (done()) fail("the file ends where " + what + " was expected (truncated?)");
    return tokens_[next_++];
  }
  double number(const std::string& what) {
    const Token& t = take(what);
    std::string_view s = t.text;
    if (!s.empty() && s.front() == '+') s.remove_prefix(1);
    double value = 0;
    const auto result = std::from_chars(s.data(), s.data() + s.size(), value);
    if (s.empty() || result.ec != std::errc() || result.ptr != s.data() + s.size() || !std::isfinite(value)) {
      fail("expected " + what + " (a finite number), got " + printable(t.text), t.line);
    }
    return value;
  }
  long long integer(const std::string& what) {
    const Token& t = take(what);
    std::string_view s = t.text;
    if (!s.empty() && s.front() == '+') s.remove_prefix(1);
    long long value = 0;
    const auto result = std::from_chars(s.data(), s.data() + s.size(), value);
    if (s.empty() || result.ec != std::errc() || result.ptr != s.data() + s.size()) {
      fail("expected " + what + " (an integer), got " + printable(t.text), t.line);
    }
    return value;
  }
  // Before entry i of `declared`: the file must not end here.
  void expect_entry(long long i, long long declared, const std::string& what) const {
    if (done()) {
      fail("the header declares " + std::to_string(declared) + " " + what + ", the file ends after " + std::to_string(i) +
           " (truncated?)");
    }
  }
  // A count no larger than the tokens left can back (each entry has at least `per_entry`).
  std::size_t count(const std::string& what, std::size_t per_entry) {
    const std::size_t at = line();
    const long long n = integer(what);
    if (n < 0) fail(what + " is negative: " + std::to_string(n), at);
    const std::size_t left = tokens_.size() - next_;
    if (static_cast<unsigned long long>(n) > left / std::max<std::size_t>(per_entry, 1)) {
      fail(what + " is " + std::to_string(n) + " but the file has room for at most " +
               std::to_string(left / std::max<std::size_t>(per_entry, 1)) + " (truncated?)",
           at);
    }
    return static_cast<std::size_t>(n);
  }

 private:
  std::string source_;
  std::vector<Token> tokens_;
  std::size_t next_ = 0;
  std::size_t last_line_ = 1;
};

bool equals_ignoring_case(std::string_view a, std::string_view b) {
  return a.size() == b.size() && std::equal(a.begin(), a.end(), b.begin(), [](char x, char y) {
           return std::tolower(static_cast<unsigned char>(x)) == std::tolower(static_cast<unsigned char>(y));
         });
}

// medit (INRIA's .mesh, ASCII): keyword sections, 1-based indices, a reference number after
// each entry.
TetrahedralMesh read_medit(const std::filesystem::path& path) {
  const std::string source = path.string();
  const std::string text = read_file(path);
  TokenReader in(source, text);
  // Numbers per entry of the sections that are skipped; volume cells other than tetrahedra
  // are refused instead.
  struct Section {
    std::string_view name;
    int numbers;
  };
  static constexpr Section kSkipped[] = {{"Edges", 3},
                                         {"Triangles", 4},
                                         {"Quadrilaterals", 5},
                                         {"Corners", 1},
                                         {"Ridges", 1},
                                         {"RequiredVertices", 1},
                                         {"RequiredEdges", 1},
                                         {"RequiredTriangles", 1},
                                         {"RequiredQuadrilaterals", 1},
                                         {"Normals", 3},
                                         {"NormalAtVertices", 2},
                                         {"Tangents", 3},
                                         {"TangentAtVertices", 2}};
  static constexpr std::string_view kRefused[] = {"Hexahedra", "Prisms", "Pyramids", "TetrahedraP2", "Tetrahedra10"};
  TetrahedralMesh mesh;
  Origins origins{source, source, "line", "line", {}, {}};
  bool saw_vertices = false, saw_tetrahedra = false;
  int dimension = 3;
  while (!in.done()) {
    const Token keyword = in.take("a keyword");
    const auto is = [&](std::string_view name) { return equals_ignoring_case(keyword.text, name); };
    if (is("MeshVersionFormatted")) {
      in.integer("the version");
    } else if (is("Dimension")) {
      dimension = static_cast<int>(in.integer("the dimension"));
      if (dimension != 3) in.fail("Dimension is " + std::to_string(dimension) + "; a tetrahedral mesh needs 3", keyword.line);
    } else if (is("End")) {
      break;
    } else if (is("Vertices")) {
      if (saw_vertices) in.fail("a second Vertices section", keyword.line);
      saw_vertices = true;
      const std::size_t n = in.count("the number of vertices", dimension + 1);
      mesh.points.reserve(n);
      for (std::size_t i = 0; i < n; ++i) {
        origins.point_place.push_back(in.line());
        Eigen::Vector3d p;
        for (int k = 0; k < 3; ++k) p[k] = in.number("coordinate " + std::to_string(k) + " of vertex " + std::to_string(i + 1));
        in.integer("the reference of vertex " + std::to_string(i + 1));
        mesh.points.push_back(p);
      }
    } else if (is("Tetrahedra")) {
      if (saw_tetrahedra) in.fail("a second Tetrahedra section", keyword.line);
      saw_tetrahedra = true;
      const std::size_t n = in.count("the number of tetrahedra", 5);
      mesh.tetrahedra.reserve(n);
      for (std::size_t i = 0; i < n; ++i) {
        const std::size_t at = in.line();
        origins.tetrahedron_place.push_back(at);
        std::array<int, 4> t;
        for (int k = 0; k < 4; ++k) {
          const long long v = in.integer("vertex " + std::to_string(k) + " of tetrahedron " + std::to_string(i + 1));
          if (v < 1 || v > static_cast<long long>(mesh.points.size())) {
            in.fail("tetrahedron " + std::to_string(i + 1) + " names vertex " + std::to_string(v) + ", not one of the " +
                        std::to_string(mesh.points.size()) + " vertices (1-based" +
                        (saw_vertices ? "" : "; Vertices must come before Tetrahedra") + ")",
                    at);
          }
          t[k] = static_cast<int>(v - 1);
        }
        in.integer("the reference of tetrahedron " + std::to_string(i + 1));
        mesh.tetrahedra.push_back(t);
      }
    } else if (std::any_of(std::begin(kRefused), std::end(kRefused), is)) {
      const std::size_t n = in.count("the number of " + std::string(keyword.text), 1);
      if (n > 0) {
        in.fail(std::string(keyword.text) + ": volume cells other than tetrahedra are not read (Ω would have holes)",
                keyword.line);
      }
    } else {
      const auto skipped = std::find_if(std::begin(kSkipped), std::end(kSkipped), [&](const Section& s) { return is(s.name); });
      if (skipped == std::end(kSkipped)) {
        in.fail("unknown keyword " + printable(keyword.text) + " (Vertices, Tetrahedra, End, ... expected)", keyword.line);
      }
      const std::size_t n = in.count("the number of " + std::string(keyword.text), skipped->numbers);
      for (std::size_t i = 0; i < n * skipped->numbers; ++i) in.number(std::string(keyword.text) + " data");
    }
  }
  if (!saw_vertices) in.fail("no Vertices section");
  if (mesh.tetrahedra.empty()) in.fail("no tetrahedra (a Tetrahedra section with at least one is needed)");
  return checked(std::move(mesh), origins);
}

// The integers of a TetGen header, each named for its error.
template <std::size_t N>
std::array<long long, N> header_integers(TokenReader& in, const std::array<const char*, N>& names) {
  std::array<long long, N> values;
  for (std::size_t k = 0; k < N; ++k) values[k] = in.integer(names[k]);
  return values;
}

// TetGen .node + .ele: a header line, then one numbered entry per line; numbering starts at
// 0 or 1 (the first point's number decides) and the .ele refers to the .node's numbers.
TetrahedralMesh read_tetgen(const std::filesystem::path& path) {
  std::filesystem::path node_path = path, ele_path = path;
  node_path.replace_extension(".node");
  ele_path.replace_extension(".ele");
  const std::string node_source = node_path.string(), ele_source = ele_path.string();
  TetrahedralMesh mesh;
  Origins origins{ele_source, node_source, "line", "line", {}, {}};

  const std::string node_text = read_file(node_path);
  TokenReader nodes(node_source, node_text);
  const std::size_t header_line = nodes.line();
  const auto [declared, dimension, attributes, markers] = header_integers<4>(
      nodes, {"the number of points", "the dimension", "the number of attributes", "the number of boundary markers"});
  if (dimension != 3) nodes.fail("dimension is " + std::to_string(dimension) + "; a tetrahedral mesh needs 3", header_line);
  if (attributes < 0 || markers < 0 || markers > 1) nodes.fail("bad attribute or boundary-marker count", header_line);
  if (declared < 0) nodes.fail("the number of points is negative", header_line);
  const std::size_t per_point = 4 + static_cast<std::size_t>(attributes + markers);
  long long base = 0;
  for (long long i = 0; i < declared; ++i) {
    nodes.expect_entry(i, declared, "points");
    const std::size_t at = nodes.line();
    const long long number = nodes.integer("the number of point " + std::to_string(i));
    if (i == 0) {
      base = number;
      if (base != 0 && base != 1) nodes.fail("the first point is numbered " + std::to_string(base) + "; TetGen numbers from 0 or 1", at);
    }
    if (number != base + i) {
      nodes.fail("point numbered " + std::to_string(number) + " where " + std::to_string(base + i) + " was expected", at);
    }
    origins.point_place.push_back(at);
    Eigen::Vector3d p;
    for (int k = 0; k < 3; ++k) p[k] = nodes.number("coordinate " + std::to_string(k) + " of point " + std::to_string(number));
    for (std::size_t k = 4; k < per_point; ++k) nodes.number("an attribute or marker of point " + std::to_string(number));
    mesh.points.push_back(p);
  }
  if (!nodes.done()) nodes.fail("more data after the " + std::to_string(declared) + " points the header declares");

  const std::string ele_text = read_file(ele_path);
  TokenReader elements(ele_source, ele_text);
  const std::size_t ele_header = elements.line();
  const auto [tetrahedra, corners, regions] = header_integers<3>(
      elements, {"the number of tetrahedra", "the number of nodes per tetrahedron", "the number of region attributes"});
  if (corners != 4) {
    elements.fail(std::to_string(corners) + " nodes per tetrahedron; only linear (4-node) tetrahedra are read", ele_header);
  }
  if (tetrahedra < 0 || regions < 0) elements.fail("negative count in the header", ele_header);
  for (long long i = 0; i < tetrahedra; ++i) {
    elements.expect_entry(i, tetrahedra, "tetrahedra");
    const std::size_t at = elements.line();
    elements.integer("the number of tetrahedron " + std::to_string(i));
    origins.tetrahedron_place.push_back(at);
    std::array<int, 4> t;
    for (int k = 0; k < 4; ++k) {
      const long long v = elements.integer("corner " + std::to_string(k) + " of tetrahedron " + std::to_string(i));
      if (v < base || v >= base + static_cast<long long>(mesh.points.size())) {
        elements.fail("corner " + std::to_string(k) + " is point " + std::to_string(v) + ", not one of " + node_source +
                          "'s points " + std::to_string(base) + ".." + std::to_string(base + mesh.points.size() - 1),
                      at);
      }
      t[k] = static_cast<int>(v - base);
    }
    for (long long k = 0; k < regions; ++k) elements.number("the region attribute of tetrahedron " + std::to_string(i));
    mesh.tetrahedra.push_back(t);
  }
  if (!elements.done()) elements.fail("more data after the " + std::to_string(tetrahedra) + " tetrahedra the header declares");
  if (mesh.tetrahedra.empty()) elements.fail("no tetrahedra", ele_header);
  return checked(std::move(mesh), origins);
}

// ---------------------------------------------------------------------------------------------
// VTK unstructured grids through the VTK library. Its errors arrive as ErrorEvents, which an
// observer collects instead of letting VTK print them.

using detail::VtkErrors;
using detail::vtk_message_text;
using detail::CapturedOutput;

std::string cell_type_name(int type) {
  switch (type) {
    case VTK_HEXAHEDRON: return "VTK_HEXAHEDRON";
    case VTK_VOXEL: return "VTK_VOXEL";
    case VTK_WEDGE: return "VTK_WEDGE";
    case VTK_PYRAMID: return "VTK_PYRAMID";
    case VTK_PENTAGONAL_PRISM: return "VTK_PENTAGONAL_PRISM";
    case VTK_HEXAGONAL_PRISM: return "VTK_HEXAGONAL_PRISM";
    case VTK_QUADRATIC_TETRA: return "VTK_QUADRATIC_TETRA";
    case VTK_QUADRATIC_HEXAHEDRON: return "VTK_QUADRATIC_HEXAHEDRON";
    case VTK_LAGRANGE_TETRAHEDRON: return "VTK_LAGRANGE_TETRAHEDRON";
    case VTK_POLYHEDRON: return "VTK_POLYHEDRON";
    default: return "cell type " + std::to_string(type);
  }
}

// Cells of dimension below 3 (points, lines, triangles, quads, polygons and their
// higher-order forms) are boundary or auxiliary elements: skipped.
bool is_lower_dimensional(int type) {
  switch (type) {
    case VTK_EMPTY_CELL: case VTK_VERTEX: case VTK_POLY_VERTEX: case VTK_LINE: case VTK_POLY_LINE:
    case VTK_TRIANGLE: case VTK_TRIANGLE_STRIP: case VTK_POLYGON: case VTK_PIXEL: case VTK_QUAD:
    case VTK_QUADRATIC_EDGE: case VTK_QUADRATIC_TRIANGLE: case VTK_QUADRATIC_QUAD: case VTK_QUADRATIC_POLYGON:
    case VTK_BIQUADRATIC_QUAD: case VTK_QUADRATIC_LINEAR_QUAD: case VTK_BIQUADRATIC_TRIANGLE: case VTK_CUBIC_LINE:
    case VTK_LAGRANGE_CURVE: case VTK_LAGRANGE_TRIANGLE: case VTK_LAGRANGE_QUADRILATERAL:
    case VTK_BEZIER_CURVE: case VTK_BEZIER_TRIANGLE: case VTK_BEZIER_QUADRILATERAL:
      return true;
    default:
      return false;
  }
}

TetrahedralMesh from_unstructured_grid(vtkUnstructuredGrid* grid, const std::string& source) {
  TetrahedralMesh mesh;
  Origins origins{source, source, "cell", "point", {}, {}};
  vtkPoints* points = grid->GetPoints();
  const vtkIdType num_points = points ? points->GetNumberOfPoints() : 0;
  mesh.points.reserve(num_points);
  for (vtkIdType i = 0; i < num_points; ++i) {
    double p[3];
    points->GetPoint(i, p);
    mesh.points.emplace_back(p[0], p[1], p[2]);
    origins.point_place.push_back(static_cast<std::size_t>(i));
  }
  vtkNew<vtkIdList> ids;
  for (vtkIdType c = 0; c < grid->GetNumberOfCells(); ++c) {
    const int type = grid->GetCellType(c);
    if (type != VTK_TETRA) {
      if (is_lower_dimensional(type)) continue;
      throw InvalidInput(cell_type_name(type) + ": only tetrahedra (VTK_TETRA) are read as volume cells (Ω would have holes)",
                         source + ": cell " + std::to_string(c));
    }
    grid->GetCellPoints(c, ids);
    if (ids->GetNumberOfIds() != 4) {
      throw InvalidInput("a VTK_TETRA with " + std::to_string(ids->GetNumberOfIds()) + " points",
                         source + ": cell " + std::to_string(c));
    }
    std::array<int, 4> t;
    for (int k = 0; k < 4; ++k) {
      const vtkIdType v = ids->GetId(k);
      if (v < 0 || v >= num_points) {
        throw InvalidInput("corner " + std::to_string(k) + " is point " + std::to_string(v) + ", not one of the " +
                               std::to_string(num_points) + " points",
                           source + ": cell " + std::to_string(c));
      }
      t[k] = static_cast<int>(v);
    }
    mesh.tetrahedra.push_back(t);
    origins.tetrahedron_place.push_back(static_cast<std::size_t>(c));
  }
  if (mesh.tetrahedra.empty()) throw InvalidInput("no tetrahedra (VTK_TETRA cells)", source);
  return checked(std::move(mesh), origins);
}

void require_readable(const std::filesystem::path& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw IoError("cannot open " + path.string());
}

template <class Reader>
TetrahedralMesh read_vtk(const std::filesystem::path& path) {
  const std::string source = path.string();
  require_readable(path);
  VtkErrors errors;
  vtkNew<Reader> reader;
  errors.watch(*reader);
  if constexpr (std::is_same_v<Reader, vtkXMLUnstructuredGridReader>) {
    if (!reader->CanReadFile(source.c_str())) {
      throw InvalidInput("not a VTK XML unstructured grid (VTKFile type=\"UnstructuredGrid\")", source);
    }
  }
  reader->SetFileName(source.c_str());
  if constexpr (std::is_same_v<Reader, vtkUnstructuredGridReader>) {
    reader->ReadAllScalarsOff();
    if (!reader->IsFileUnstructuredGrid()) {
      throw InvalidInput(errors.first.empty() ? "not a legacy VTK file with DATASET UNSTRUCTURED_GRID" : vtk_message_text(errors.first),
                         source);
    }
  }
  if constexpr (std::is_same_v<Reader, vtkUnstructuredGridReader>) {
    // The legacy reader reports values it could not read as generic warnings and goes on with
    // zeros (a missing point read as the origin): caught and refused.
    const CapturedOutput output;
    reader->Update();
    if (errors.first.empty() && !output.first().empty()) errors.first = output.first();
  } else {
    reader->Update();
  }
  if (!errors.first.empty()) throw InvalidInput(vtk_message_text(errors.first), source);
  vtkUnstructuredGrid* grid = reader->GetOutput();
  if (!grid) throw InvalidInput("the VTK reader produced no grid", source);
  return from_unstructured_grid(grid, source);
}

std::string lower(std::string s) {
  std::transform(s.begin(), s.end(), s.begin(), [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  return s;
}

}  // namespace

TetrahedralMesh read_tetrahedral_mesh(const std::filesystem::path& path) {
  const std::string extension = lower(path.extension().string());
  if (extension == ".mesh") return read_medit(path);
  if (extension == ".node" || extension == ".ele") return read_tetgen(path);
  if (extension == ".vtu") return read_vtk<vtkXMLUnstructuredGridReader>(path);
  if (extension == ".vtk") return read_vtk<vtkUnstructuredGridReader>(path);
  throw InvalidInput("unknown tetrahedral mesh format " + (extension.empty() ? std::string("(no extension)") : extension) +
                         " (.mesh, .node/.ele, .vtu or .vtk expected)",
                     path.string());
}

}  // namespace volspline
