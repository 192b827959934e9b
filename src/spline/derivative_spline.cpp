#include "volspline/spline/derivative_spline.h"

#include <string>

#include "directional.h"
#include "volspline/core/error.h"

namespace volspline {

template <int D>
TensorSpline<D> derivative_spline(const TensorSpline<D>& spline, int direction) {
  if (direction < 0 || direction >= D) throw InvalidInput("direction " + std::to_string(direction) + " does not exist");
  if (spline.is_rational())
    throw InvalidInput("the derivative of a rational spline is not a spline of one degree less; evaluate derivatives instead");
  const KnotVector& kv = spline.knot_vector(direction);
  const int p = kv.degree();
  if (p < 2) throw InvalidInput("the derivative of a degree-1 direction is piecewise constant (degree 0), which volspline does not represent");
  const std::vector<double>& U = kv.knots();
  // A basis function of degree p-1 whose knots t_{i+1}..t_{i+p} all coincide is identically
  // zero (next to a knot of multiplicity p+1): drop it together with one copy of that knot.
  std::vector<double> knots;
  std::vector<int> kept;
  const int n = kv.num_basis();
  std::vector<bool> drop_knot(U.size(), false);
  for (int i = 0; i + 1 < n; ++i) {
    if (U[static_cast<std::size_t>(i + p + 1)] == U[static_cast<std::size_t>(i + 1)])
      drop_knot[static_cast<std::size_t>(i + 1)] = true;
    else
      kept.push_back(i);
  }
  for (std::size_t j = 1; j + 1 < U.size(); ++j)
    if (!drop_knot[j]) knots.push_back(U[j]);
  KnotVector derived(p - 1, std::move(knots));
  return detail::transform_lines(spline, direction, derived, [&](const double* in, double* out, std::size_t B) {
    for (std::size_t q = 0; q < kept.size(); ++q) {
      const int i = kept[q];
      const double f = p / (U[static_cast<std::size_t>(i + p + 1)] - U[static_cast<std::size_t>(i + 1)]);
      const double* a = in + static_cast<std::size_t>(i + 1) * B;
      const double* b = in + static_cast<std::size_t>(i) * B;
      double* o = out + q * B;
      for (std::size_t x = 0; x < B; ++x) o[x] = f * (a[x] - b[x]);
    }
  });
}

template TensorSpline<1> derivative_spline(const TensorSpline<1>&, int);
template TensorSpline<2> derivative_spline(const TensorSpline<2>&, int);
template TensorSpline<3> derivative_spline(const TensorSpline<3>&, int);
template TensorSpline<4> derivative_spline(const TensorSpline<4>&, int);

}  // namespace volspline
