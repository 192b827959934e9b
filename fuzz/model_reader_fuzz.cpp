// libFuzzer target for the model reader: any bytes either parse or throw a volspline::Error.
// Anything else (a crash, another exception, a sanitizer report, a hang, unbounded memory) is a
// bug. A model that parses is written, parsed again and written again: the numbers must come
// back bit for bit and the two texts must be equal.
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <string>
#include <string_view>
#include <variant>
#include <vector>

#include "volspline/core/error.h"
#include "volspline/io/model_file.h"

namespace {

using volspline::Model;
using volspline::ModelObject;
using volspline::TensorSpline;

[[noreturn]] void mismatch(const char* what) {
  std::fprintf(stderr, "model_reader_fuzz: round trip changed %s\n", what);
  std::abort();
}

void check_same(const std::vector<double>& a, const std::vector<double>& b, const char* what) {
  if (a.size() != b.size()) mismatch(what);
  if (!a.empty() && std::memcmp(a.data(), b.data(), a.size() * sizeof(double)) != 0) mismatch(what);
}

template <int D>
void check_same(const TensorSpline<D>& a, const TensorSpline<D>& b) {
  if (a.dimension() != b.dimension()) mismatch("the dimension");
  for (int d = 0; d < D; ++d) {
    if (a.knot_vector(d).degree() != b.knot_vector(d).degree()) mismatch("a degree");
    check_same(a.knot_vector(d).knots(), b.knot_vector(d).knots(), "a knot");
  }
  check_same(a.points(), b.points(), "a control point");
  check_same(a.weights(), b.weights(), "a weight");
}

void check_same(const volspline::SweptSolid& a, const volspline::SweptSolid& b) {
  if (a.generator.size() != b.generator.size()) mismatch("the generator");
  for (std::size_t i = 0; i < a.generator.size(); ++i) check_same(a.generator[i], b.generator[i]);
  check_same(a.path, b.path);
  for (std::size_t k = 0; k < 3; ++k) check_same(a.frame[k], b.frame[k]);
  if (a.frame_name != b.frame_name) mismatch("a frame name");
  check_same(std::vector<double>{a.frame_fit_error}, std::vector<double>{b.frame_fit_error}, "a frame fit error");
}

void check_same(const volspline::DmsSplineVolume& a, const volspline::DmsSplineVolume& b) {
  if (a.degree() != b.degree() || a.sharing() != b.sharing()) mismatch("a simplex spline's degree or sharing");
  if (a.domain().tetrahedra != b.domain().tetrahedra) mismatch("a tetrahedron");
  if (a.attribute_names() != b.attribute_names()) mismatch("an attribute name");
  std::vector<double> ka, kb;
  for (const auto& k : a.knots().knots) ka.insert(ka.end(), {k.x(), k.y(), k.z()});
  for (const auto& k : b.knots().knots) kb.insert(kb.end(), {k.x(), k.y(), k.z()});
  check_same(ka, kb, "a knot of a cloud");
  const Eigen::MatrixXd& ca = a.control_vectors();
  const Eigen::MatrixXd& cb = b.control_vectors();
  check_same(std::vector<double>(ca.data(), ca.data() + ca.size()), std::vector<double>(cb.data(), cb.data() + cb.size()),
             "a control vector");
}

void check_same(const Model& a, const Model& b) {
  if (a.objects.size() != b.objects.size()) mismatch("the number of objects");
  if (a.metadata != b.metadata) mismatch("the metadata");
  for (std::size_t i = 0; i < a.objects.size(); ++i) {
    const ModelObject& x = a.objects[i];
    const ModelObject& y = b.objects[i];
    if (x.name != y.name) mismatch("a name");
    if (x.bezier != y.bezier) mismatch("a type");
    if (x.metadata != y.metadata) mismatch("object metadata");
    if (x.spline.index() != y.spline.index()) mismatch("a type");
    std::visit(
        [&](const auto& s) {
          using S = std::decay_t<decltype(s)>;
          check_same(s, std::get<S>(y.spline));
        },
        x.spline);
  }
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string_view text(reinterpret_cast<const char*>(data), size);
  Model model;
  try {
    model = volspline::parse_model(text, "fuzz.json");
  } catch (const volspline::Error&) {
    return 0;  // rejected: fine, as long as it is a volspline::Error
  }
  const std::string written = volspline::model_to_json(model);
  Model again;
  try {
    again = volspline::parse_model(written, "written.json");
  } catch (const volspline::Error& e) {
    std::fprintf(stderr, "model_reader_fuzz: written model does not parse: %s\n%s\n", e.what(), written.c_str());
    std::abort();
  }
  check_same(model, again);
  if (volspline::model_to_json(again) != written) mismatch("the written text");
  return 0;
}
