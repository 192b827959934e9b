#include "volspline/io/gismo_xml.h"

#include <algorithm>
#include <climits>
#include <array>
#include <cstdint>
#include <set>
#include <sstream>
#include <utility>
#include <vector>

#include <pugixml.hpp>

#include "text_numbers.h"
#include "xml_support.h"
#include "volspline/core/checked_arithmetic.h"
#include "volspline/core/error.h"
#include "volspline/core/format.h"
#include "volspline/io/atomic_file.h"
#include "volspline/io/coordinate_range.h"

namespace volspline {

namespace {

using nlohmann::json;
using pugi::xml_node;
using detail::Locator;
using detail::element_text;
using detail::tokens_of;

/// Limits that keep a small malformed file from asking for huge allocations.
constexpr long long kMaxGeoDim = 1 << 16;
constexpr long long kMaxId = 1LL << 40;

class Reader {
 public:
  explicit Reader(std::string_view text) : at_(text) {}

  [[noreturn]] void fail(const xml_node& node, const std::string& message) const {
    throw InvalidInput(message, at_.where(node));
  }

  xml_node child(const xml_node& node, const char* name, const std::string& what) const {
    xml_node c = node.child(name);
    if (!c) fail(node, "missing element <" + std::string(name) + "> (" + what + ")");
    return c;
  }

  std::vector<double> numbers(const xml_node& node) const {
    const std::string text = element_text(node);
    std::vector<double> values;
    for (std::string_view token : tokens_of(text)) {
      const auto value = detail::parse_double(token);
      if (!value) fail(node, "expected a finite number, got " + detail::quoted_token(token));
      values.push_back(*value);
    }
    return values;
  }

  std::vector<long long> integers(const xml_node& node, long long lo, long long hi) const {
    const std::string text = element_text(node);
    std::vector<long long> values;
    for (std::string_view token : tokens_of(text)) {
      const auto value = detail::parse_integer(token, lo, hi);
      if (!value) {
        fail(node, "expected an integer from " + std::to_string(lo) + " to " + std::to_string(hi) + ", got " +
                       detail::quoted_token(token));
      }
      values.push_back(*value);
    }
    return values;
  }

  long long integer_attribute(const xml_node& node, const char* name, long long lo, long long hi, bool required,
                              long long fallback = 0) const {
    const pugi::xml_attribute a = node.attribute(name);
    if (!a) {
      if (required) fail(node, "missing attribute " + std::string(name) + " (an integer from " + std::to_string(lo) + ")");
      return fallback;
    }
    const auto value = detail::parse_integer(a.value(), lo, hi);
    if (!value) {
      fail(node, "expected attribute " + std::string(name) + " to be an integer from " + std::to_string(lo) + " to " +
                     std::to_string(hi) + ", got " + detail::quoted_token(a.value()));
    }
    return *value;
  }

  std::string type_of(const xml_node& node) const { return node.attribute("type").value(); }

  KnotVector knot_vector(const xml_node& basis) const {
    if (type_of(basis) != "BSplineBasis") {
      fail(basis, "expected a <Basis type=\"BSplineBasis\">, got type " + detail::quoted_token(type_of(basis)));
    }
    const xml_node kv = child(basis, "KnotVector", "the knot vector of this direction");
    const int degree = static_cast<int>(integer_attribute(kv, "degree", 1, kMaxModelDegree, true));
    std::vector<double> knots = numbers(kv);
    const std::size_t needed = 2 * static_cast<std::size_t>(degree + 1);
    if (knots.size() < needed) {
      fail(kv, "a knot vector of degree " + std::to_string(degree) + " needs at least " + std::to_string(needed) +
                   " knots, got " + std::to_string(knots.size()));
    }
    try {
      return KnotVector(degree, std::move(knots));
    } catch (const InvalidInput& e) {
      fail(kv, e.message() + (e.where().empty() ? "" : " (knot " + e.where() + ")"));
    }
  }

  /// The D knot vectors of a (non-rational) B-spline basis element.
  template <int D>
  std::array<KnotVector, D> source_basis(const xml_node& basis) const {
    const std::string type = type_of(basis);
    const std::string tensor = "TensorBSplineBasis" + std::to_string(D);
    if constexpr (D == 1) {
      if (type == "BSplineBasis") return {knot_vector(basis)};
    }
    if (type != tensor) {
      fail(basis, "expected a <Basis type=\"" + (D == 1 ? std::string("BSplineBasis") : tensor) + "\">, got type " +
                      detail::quoted_token(type));
    }
    std::vector<xml_node> parts;
    for (xml_node b = basis.child("Basis"); b; b = b.next_sibling("Basis")) parts.push_back(b);
    if (parts.size() != static_cast<std::size_t>(D)) {
      fail(basis, "expected " + std::to_string(D) + " <Basis> elements (one knot vector per direction), got " +
                      std::to_string(parts.size()));
    }
    return [&]<std::size_t... I>(std::index_sequence<I...>) {
      return std::array<KnotVector, D>{knot_vector(parts[I])...};
    }(std::make_index_sequence<D>{});
  }

  template <int D>
  ModelObject geometry(const xml_node& node, bool rational) const {
    const xml_node basis = child(node, "Basis", "the basis of the geometry");
    std::vector<double> weights;
    xml_node weights_node;
    if (rational) {
      const std::string expected = D == 1 ? "NurbsBasis" : "TensorNurbsBasis" + std::to_string(D);
      if (type_of(basis) != expected) {
        fail(basis, "expected a <Basis type=\"" + expected + "\">, got type " + detail::quoted_token(type_of(basis)));
      }
      weights_node = child(basis, "weights", "one weight per coefficient");
    }
    std::array<KnotVector, D> knots =
        source_basis<D>(rational ? child(basis, "Basis", "the B-spline basis under the weights") : basis);

    const xml_node coefs = child(node, "coefs", "the control points, one per row");
    const auto k = static_cast<std::uint64_t>(integer_attribute(coefs, "geoDim", 1, kMaxGeoDim, true));
    std::array<std::uint64_t, D + 1> factors{};
    for (std::size_t d = 0; d < static_cast<std::size_t>(D); ++d) factors[d] = static_cast<std::uint64_t>(knots[d].num_basis());
    std::uint64_t n = 0;
    try {
      // Sizes in the spline are ints: coefficients x (geoDim + 1) numbers must fit in one.
      factors[D] = k + 1;
      checked_product<std::uint64_t>(factors, "coefficients (from the knot vectors) x (geoDim + 1)", {}, INT_MAX);
      factors[D] = 1;
      n = checked_product<std::uint64_t>(factors, "coefficients");
    } catch (const InvalidInput& e) {
      fail(coefs, e.message());
    }
    const pugi::xml_attribute format = coefs.attribute("format");
    if (format && std::string(format.value()) != "ascii") {
      fail(coefs, "expected format=\"ascii\", got " + detail::quoted_token(format.value()) + " (only text matrices are read)");
    }
    std::string shape;
    for (const KnotVector& kv : knots) shape += (shape.empty() ? "" : " x ") + std::to_string(kv.num_basis());
    std::vector<double> points = numbers(coefs);
    if (points.size() != n * k) {
      fail(coefs, "expected " + std::to_string(n * k) + " numbers (" + std::to_string(n) + " coefficients (" + shape +
                      " from the knot vectors) with geoDim " + std::to_string(k) + " each), got " +
                      std::to_string(points.size()));
    }
    if (rational) {
      weights = numbers(weights_node);
      if (weights.size() != n) {
        fail(weights_node, "expected " + std::to_string(n) + " weights (one per coefficient, " + shape + "), got " +
                               std::to_string(weights.size()));
      }
      // G+Smo's R_i = w_i N_i / sum_j w_j N_j: a weight-0 coefficient has no influence, which in
      // volspline's homogeneous form is the coefficient (0, 0).
      for (std::size_t i = 0; i < n; ++i) {
        if (weights[i] == 0.0) std::fill_n(points.begin() + static_cast<std::ptrdiff_t>(i * k), k, 0.0);
      }
    }
    try {
      ModelObject object{"", false, TensorSpline<D>(std::move(knots), static_cast<int>(k), std::move(points), std::move(weights)), nullptr};
      if (node.attribute("id")) {
        object.metadata = json{{"gismo", {{"id", integer_attribute(node, "id", -kMaxId, kMaxId, true)}}}};
      }
      return object;
    } catch (const InvalidInput& e) {
      const bool about_weights = e.where().rfind("weights", 0) == 0;
      fail(about_weights ? weights_node : node, e.message() + (e.where().empty() ? "" : " (" + e.where() + ")"));
    }
  }

  json multipatch(const xml_node& node, const std::set<long long>& ids) const {
    json entry = json::object();
    if (node.attribute("id")) entry["id"] = integer_attribute(node, "id", -kMaxId, kMaxId, true);
    const long long dim = integer_attribute(node, "parDim", 1, 3, false, 3);
    entry["parDim"] = dim;

    const xml_node patches = child(node, "patches", "the ids of the patch geometries");
    const std::string type = type_of(patches);
    std::vector<long long> patch_ids;
    if (type == "id_range") {
      const std::vector<long long> range = integers(patches, -kMaxId, kMaxId);
      if (range.size() != 2 || range[0] > range[1]) {
        fail(patches, "expected two ids FIRST LAST with FIRST <= LAST for type=\"id_range\"");
      }
      if (static_cast<std::uint64_t>(range[1] - range[0]) >= ids.size()) {
        fail(patches, "the range " + std::to_string(range[0]) + ".." + std::to_string(range[1]) + " names more patches than the " +
                          std::to_string(ids.size()) + " geometries of the file");
      }
      for (long long id = range[0]; id <= range[1]; ++id) patch_ids.push_back(id);
    } else if (type == "id_index") {
      patch_ids = integers(patches, -kMaxId, kMaxId);
    } else {
      fail(patches, "expected type=\"id_range\" or type=\"id_index\", got " + detail::quoted_token(type));
    }
    for (long long id : patch_ids) {
      if (!ids.contains(id)) fail(patches, "patch id " + std::to_string(id) + " is not the id of any <Geometry>");
    }
    entry["patches"] = patch_ids;

    // An interface is: patch side patch side, then parDim numbers of the direction map and
    // parDim orientation flags (G+Smo's boundaryInterface).
    const std::size_t row = 4 + 2 * static_cast<std::size_t>(dim);
    json interfaces = json::array();
    for (xml_node i = node.child("interfaces"); i; i = i.next_sibling("interfaces")) {
      const std::vector<long long> values = integers(i, -kMaxId, kMaxId);
      if (values.size() % row != 0) {
        fail(i, "expected rows of " + std::to_string(row) + " integers (patch side patch side, " + std::to_string(dim) +
                    " direction indices, " + std::to_string(dim) + " orientation flags), got " +
                    std::to_string(values.size()) + " integers");
      }
      for (std::size_t r = 0; r < values.size(); r += row) {
        for (std::size_t c : {std::size_t{0}, std::size_t{2}}) {
          if (std::find(patch_ids.begin(), patch_ids.end(), values[r + c]) == patch_ids.end()) {
            fail(i, "interface " + std::to_string(r / row + 1) + " names patch " + std::to_string(values[r + c]) +
                        ", which is not among the <patches>");
          }
          if (values[r + c + 1] < 1 || values[r + c + 1] > 2 * dim) {
            fail(i, "interface " + std::to_string(r / row + 1) + " names side " + std::to_string(values[r + c + 1]) +
                        ": expected a side from 1 to " + std::to_string(2 * dim));
          }
        }
        interfaces.push_back(std::vector<long long>(values.begin() + static_cast<std::ptrdiff_t>(r),
                                                    values.begin() + static_cast<std::ptrdiff_t>(r + row)));
      }
    }
    entry["interfaces"] = interfaces;

    json boundary = json::array();
    for (xml_node b = node.child("boundary"); b; b = b.next_sibling("boundary")) {
      const std::vector<long long> values = integers(b, -kMaxId, kMaxId);
      if (values.size() % 2 != 0) fail(b, "expected pairs of integers (patch side), got " + std::to_string(values.size()) + " integers");
      for (std::size_t r = 0; r < values.size(); r += 2) {
        if (std::find(patch_ids.begin(), patch_ids.end(), values[r]) == patch_ids.end()) {
          fail(b, "boundary entry " + std::to_string(r / 2 + 1) + " names patch " + std::to_string(values[r]) +
                      ", which is not among the <patches>");
        }
        if (values[r + 1] < 1 || values[r + 1] > 2 * dim) {
          fail(b, "boundary entry " + std::to_string(r / 2 + 1) + " names side " + std::to_string(values[r + 1]) +
                      ": expected a side from 1 to " + std::to_string(2 * dim));
        }
        boundary.push_back({values[r], values[r + 1]});
      }
    }
    entry["boundary"] = boundary;
    return entry;
  }

  const Locator& locator() const { return at_; }

 private:
  Locator at_;
};

struct GeometryKind {
  const char* type;
  int parameters;
  bool rational;
};

constexpr std::array<GeometryKind, 6> kKinds{{
    {"BSpline", 1, false},
    {"Nurbs", 1, true},
    {"TensorBSpline2", 2, false},
    {"TensorNurbs2", 2, true},
    {"TensorBSpline3", 3, false},
    {"TensorNurbs3", 3, true},
}};

Model read_document(std::string_view text) {
  pugi::xml_document document;
  const pugi::xml_parse_result parsed = document.load_buffer(text.data(), text.size(), pugi::parse_default, pugi::encoding_utf8);
  const Reader reader(text);
  if (!parsed) {
    throw InvalidInput(std::string("invalid XML: ") + parsed.description(),
                       reader.locator().line_and_column(static_cast<std::size_t>(std::max<std::ptrdiff_t>(parsed.offset, 0))));
  }
  if (const xml_node deep = detail::element_deeper_than_limit(document)) {
    throw InvalidInput("expected at most " + std::to_string(detail::kMaxXmlDepth) + " levels of nested elements, got more",
                       reader.locator().line_and_column(static_cast<std::size_t>(std::max<std::ptrdiff_t>(deep.offset_debug(), 0))));
  }
  const xml_node root = document.document_element();
  if (!root || std::string(root.name()) != "xml") {
    throw InvalidInput(std::string("expected the root element <xml> of a G+Smo file, got ") +
                           (root ? "<" + std::string(root.name()) + ">" : std::string("no element")),
                       root ? reader.locator().where(root) : std::string());
  }

  Model model;
  std::set<long long> ids;
  std::string kinds;
  for (const GeometryKind& kind : kKinds) kinds += (kinds.empty() ? "" : ", ") + std::string(kind.type);
  for (xml_node g = root.child("Geometry"); g; g = g.next_sibling("Geometry")) {
    const std::string type = reader.type_of(g);
    const auto kind = std::find_if(kKinds.begin(), kKinds.end(), [&](const GeometryKind& k) { return type == k.type; });
    if (kind == kKinds.end()) {
      reader.fail(g, "expected a geometry of type " + kinds + ", got type " + detail::quoted_token(type));
    }
    switch (kind->parameters) {
      case 1:
        model.objects.push_back(reader.geometry<1>(g, kind->rational));
        break;
      case 2:
        model.objects.push_back(reader.geometry<2>(g, kind->rational));
        break;
      default:
        model.objects.push_back(reader.geometry<3>(g, kind->rational));
        break;
    }
    if (!model.objects.back().metadata.is_null()) ids.insert(model.objects.back().metadata["gismo"]["id"].get<long long>());
  }
  if (model.objects.empty()) {
    reader.fail(root, "expected at least one <Geometry> (of type " + kinds + "), got none");
  }
  json multipatches = json::array();
  for (xml_node m = root.child("MultiPatch"); m; m = m.next_sibling("MultiPatch")) multipatches.push_back(reader.multipatch(m, ids));
  if (!multipatches.empty()) model.metadata = json{{"gismo", {{"multipatch", multipatches}}}};
  return model;
}

// ------------------------------------------------------------------------------------------
// Writing.

void set_text(xml_node node, const std::string& text) { node.append_child(pugi::node_pcdata).set_value(text.c_str()); }

std::string joined(const std::vector<double>& values) {
  std::string text;
  for (std::size_t i = 0; i < values.size(); ++i) {
    if (i) text += ' ';
    text += format_double(values[i]);
  }
  return text;
}

void put_knot_vector(xml_node parent, const KnotVector& kv, int index) {
  xml_node basis = parent.append_child("Basis");
  basis.append_attribute("type") = "BSplineBasis";
  if (index >= 0) basis.append_attribute("index") = index;
  xml_node node = basis.append_child("KnotVector");
  node.append_attribute("degree") = kv.degree();
  set_text(node, joined(kv.knots()));
}

template <int D>
void put_geometry(xml_node root, const TensorSpline<D>& spline, long long id, const std::string& path) {
  const bool rational = spline.is_rational();
  const std::string suffix = D == 1 ? "" : std::to_string(D);
  const std::string type = D == 1 ? (rational ? "Nurbs" : "BSpline") : (rational ? "TensorNurbs" : "TensorBSpline") + suffix;
  xml_node geometry = root.append_child("Geometry");
  geometry.append_attribute("type") = type.c_str();
  geometry.append_attribute("id") = id;

  xml_node basis = geometry.append_child("Basis");
  xml_node source = basis;
  if (rational) {
    basis.append_attribute("type") = (D == 1 ? std::string("NurbsBasis") : "TensorNurbsBasis" + suffix).c_str();
    source = basis.append_child("Basis");
  }
  if (D == 1) {
    source.append_attribute("type") = "BSplineBasis";
    xml_node node = source.append_child("KnotVector");
    node.append_attribute("degree") = spline.knot_vector(0).degree();
    set_text(node, joined(spline.knot_vector(0).knots()));
  } else {
    source.append_attribute("type") = ("TensorBSplineBasis" + suffix).c_str();
    for (int d = 0; d < D; ++d) put_knot_vector(source, spline.knot_vector(d), d);
  }

  const auto n = static_cast<std::size_t>(spline.num_control_points_total());
  const auto k = static_cast<std::size_t>(spline.dimension());
  if (rational) {
    for (std::size_t i = 0; i < n; ++i) {
      if (spline.weights()[i] != 0.0) continue;
      for (std::size_t c = 0; c < k; ++c) {
        if (spline.points()[i * k + c] != 0.0) {
          throw InvalidInput("control point " + std::to_string(i) +
                                 " is a point at infinity (weight 0, nonzero direction), which G+Smo cannot hold: "
                                 "its NURBS ignore weight-0 coefficients",
                             path);
        }
      }
    }
    xml_node w = basis.append_child("weights");
    set_text(w, joined(spline.weights()));
  }
  xml_node coefs = geometry.append_child("coefs");
  coefs.append_attribute("geoDim") = static_cast<unsigned>(k);
  std::string text = "\n";
  for (std::size_t i = 0; i < n; ++i) {
    for (std::size_t c = 0; c < k; ++c) {
      if (c) text += ' ';
      text += format_double(spline.points()[i * k + c]);
    }
    text += '\n';
  }
  set_text(coefs, text);
}

std::vector<long long> integer_list(const json& value, const std::string& path, const std::string& what) {
  if (!value.is_array()) throw InvalidInput("expected " + what, path);
  std::vector<long long> out;
  for (std::size_t i = 0; i < value.size(); ++i) {
    if (!value[i].is_number_integer()) throw InvalidInput("expected an integer", path + "[" + std::to_string(i) + "]");
    out.push_back(value[i].get<long long>());
  }
  return out;
}

std::string joined_integers(const std::vector<long long>& values) {
  std::string text;
  for (std::size_t i = 0; i < values.size(); ++i) {
    if (i) text += ' ';
    text += std::to_string(values[i]);
  }
  return text;
}

void put_multipatch(xml_node root, const json& entry, const std::string& path, const std::set<long long>& ids) {
  if (!entry.is_object()) throw InvalidInput("expected an object with parDim, patches, interfaces and boundary", path);
  xml_node node = root.append_child("MultiPatch");
  long long dim = 3;
  if (const auto it = entry.find("parDim"); it != entry.end()) {
    if (!it->is_number_integer() || it->get<long long>() < 1 || it->get<long long>() > 3) {
      throw InvalidInput("expected parDim 1, 2 or 3", path + ".parDim");
    }
    dim = it->get<long long>();
  }
  node.append_attribute("parDim") = dim;
  if (const auto it = entry.find("id"); it != entry.end()) {
    if (!it->is_number_integer()) throw InvalidInput("expected an integer id", path + ".id");
    node.append_attribute("id") = it->get<long long>();
  }
  const auto patches_it = entry.find("patches");
  if (patches_it == entry.end()) throw InvalidInput("missing key \"patches\" (the ids of the patch geometries)", path);
  const std::vector<long long> patches = integer_list(*patches_it, path + ".patches", "an array of patch ids");
  for (std::size_t i = 0; i < patches.size(); ++i) {
    if (!ids.contains(patches[i])) {
      throw InvalidInput("patch id " + std::to_string(patches[i]) + " is not the G+Smo id of any object",
                         path + ".patches[" + std::to_string(i) + "]");
    }
  }
  xml_node p = node.append_child("patches");
  p.append_attribute("type") = "id_index";
  set_text(p, joined_integers(patches));
  const std::size_t row = 4 + 2 * static_cast<std::size_t>(dim);
  for (const auto& [key, size] : {std::pair<const char*, std::size_t>{"interfaces", row}, {"boundary", 2}}) {
    const auto it = entry.find(key);
    if (it == entry.end()) continue;
    const std::string at = path + "." + key;
    if (!it->is_array()) throw InvalidInput("expected an array of rows of " + std::to_string(size) + " integers", at);
    std::string text = "\n";
    for (std::size_t r = 0; r < it->size(); ++r) {
      const std::string row_path = at + "[" + std::to_string(r) + "]";
      const std::vector<long long> values = integer_list((*it)[r], row_path, "a row of " + std::to_string(size) + " integers");
      if (values.size() != size) throw InvalidInput("expected a row of " + std::to_string(size) + " integers", row_path);
      text += joined_integers(values) + "\n";
    }
    set_text(node.append_child(key), text);
  }
}

}  // namespace

Model parse_gismo_xml(std::string_view text, const std::string& source_name) {
  try {
    Model model = read_document(text);
    check_coordinate_range(model);
    return model;
  } catch (const InvalidInput& e) {
    std::string where = source_name;
    if (!where.empty() && !e.where().empty()) where += ": ";
    throw InvalidInput(e.message(), where + e.where());
  }
}

Model read_gismo_xml(const std::filesystem::path& path) { return parse_gismo_xml(read_file(path), path.string()); }

std::string gismo_xml_text(const Model& model) {
  if (model.objects.empty()) throw InvalidInput("expected at least one object, got none", "objects");
  pugi::xml_document document;
  xml_node declaration = document.append_child(pugi::node_declaration);
  declaration.append_attribute("version") = "1.0";
  declaration.append_attribute("encoding") = "UTF-8";
  document.append_child(pugi::node_comment).set_value(" written by volspline: G+Smo geometries, coefficients one per row, u fastest ");
  xml_node root = document.append_child("xml");
  std::set<long long> ids;
  for (std::size_t i = 0; i < model.objects.size(); ++i) {
    const ModelObject& object = model.objects[i];
    const std::string path = "objects[" + std::to_string(i) + "]";
    auto id = static_cast<long long>(i);
    if (object.metadata.is_object()) {
      const auto g = object.metadata.find("gismo");
      if (g != object.metadata.end() && g->is_object() && g->contains("id")) {
        if (!(*g)["id"].is_number_integer()) throw InvalidInput("expected an integer G+Smo id", path + ".metadata.gismo.id");
        id = (*g)["id"].get<long long>();
      }
    }
    ids.insert(id);
    visit_classic_spline(object, "G+Smo XML", path, [&](const auto& spline) { put_geometry(root, spline, id, path); });
  }
  if (model.metadata.is_object()) {
    const auto g = model.metadata.find("gismo");
    if (g != model.metadata.end() && g->is_object() && g->contains("multipatch")) {
      const json& list = (*g)["multipatch"];
      if (!list.is_array()) throw InvalidInput("expected an array of multipatch descriptions", "metadata.gismo.multipatch");
      for (std::size_t m = 0; m < list.size(); ++m) {
        put_multipatch(root, list[m], "metadata.gismo.multipatch[" + std::to_string(m) + "]", ids);
      }
    }
  }
  std::ostringstream out;
  document.save(out, "  ", pugi::format_indent, pugi::encoding_utf8);
  return out.str();
}

void write_gismo_xml(const Model& model, const std::filesystem::path& path) {
  write_file_atomically(path, gismo_xml_text(model));
}

}  // namespace volspline
