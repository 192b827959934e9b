#include "volspline/io/vtk_xml.h"

#include "simplex_vtu.h"
#include "vtk_data_array.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <map>
#include <set>
#include <utility>

#include <pugixml.hpp>

#include "text_numbers.h"
#include "volspline/analysis/jacobian_determinant.h"
#include "volspline/core/checked_arithmetic.h"
#include "volspline/core/error.h"
#include "volspline/core/resource_limits.h"
#include "volspline/core/format.h"
#include "volspline/io/atomic_file.h"
#include "volspline/io/coordinate_range.h"
#include "volspline/spline/attribute_spline.h"
#include "volspline/spline/bezier_extraction.h"
#include "xml_support.h"

namespace volspline {

namespace {

constexpr int kBezierCurve = 75;
constexpr int kBezierQuadrilateral = 77;
constexpr int kBezierHexahedron = 79;

int cell_type(int parameters) {
  return parameters == 1 ? kBezierCurve : parameters == 2 ? kBezierQuadrilateral : kBezierHexahedron;
}

}  // namespace

std::vector<std::array<int, 3>> vtk_bezier_point_order(int parameters, const std::array<int, 3>& degrees) {
  const int p = degrees[0];
  const int q = parameters >= 2 ? degrees[1] : 0;
  const int r = parameters >= 3 ? degrees[2] : 0;
  std::vector<std::array<int, 3>> order;
  if (parameters == 1) {
    order.push_back({0, 0, 0});
    order.push_back({p, 0, 0});
    for (int i = 1; i < p; ++i) order.push_back({i, 0, 0});
    return order;
  }
  // The corners and edges of the quadrilateral k = const, counter-clockwise from (0, 0).
  const std::array<std::array<int, 2>, 4> corners{{{0, 0}, {p, 0}, {p, q}, {0, q}}};
  const auto quad_corners = [&](int k) {
    for (const auto& c : corners) order.push_back({c[0], c[1], k});
  };
  // Edges run in the direction of increasing parameter, not around the quadrilateral.
  const auto quad_edges = [&](int k) {
    for (int i = 1; i < p; ++i) order.push_back({i, 0, k});
    for (int j = 1; j < q; ++j) order.push_back({p, j, k});
    for (int i = 1; i < p; ++i) order.push_back({i, q, k});
    for (int j = 1; j < q; ++j) order.push_back({0, j, k});
  };
  if (parameters == 2) {
    quad_corners(0);
    quad_edges(0);
    for (int j = 1; j < q; ++j)
      for (int i = 1; i < p; ++i) order.push_back({i, j, 0});
    return order;
  }
  quad_corners(0);
  quad_corners(r);
  quad_edges(0);
  quad_edges(r);
  for (const auto& c : corners)
    for (int k = 1; k < r; ++k) order.push_back({c[0], c[1], k});
  // Faces in the order i = 0, i = p, j = 0, j = q, k = 0, k = r; each with its first free index fastest.
  for (int i : {0, p})
    for (int k = 1; k < r; ++k)
      for (int j = 1; j < q; ++j) order.push_back({i, j, k});
  for (int j : {0, q})
    for (int k = 1; k < r; ++k)
      for (int i = 1; i < p; ++i) order.push_back({i, j, k});
  for (int k : {0, r})
    for (int j = 1; j < q; ++j)
      for (int i = 1; i < p; ++i) order.push_back({i, j, k});
  for (int k = 1; k < r; ++k)
    for (int j = 1; j < q; ++j)
      for (int i = 1; i < p; ++i) order.push_back({i, j, k});
  return order;
}

namespace {

// ------------------------------------------------------------------------------------------
// Writing.

struct Arrays {
  std::string points, weights, jacobian, degrees, objects, connectivity, offsets, types;
  std::vector<std::string> attributes;
  std::size_t num_points = 0;
  std::size_t num_cells = 0;
};

void append(std::string& out, double value) {
  out += format_double(value);
  out += ' ';
}

template <int D>
void write_object(Arrays& a, const TensorSpline<D>& spline, const ModelObject& object, std::size_t object_index,
                  const std::vector<std::string>& names, bool jacobian) {
  const std::string path = "objects[" + std::to_string(object_index) + "]";
  const int k = spline.dimension();
  if (k > 3) {
    throw InvalidInput("VTK points have 3 coordinates, the object has " + std::to_string(k), path);
  }
  try {
    validate_attributes(object);
  } catch (const InvalidInput& e) {
    throw e.located(path);
  }
  std::vector<std::vector<double>> fields;
  std::vector<int> column(names.size(), -1);
  for (std::size_t f = 0; f < names.size(); ++f) {
    const auto it = object.attributes.find(names[f]);
    if (it == object.attributes.end()) continue;
    column[f] = k + static_cast<int>(fields.size());
    fields.push_back(it->second);
  }
  const TensorSpline<D> augmented = append_coordinates(spline, fields);
  const auto m = static_cast<std::size_t>(augmented.dimension());
  if (jacobian) {
    // J at every control point of every Bézier cell: (p + 1)^3 evaluations of (p + 1)^3 terms of
    // m + 1 coordinates and their derivatives, per cell. Degree 64 makes that ~1e12 per cell.
    std::uint64_t points = 1, cells = 1;
    for (int d = 0; d < D; ++d) {
      points = saturating_product({points, static_cast<std::uint64_t>(spline.knot_vector(d).degree() + 1)});
      cells = saturating_product({cells, static_cast<std::uint64_t>(std::max(1, spline.knot_vector(d).num_spans()))});
    }
    require_work(saturating_product({cells, points, points, 4 * (m + 1)}),
                 "writing the Jacobian at the " + std::to_string(points) + " control points of each of " + std::to_string(cells) +
                     " Bezier cells",
                 path);
  }
  for (const TensorSpline<D>& piece : bezier_pieces(augmented)) {
    std::array<int, 3> degrees{};
    for (int d = 0; d < D; ++d) degrees[static_cast<std::size_t>(d)] = piece.knot_vector(d).degree();
    const auto order = vtk_bezier_point_order(D, degrees);
    std::vector<double> derivatives(jacobian ? (D + 1) * m : 0);
    for (const auto& ijk : order) {
      typename TensorSpline<D>::Index index{};
      for (int d = 0; d < D; ++d) index[static_cast<std::size_t>(d)] = ijk[static_cast<std::size_t>(d)];
      const auto i = static_cast<std::size_t>(piece.linear_index(index));
      const double* x = &piece.points()[i * m];
      const double w = piece.is_rational() ? piece.weights()[i] : 1.0;
      if (w == 0.0 && std::any_of(x, x + k, [](double c) { return c != 0.0; })) {
        throw InvalidInput("a Bezier cell has a point at infinity (weight 0), which VTK's rational Bezier cells cannot hold",
                           path);
      }
      for (int c = 0; c < 3; ++c) append(a.points, c < k ? x[c] : 0.0);
      append(a.weights, w);
      for (std::size_t f = 0; f < names.size(); ++f) {
        append(a.attributes[f], column[f] < 0 ? std::numeric_limits<double>::quiet_NaN() : x[column[f]]);
      }
      if constexpr (D == 3) {
        if (jacobian) {
          // The cell's own parameter of the control point: the Bézier Greville abscissae i/p.
          typename TensorSpline<D>::Parameter t{};
          for (std::size_t d = 0; d < 3; ++d) {
            t[d] = piece.domain_min(static_cast<int>(d)) +
                   (piece.domain_max(static_cast<int>(d)) - piece.domain_min(static_cast<int>(d))) * ijk[d] / degrees[d];
          }
          piece.evaluate_derivatives(t, 1, derivatives.data());
          append(a.jacobian, jacobian_determinant(derivatives.data(), static_cast<std::ptrdiff_t>(m)));
        }
      }
      a.connectivity += std::to_string(a.num_points++) + ' ';
    }
    a.offsets += std::to_string(a.num_points) + ' ';
    a.types += std::to_string(cell_type(D)) + ' ';
    for (int c = 0; c < 3; ++c) a.degrees += std::to_string(degrees[static_cast<std::size_t>(c)]) + ' ';
    a.objects += std::to_string(object_index) + ' ';
    ++a.num_cells;
  }
}


std::string xml_escaped(const std::string& text) {
  std::string out;
  for (char c : text) {
    switch (c) {
      case '&': out += "&amp;"; break;
      case '<': out += "&lt;"; break;
      case '>': out += "&gt;"; break;
      case '"': out += "&quot;"; break;
      default: out += c;
    }
  }
  return out;
}

}  // namespace

std::string vtu_text(const Model& model) {
  if (model.objects.empty()) throw InvalidInput("expected at least one object, got none", "objects");
  // A simplex spline volume is written on its own (io/simplex_vtu.h): its cells are sampled
  // tetrahedra, not Bézier cells.
  for (std::size_t i = 0; i < model.objects.size(); ++i) {
    if (!is_simplex_spline_volume(model.objects[i])) continue;
    if (model.objects.size() > 1)
      throw InvalidInput("a simplex_spline_volume is written to VTK alone; this model has " + std::to_string(model.objects.size()) +
                             " objects (write them to separate files)",
                         "objects[" + std::to_string(i) + "]");
    try {
      return simplex_spline_vtu_text(std::get<DmsSplineVolume>(model.objects[i].spline));
    } catch (const InvalidInput& e) {
      throw e.located("objects[" + std::to_string(i) + "]");
    }
  }
  std::set<std::string> name_set;
  bool rational = false;
  bool jacobian = true;
  for (std::size_t i = 0; i < model.objects.size(); ++i) {
    const ModelObject& object = model.objects[i];
    for (const auto& item : object.attributes) name_set.insert(item.first);
    visit_classic_spline(object, "VTK", "objects[" + std::to_string(i) + "]", [&](const auto& s) {
      rational = rational || s.is_rational();
      jacobian = jacobian && std::decay_t<decltype(s)>::num_parameters == 3 && s.dimension() == 3;
    });
  }
  std::vector<std::string> names(name_set.begin(), name_set.end());
  for (const std::string& name : names) {
    if (name == "RationalWeights" || name == "Jacobian" || name.empty()) {
      throw InvalidInput("an attribute named \"" + name + "\" would clash with an array volspline writes; rename it", "attributes");
    }
  }
  Arrays a;
  a.attributes.resize(names.size());
  for (std::size_t i = 0; i < model.objects.size(); ++i) {
    visit_classic_spline(model.objects[i], "VTK", "objects[" + std::to_string(i) + "]",
                         [&](const auto& s) { write_object(a, s, model.objects[i], i, names, jacobian); });
  }

  std::string out = "<?xml version=\"1.0\"?>\n";
  out += "<!-- written by volspline: one rational Bezier cell per knot cell of every object -->\n";
  out += "<VTKFile type=\"UnstructuredGrid\" version=\"2.2\" byte_order=\"LittleEndian\" header_type=\"UInt64\">\n";
  out += "  <UnstructuredGrid>\n";
  out += "    <Piece NumberOfPoints=\"" + std::to_string(a.num_points) + "\" NumberOfCells=\"" + std::to_string(a.num_cells) + "\">\n";
  out += "      <PointData";
  if (rational) out += " RationalWeights=\"RationalWeights\"";
  if (jacobian) out += " Scalars=\"Jacobian\"";
  out += ">\n";
  if (rational) vtk_data_array(out, "Float64", "RationalWeights", 1, a.weights);
  if (jacobian) vtk_data_array(out, "Float64", "Jacobian", 1, a.jacobian);
  for (std::size_t f = 0; f < names.size(); ++f) vtk_data_array(out, "Float64", xml_escaped(names[f]), 1, a.attributes[f]);
  out += "      </PointData>\n";
  out += "      <CellData HigherOrderDegrees=\"HigherOrderDegrees\">\n";
  vtk_data_array(out, "Int32", "HigherOrderDegrees", 3, a.degrees);
  vtk_data_array(out, "Int32", "Object", 1, a.objects);
  out += "      </CellData>\n";
  out += "      <Points>\n";
  vtk_data_array(out, "Float64", "Points", 3, a.points);
  out += "      </Points>\n";
  out += "      <Cells>\n";
  vtk_data_array(out, "Int64", "connectivity", 1, a.connectivity);
  vtk_data_array(out, "Int64", "offsets", 1, a.offsets);
  vtk_data_array(out, "UInt8", "types", 1, a.types);
  out += "      </Cells>\n";
  out += "    </Piece>\n  </UnstructuredGrid>\n</VTKFile>\n";
  return out;
}

void write_vtu(const Model& model, const std::filesystem::path& path) { write_file_atomically(path, vtu_text(model)); }

// ------------------------------------------------------------------------------------------
// Reading.

namespace {

using pugi::xml_node;

class VtuReader {
 public:
  explicit VtuReader(std::string_view text) : at_(text) {}

  [[noreturn]] void fail(const xml_node& node, const std::string& message) const { throw InvalidInput(message, at_.where(node)); }

  xml_node child(const xml_node& node, const char* name) const {
    xml_node c = node.child(name);
    if (!c) fail(node, "missing element <" + std::string(name) + ">");
    return c;
  }

  std::uint64_t count_attribute(const xml_node& node, const char* name) const {
    const auto value = detail::parse_integer(node.attribute(name).value(), 0, std::numeric_limits<std::int32_t>::max());
    if (!value) fail(node, "expected attribute " + std::string(name) + " to be a count, got " + detail::quoted_token(node.attribute(name).value()));
    return static_cast<std::uint64_t>(*value);
  }

  void check_ascii(const xml_node& array) const {
    const std::string format = array.attribute("format").value();
    if (format != "ascii") {
      fail(array, "expected format=\"ascii\", got " + detail::quoted_token(format) + " (binary and appended data are not read)");
    }
  }

  std::vector<double> numbers(const xml_node& array, std::uint64_t expected, const std::string& what) const {
    check_ascii(array);
    const std::string text = detail::element_text(array);
    std::vector<double> values;
    for (std::string_view token : detail::tokens_of(text)) {
      if (token == "nan" || token == "NaN") {
        values.push_back(std::numeric_limits<double>::quiet_NaN());
        continue;
      }
      const auto value = detail::parse_double(token);
      if (!value) fail(array, "expected a finite number, got " + detail::quoted_token(token));
      values.push_back(*value);
    }
    if (values.size() != expected) {
      fail(array, "expected " + std::to_string(expected) + " numbers (" + what + "), got " + std::to_string(values.size()));
    }
    return values;
  }

  std::vector<long long> integers(const xml_node& array, std::uint64_t expected, long long lo, long long hi, const std::string& what) const {
    check_ascii(array);
    const std::string text = detail::element_text(array);
    std::vector<long long> values;
    for (std::string_view token : detail::tokens_of(text)) {
      const auto value = detail::parse_integer(token, lo, hi);
      if (!value) fail(array, "expected an integer from " + std::to_string(lo) + " to " + std::to_string(hi) + ", got " + detail::quoted_token(token));
      values.push_back(*value);
    }
    if (values.size() != expected) {
      fail(array, "expected " + std::to_string(expected) + " integers (" + what + "), got " + std::to_string(values.size()));
    }
    return values;
  }

  xml_node named_array(const xml_node& parent, const std::string& name) const {
    for (xml_node a = parent.child("DataArray"); a; a = a.next_sibling("DataArray")) {
      if (name == a.attribute("Name").value()) return a;
    }
    fail(parent, "missing <DataArray Name=\"" + name + "\">");
  }

  Model model(const xml_node& file) const {
    if (std::string(file.name()) != "VTKFile" || std::string(file.attribute("type").value()) != "UnstructuredGrid") {
      fail(file, "expected <VTKFile type=\"UnstructuredGrid\">");
    }
    const std::string version = file.attribute("version").value();
    const auto dot = version.find('.');
    const auto major = detail::parse_integer(version.substr(0, dot), 0, 1000);
    const auto minor = dot == std::string::npos ? std::optional<long long>(0) : detail::parse_integer(version.substr(dot + 1), 0, 1000);
    if (!major || !minor || *major < 2 || (*major == 2 && *minor < 2)) {
      fail(file, "expected version 2.2 or later (earlier files order the edges of higher-order hexahedra differently), got " +
                     detail::quoted_token(version));
    }
    if (file.attribute("compressor")) fail(file, "compressed files are not read");
    Model result;
    const xml_node grid = child(file, "UnstructuredGrid");
    for (xml_node piece = grid.child("Piece"); piece; piece = piece.next_sibling("Piece")) read_piece(piece, result);
    if (result.objects.empty()) fail(grid, "expected at least one cell, got none");
    return result;
  }

 private:
  void read_piece(const xml_node& piece, Model& result) const {
    const std::uint64_t n_points = count_attribute(piece, "NumberOfPoints");
    const std::uint64_t n_cells = count_attribute(piece, "NumberOfCells");
    const xml_node points_array = child(child(piece, "Points"), "DataArray");
    if (std::string(points_array.attribute("NumberOfComponents").value()) != "3") {
      fail(points_array, "expected NumberOfComponents=\"3\"");
    }
    const std::vector<double> points = numbers(points_array, checked_product<std::uint64_t>({n_points, std::uint64_t{3}}, "coordinates: NumberOfPoints x 3"), "3 per point, NumberOfPoints = " + std::to_string(n_points));
    for (double x : points) {
      if (std::isnan(x)) fail(points_array, "expected finite coordinates, got NaN");
    }
    const xml_node cells = child(piece, "Cells");
    const auto max = static_cast<long long>(std::numeric_limits<std::int32_t>::max());
    const std::vector<long long> offsets = integers(named_array(cells, "offsets"), n_cells, 0, max, "one per cell");
    const std::vector<long long> types = integers(named_array(cells, "types"), n_cells, 0, 255, "one per cell");
    const std::uint64_t n_connectivity = n_cells == 0 ? 0 : static_cast<std::uint64_t>(offsets.back());
    const xml_node connectivity_array = named_array(cells, "connectivity");
    const std::vector<long long> connectivity =
        integers(connectivity_array, n_connectivity, 0, static_cast<long long>(n_points) - 1, "the last offset");

    std::vector<double> weights;
    std::map<std::string, std::vector<double>> fields;
    if (const xml_node point_data = piece.child("PointData")) {
      const std::string weights_name = point_data.attribute("RationalWeights").value();
      for (xml_node a = point_data.child("DataArray"); a; a = a.next_sibling("DataArray")) {
        const std::string name = a.attribute("Name").value();
        const std::string components = a.attribute("NumberOfComponents").value();
        if (name == "Jacobian" || !(components.empty() || components == "1")) continue;
        std::vector<double> values = numbers(a, n_points, "one per point, NumberOfPoints = " + std::to_string(n_points));
        if (!weights_name.empty() && name == weights_name) {
          weights = std::move(values);
        } else if (!name.empty()) {
          fields[name] = std::move(values);
        }
      }
      if (!weights_name.empty() && weights.empty()) fail(point_data, "missing the RationalWeights array \"" + weights_name + "\"");
    }
    std::vector<long long> degrees;
    if (const xml_node cell_data = piece.child("CellData")) {
      const std::string name = cell_data.attribute("HigherOrderDegrees").value();
      if (!name.empty()) degrees = integers(named_array(cell_data, name), checked_product<std::uint64_t>({n_cells, std::uint64_t{3}}, "degrees: NumberOfCells x 3"), 0, kMaxModelDegree, "3 per cell");
    }

    long long start = 0;
    for (std::size_t c = 0; c < n_cells; ++c) {
      const long long end = offsets[c];
      if (end < start) fail(named_array(cells, "offsets"), "offsets must not decrease: " + std::to_string(end) + " follows " + std::to_string(start));
      const auto count = static_cast<std::size_t>(end - start);
      int parameters = 0;
      if (types[c] == kBezierCurve) parameters = 1;
      if (types[c] == kBezierQuadrilateral) parameters = 2;
      if (types[c] == kBezierHexahedron) parameters = 3;
      if (parameters == 0) {
        fail(named_array(cells, "types"), "cell " + std::to_string(c) + " has type " + std::to_string(types[c]) +
                                              ": expected a Bezier curve (75), quadrilateral (77) or hexahedron (79)");
      }
      std::array<int, 3> degree{};
      if (!degrees.empty()) {
        for (int d = 0; d < 3; ++d) degree[static_cast<std::size_t>(d)] = static_cast<int>(degrees[3 * c + static_cast<std::size_t>(d)]);
      } else {
        // Without HigherOrderDegrees VTK takes the same degree in every direction.
        const double root = std::round(std::pow(static_cast<double>(count), 1.0 / parameters));
        for (int d = 0; d < parameters; ++d) degree[static_cast<std::size_t>(d)] = static_cast<int>(root) - 1;
      }
      std::array<std::size_t, 3> orders{1, 1, 1};
      std::string shown;
      for (int d = 0; d < parameters; ++d) {
        orders[static_cast<std::size_t>(d)] = static_cast<std::size_t>(std::max(degree[static_cast<std::size_t>(d)], 0) + 1);
        if (d) shown += ' ';
        shown += std::to_string(degree[static_cast<std::size_t>(d)]);
      }
      // Degrees guessed from the count without HigherOrderDegrees are not bounded by the format.
      const std::optional<std::size_t> product = product_exactly<std::size_t>(orders);
      const std::size_t expected = product.value_or(0);
      bool valid = product.has_value();
      for (int d = 0; d < parameters; ++d) valid = valid && degree[static_cast<std::size_t>(d)] >= 1;
      if (!valid || count != expected) {
        fail(named_array(cells, "offsets"), "cell " + std::to_string(c) + " has " + std::to_string(count) + " points, expected " +
                                                std::to_string(expected) + " for degrees " + shown +
                                                " (a Bezier cell of degree >= 1 with prod (degree + 1) points)");
      }
      switch (parameters) {
        case 1:
          result.objects.push_back(cell<1>(degree, connectivity, static_cast<std::size_t>(start), points, weights, fields, c, piece));
          break;
        case 2:
          result.objects.push_back(cell<2>(degree, connectivity, static_cast<std::size_t>(start), points, weights, fields, c, piece));
          break;
        default:
          result.objects.push_back(cell<3>(degree, connectivity, static_cast<std::size_t>(start), points, weights, fields, c, piece));
          break;
      }
      start = end;
    }
  }

  template <int D>
  ModelObject cell(const std::array<int, 3>& degree, const std::vector<long long>& connectivity, std::size_t start,
                   const std::vector<double>& points, const std::vector<double>& weights,
                   const std::map<std::string, std::vector<double>>& fields, std::size_t c, const xml_node& piece) const {
    const auto order = vtk_bezier_point_order(D, degree);
    std::array<KnotVector, D> knots = [&]<std::size_t... I>(std::index_sequence<I...>) {
      return std::array<KnotVector, D>{KnotVector::bezier(degree[I])...};
    }(std::make_index_sequence<D>{});
    const std::size_t n = order.size();
    std::vector<double> cp(3 * n);
    std::vector<double> w(weights.empty() ? 0 : n);
    std::map<std::string, std::vector<double>> attributes;
    for (const auto& item : fields) attributes[item.first].resize(n);
    for (std::size_t m = 0; m < n; ++m) {
      const auto& ijk = order[m];
      const std::size_t i = static_cast<std::size_t>(ijk[0]) +
                            static_cast<std::size_t>(degree[0] + 1) *
                                (static_cast<std::size_t>(ijk[1]) + static_cast<std::size_t>(degree[1] + 1) * static_cast<std::size_t>(ijk[2]));
      const auto point = static_cast<std::size_t>(connectivity[start + m]);
      for (std::size_t k = 0; k < 3; ++k) cp[3 * i + k] = points[3 * point + k];
      if (!w.empty()) w[i] = weights[point];
      for (const auto& item : fields) attributes[item.first][i] = item.second[point];
    }
    // An attribute that some object lacked was written as NaN at that object's points.
    std::erase_if(attributes, [](const auto& item) {
      return std::any_of(item.second.begin(), item.second.end(), [](double v) { return std::isnan(v); });
    });
    try {
      ModelObject object{"", true, TensorSpline<D>(std::move(knots), 3, std::move(cp), std::move(w)), nullptr};
      object.attributes = std::move(attributes);
      validate_attributes(object);
      return object;
    } catch (const InvalidInput& e) {
      fail(piece, "cell " + std::to_string(c) + ": " + e.message() + (e.where().empty() ? "" : " (" + e.where() + ")"));
    }
  }

  detail::Locator at_;
};

}  // namespace

Model parse_vtu(std::string_view text, const std::string& source_name) {
  try {
    pugi::xml_document document;
    const pugi::xml_parse_result parsed = document.load_buffer(text.data(), text.size(), pugi::parse_default, pugi::encoding_utf8);
    const detail::Locator locator(text);
    if (!parsed) {
      throw InvalidInput(std::string("invalid XML: ") + parsed.description(),
                         locator.line_and_column(static_cast<std::size_t>(std::max<std::ptrdiff_t>(parsed.offset, 0))));
    }
    if (const pugi::xml_node deep = detail::element_deeper_than_limit(document)) {
      throw InvalidInput("expected at most " + std::to_string(detail::kMaxXmlDepth) + " levels of nested elements, got more",
                         locator.line_and_column(static_cast<std::size_t>(std::max<std::ptrdiff_t>(deep.offset_debug(), 0))));
    }
    if (!document.document_element()) throw InvalidInput("expected a <VTKFile> element, got none");
    Model model = VtuReader(text).model(document.document_element());
    check_coordinate_range(model);
    return model;
  } catch (const InvalidInput& e) {
    std::string where = source_name;
    if (!where.empty() && !e.where().empty()) where += ": ";
    throw InvalidInput(e.message(), where + e.where());
  }
}

Model read_vtu(const std::filesystem::path& path) { return parse_vtu(read_file(path), path.string()); }

}  // namespace volspline
