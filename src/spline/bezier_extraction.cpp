#include "volspline/spline/bezier_extraction.h"

#include <algorithm>
#include <string>

#include "directional.h"
#include "volspline/core/error.h"
#include "volspline/core/format.h"
#include "volspline/spline/knot_insertion.h"

namespace volspline {

namespace {

// Raises every interior breakpoint of `direction` to multiplicity degree + 1, so that the
// control points split into independent groups of degree + 1 per cell.
template <int D>
TensorSpline<D> separate_cells(const TensorSpline<D>& s, int direction) {
  TensorSpline<D> current = s;
  const KnotVector& kv = s.knot_vector(direction);
  const auto breaks = kv.breakpoints();
  for (std::size_t i = 1; i + 1 < breaks.size(); ++i) {
    const int missing = kv.degree() + 1 - kv.multiplicity(breaks[i]);
    current = insert_knot(current, direction, breaks[i], missing);
  }
  return current;
}

}  // namespace

template <int D>
std::vector<TensorSpline<D>> bezier_pieces(const TensorSpline<D>& spline) {
  TensorSpline<D> separated = clamp(spline);
  for (int d = 0; d < D; ++d) separated = separate_cells(separated, d);
  std::vector<TensorSpline<D>> pieces{separated};
  // Cut one direction at a time; the running list stays in cell order, first direction fastest,
  // because later directions multiply the list from the outside.
  for (int d = 0; d < D; ++d) {
    std::vector<TensorSpline<D>> next;
    const auto breaks = separated.knot_vector(d).breakpoints();
    const int p = separated.knot_vector(d).degree();
    for (std::size_t cell = 0; cell + 1 < breaks.size(); ++cell) {
      for (const auto& piece : pieces) {
        next.push_back(detail::slice_rows(piece, d, static_cast<int>(cell) * (p + 1),
                                          KnotVector::bezier(p, breaks[cell], breaks[cell + 1])));
      }
    }
    // next is ordered [cell_d][previous]; previous varies fastest, as required.
    pieces = std::move(next);
  }
  return pieces;
}

template <int D>
std::pair<TensorSpline<D>, TensorSpline<D>> split(const TensorSpline<D>& spline, int direction, double t) {
  if (direction < 0 || direction >= D) throw InvalidInput("direction " + std::to_string(direction) + " does not exist");
  const KnotVector& kv0 = spline.knot_vector(direction);
  if (!(t > kv0.domain_min() && t < kv0.domain_max())) {
    throw InvalidInput("cannot split at " + format_double(t) + ": expected a parameter strictly inside (" +
                       format_double(kv0.domain_min()) + ", " + format_double(kv0.domain_max()) + ")");
  }
  TensorSpline<D> s = clamp(spline);
  const int p = kv0.degree();
  s = insert_knot(s, direction, t, p + 1 - s.knot_vector(direction).multiplicity(t));
  const std::vector<double>& U = s.knot_vector(direction).knots();
  const int j = static_cast<int>(std::lower_bound(U.begin(), U.end(), t) - U.begin());  // first copy of t
  KnotVector left(p, std::vector<double>(U.begin(), U.begin() + j + p + 1));
  KnotVector right(p, std::vector<double>(U.begin() + j, U.end()));
  return {detail::slice_rows(s, direction, 0, left), detail::slice_rows(s, direction, j, right)};
}

#define VOLSPLINE_INSTANTIATE(D)                                                     \
  template std::vector<TensorSpline<D>> bezier_pieces(const TensorSpline<D>&);       \
  template std::pair<TensorSpline<D>, TensorSpline<D>> split(const TensorSpline<D>&, int, double);
VOLSPLINE_INSTANTIATE(1)
VOLSPLINE_INSTANTIATE(2)
VOLSPLINE_INSTANTIATE(3)
VOLSPLINE_INSTANTIATE(4)
#undef VOLSPLINE_INSTANTIATE

}  // namespace volspline
