#include "volspline/spline/reparameterization.h"

#include <cmath>
#include <string>

#include "volspline/core/error.h"
#include "volspline/core/format.h"

namespace volspline {

template <int D>
TensorSpline<D> reparameterize(const TensorSpline<D>& spline, int direction, double a, double b) {
  if (direction < 0 || direction >= D) throw InvalidInput("direction " + std::to_string(direction) + " does not exist");
  if (!(std::isfinite(a) && std::isfinite(b) && a < b))
    throw InvalidInput("expected a finite interval a < b, got [" + format_double(a) + ", " + format_double(b) + "]");
  const KnotVector& kv = spline.knot_vector(direction);
  const double a0 = kv.domain_min(), b0 = kv.domain_max();
  std::vector<double> knots;
  for (double t : kv.knots()) {
    // The domain ends map exactly onto a and b; other knots affinely.
    knots.push_back(t == a0 ? a : t == b0 ? b : a + (t - a0) * ((b - a) / (b0 - a0)));
  }
  auto all = spline.knot_vectors();
  all[static_cast<std::size_t>(direction)] = KnotVector(kv.degree(), std::move(knots));
  return TensorSpline<D>::from_homogeneous(std::move(all), spline.dimension(), spline.is_rational(), spline.homogeneous());
}

template <int D>
TensorSpline<D> reparameterize_to_unit_box(const TensorSpline<D>& spline) {
  TensorSpline<D> s = spline;
  for (int d = 0; d < D; ++d) s = reparameterize(s, d, 0.0, 1.0);
  return s;
}

#define VOLSPLINE_INSTANTIATE(D)                                                     \
  template TensorSpline<D> reparameterize(const TensorSpline<D>&, int, double, double); \
  template TensorSpline<D> reparameterize_to_unit_box(const TensorSpline<D>&);
VOLSPLINE_INSTANTIATE(1)
VOLSPLINE_INSTANTIATE(2)
VOLSPLINE_INSTANTIATE(3)
VOLSPLINE_INSTANTIATE(4)
#undef VOLSPLINE_INSTANTIATE

}  // namespace volspline
