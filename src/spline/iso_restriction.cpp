#include "volspline/spline/iso_restriction.h"

#include <string>
#include <utility>

#include "directional.h"
#include "volspline/core/error.h"
#include "volspline/core/format.h"

namespace volspline {

namespace {

template <int D, std::size_t... I>
std::array<KnotVector, D - 1> drop_direction(const std::array<KnotVector, D>& k, int direction, std::index_sequence<I...>) {
  return {k[static_cast<int>(I) < direction ? I : I + 1]...};
}

}  // namespace

template <int D>
TensorSpline<D - 1> restrict_to_iso(const TensorSpline<D>& spline, int direction, double value) {
  if (direction < 0 || direction >= D) throw InvalidInput("direction " + std::to_string(direction) + " does not exist");
  const KnotVector& kv = spline.knot_vector(direction);
  if (!kv.contains(value)) {
    throw InvalidInput("iso-parameter " + format_double(value) + " is outside the domain [" + format_double(kv.domain_min()) +
                       ", " + format_double(kv.domain_max()) + "]");
  }
  const int p = kv.degree();
  const int span = kv.find_span(value);
  std::vector<double> N(static_cast<std::size_t>(p + 1));
  kv.basis(span, value, N.data());
  const detail::LineLayout l = detail::line_layout(spline, direction);
  std::vector<double> coefficients(l.block * l.lines, 0.0);
  const double* in = spline.homogeneous().data();
  for (std::size_t line = 0; line < l.lines; ++line) {
    double* out = coefficients.data() + line * l.block;
    for (int j = 0; j <= p; ++j) {
      const double* row = in + (line * static_cast<std::size_t>(l.count) + static_cast<std::size_t>(span - p + j)) * l.block;
      for (std::size_t x = 0; x < l.block; ++x) out[x] += N[static_cast<std::size_t>(j)] * row[x];
    }
  }
  auto knots = drop_direction<D>(spline.knot_vectors(), direction, std::make_index_sequence<D - 1>{});
  return TensorSpline<D - 1>::from_homogeneous(std::move(knots), spline.dimension(), spline.is_rational(),
                                               std::move(coefficients));
}

template TensorSpline<1> restrict_to_iso(const TensorSpline<2>&, int, double);
template TensorSpline<2> restrict_to_iso(const TensorSpline<3>&, int, double);
template TensorSpline<3> restrict_to_iso(const TensorSpline<4>&, int, double);

}  // namespace volspline
