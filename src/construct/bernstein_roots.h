#pragma once
// Real roots of a univariate polynomial in Bernstein form on [0, 1], by subdivision: the number
// of roots in an interval is at most the number of sign changes of the Bernstein coefficients
// there (Descartes' rule in Bernstein form; Lane–Riesenfeld 1981), so a span without a change has
// none and a span with one change between end values of opposite sign has exactly one, which
// Brent's method refines. Used for the critical points of a curve's distance and the minimum of
// a polynomial falloff (construct/skeleton_field.h).
#include <vector>

#include "volspline/core/bernstein_tensor.h"

namespace volspline {

/// The roots of the scalar f in [0, 1], ascending, each to a few units of rounding in s.
/// Coefficients with |c| <= noise count as zero (rounding of their computation): a span on
/// which they all do is flat and reports its midpoint; a span still undecided after 40 halvings
/// (a multiple root, or a cluster) reports its midpoint too. Roots exactly at 0 or 1 may be
/// missed or reported; callers examine the ends themselves.
std::vector<double> bernstein_roots(const BernsteinTensor<1>& f, double noise);

}  // namespace volspline
