#include "volspline/spline/knot_insertion.h"

#include <algorithm>
#include <string>

#include "directional.h"
#include "volspline/core/error.h"
#include "volspline/core/format.h"

namespace volspline {

namespace {

void check_direction(int direction, int D) {
  if (direction < 0 || direction >= D)
    throw InvalidInput("direction " + std::to_string(direction) + " does not exist; expected 0.." + std::to_string(D - 1));
}

}  // namespace

template <int D>
TensorSpline<D> insert_knot(const TensorSpline<D>& spline, int direction, double t, int times) {
  check_direction(direction, D);
  const KnotVector& kv = spline.knot_vector(direction);
  if (!kv.contains(t)) {
    throw InvalidInput("cannot insert knot " + format_double(t) + ": outside the domain [" + format_double(kv.domain_min()) +
                       ", " + format_double(kv.domain_max()) + "]");
  }
  if (times < 0) throw InvalidInput("cannot insert a knot a negative number of times");
  if (kv.multiplicity(t) + times > kv.degree() + 1) {
    throw InvalidInput("cannot insert knot " + format_double(t) + " " + std::to_string(times) +
                       " time(s): its multiplicity would exceed degree + 1 = " + std::to_string(kv.degree() + 1));
  }
  TensorSpline<D> current = spline;
  for (int r = 0; r < times; ++r) {
    const KnotVector& old = current.knot_vector(direction);
    const int p = old.degree();
    const int k = old.find_span(t);
    const std::vector<double>& U = old.knots();
    std::vector<double> knots = U;
    knots.insert(knots.begin() + k + 1, t);
    KnotVector refined(p, std::move(knots));
    const int n = old.num_basis();
    // Boehm: Q_i = P_i (i <= k-p), a_i P_i + (1-a_i) P_{i-1} (k-p < i <= k), P_{i-1} (i > k).
    current = detail::transform_lines(current, direction, refined, [&](const double* in, double* out, std::size_t B) {
      for (int i = 0; i <= k - p; ++i) std::copy(in + i * B, in + (i + 1) * B, out + i * B);
      for (int i = k - p + 1; i <= k; ++i) {
        const double a = (t - U[static_cast<std::size_t>(i)]) / (U[static_cast<std::size_t>(i + p)] - U[static_cast<std::size_t>(i)]);
        detail::axpby(a, in + i * B, 1.0 - a, in + (i - 1) * B, out + i * B, B);
      }
      for (int i = k + 1; i <= n; ++i) std::copy(in + (i - 1) * B, in + i * B, out + i * B);
    });
  }
  return current;
}

template <int D>
TensorSpline<D> refine_knots(const TensorSpline<D>& spline, int direction, const std::vector<double>& knots) {
  TensorSpline<D> current = spline;
  for (double t : knots) current = insert_knot(current, direction, t, 1);
  return current;
}

template <int D>
TensorSpline<D> clamp(const TensorSpline<D>& spline) {
  TensorSpline<D> current = spline;
  for (int d = 0; d < D; ++d) {
    const KnotVector& kv = current.knot_vector(d);
    if (kv.is_clamped()) continue;
    const int p = kv.degree();
    const double a = kv.domain_min(), b = kv.domain_max();
    current = insert_knot(current, d, a, p + 1 - kv.multiplicity(a));
    current = insert_knot(current, d, b, p + 1 - current.knot_vector(d).multiplicity(b));
    const std::vector<double>& U = current.knot_vector(d).knots();
    const auto lo = std::lower_bound(U.begin(), U.end(), a) - U.begin();  // knots before the first a
    const auto hi = std::upper_bound(U.begin(), U.end(), b) - U.begin();  // one past the last b
    KnotVector clamped(p, std::vector<double>(U.begin() + lo, U.begin() + hi));
    current = detail::slice_rows(current, d, static_cast<int>(lo), clamped);
  }
  return current;
}

#define VOLSPLINE_INSTANTIATE(D)                                                                 \
  template TensorSpline<D> insert_knot(const TensorSpline<D>&, int, double, int);                \
  template TensorSpline<D> refine_knots(const TensorSpline<D>&, int, const std::vector<double>&); \
  template TensorSpline<D> clamp(const TensorSpline<D>&);
VOLSPLINE_INSTANTIATE(1)
VOLSPLINE_INSTANTIATE(2)
VOLSPLINE_INSTANTIATE(3)
VOLSPLINE_INSTANTIATE(4)
#undef VOLSPLINE_INSTANTIATE

}  // namespace volspline
