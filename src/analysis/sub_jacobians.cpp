#include "volspline/analysis/sub_jacobians.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numeric>
#include <cstddef>
#include <string>
#include <utility>
#include <vector>

#include <Eigen/Dense>

#include "volspline/analysis/cone_bounds.h"
#include "volspline/analysis/jacobian_determinant.h"
#include "volspline/core/error.h"

namespace volspline {

namespace {

using Scaled = ScaledBernsteinTensor<4>;
// Rows of the sub-Jacobians: the point (homogeneous only) and the four first partials.
using Row = std::array<Scaled, 4>;

// The cell's homogeneous coefficients differentiated along `direction` (-1: not differentiated)
// with respect to the global parameter, the components `columns` in that order, scaled.
Row scaled_row(const BSplineHypervolume& cell, const BernsteinTensor<4>& h, int direction, const std::array<int, 4>& columns,
               int count) {
  const BernsteinTensor<4> f =
      direction < 0 ? h : bernstein_derivative(h, direction, cell.domain_max(direction) - cell.domain_min(direction));
  Row row;
  for (std::size_t c = 0; c < static_cast<std::size_t>(count); ++c) row[c] = bernstein_scaled(bernstein_components(f, columns[c]));
  return row;
}

Scaled zero_product(const Scaled& a, const Scaled& b) { return Scaled(product_degrees(a.degrees, b.degrees)); }

// The 2 x 2 minors of rows b and c over the column pairs (i, j), i < j < n.
std::array<std::array<Scaled, 4>, 4> minors2(const Row& b, const Row& c, int n) {
  std::array<std::array<Scaled, 4>, 4> m;
  for (std::size_t i = 0; i < static_cast<std::size_t>(n); ++i) {
    for (std::size_t j = i + 1; j < static_cast<std::size_t>(n); ++j) {
      m[i][j] = zero_product(b[0], c[0]);
      scaled_product_add(b[i], c[j], 1.0, m[i][j]);
      scaled_product_add(b[j], c[i], -1.0, m[i][j]);
    }
  }
  return m;
}

// det[a; b; c] over the columns `cols` (three of them), from the 2 x 2 minors of (b, c).
Scaled det3(const Row& a, const std::array<std::array<Scaled, 4>, 4>& m, const std::array<std::size_t, 3>& cols) {
  Scaled d = zero_product(a[cols[0]], m[cols[1]][cols[2]]);
  scaled_product_add(a[cols[0]], m[cols[1]][cols[2]], 1.0, d);
  scaled_product_add(a[cols[1]], m[cols[0]][cols[2]], -1.0, d);
  scaled_product_add(a[cols[2]], m[cols[0]][cols[1]], 1.0, d);
  return d;
}

// det[p; a; b; c] (4 columns), expanded along p: sum_j (-1)^j p_j det[a; b; c without column j].
Scaled det4(const Row& p, const Row& a, const std::array<std::array<Scaled, 4>, 4>& m) {
  Scaled d;
  for (std::size_t j = 0; j < 4; ++j) {
    std::array<std::size_t, 3> cols{};
    std::size_t k = 0;
    for (std::size_t c = 0; c < 4; ++c) {
      if (c != j) cols[k++] = c;
    }
    const Scaled minor = det3(a, m, cols);
    if (j == 0) d = zero_product(p[0], minor);
    scaled_product_add(p[j], minor, (j % 2 == 0) ? 1.0 : -1.0, d);
  }
  return d;
}

// Wolfe's minimum-norm-point algorithm (Wolfe 1976) on the unit vectors u_i = c_i / |c_i|: the
// point of their convex hull nearest the origin is, when it is not the origin, the direction
// that separates them best (x . u_i >= |x|^2 for all i). Each major step adds the vector most
// opposed to the current point; the minor steps keep the point in the relative interior of the
// hull of the active set (at most five vectors in R^4). Every candidate x is tested on the
// unnormalised coefficients (x . c_i > slack_of(x) for every i; `accept(x)`, the same test, for
// the last one) and the search stops as soon as one proves; it gives up
// when the point reaches the origin (the hull contains it: no certificate exists) or after a
// fixed number of steps. Rounding can only cost a certificate, never make a wrong one: whatever
// direction is returned, the caller's test decides.
template <class Slack, class Accept>
bool minimum_norm_separation(const double* c, const std::vector<double>& inverse_norm, Slack slack_of, Accept accept) {
  const std::size_t n = inverse_norm.size();
  using Vec4 = Eigen::Vector4d;
  auto unit = [&](std::size_t i) { return Vec4(Eigen::Map<const Vec4>(c + 4 * i) * inverse_norm[i]); };
  std::vector<std::size_t> active{0};
  std::vector<double> weight{1.0};
  Vec4 x = unit(0);
  constexpr int kMajorSteps = 48;
  constexpr double kOrigin = 1e-9;
  for (int major = 0; major < kMajorSteps; ++major) {
    // One pass over the coefficients for both the caller's test of x (every x . c_i above
    // slack(x)) and the vector most opposed to x: the tensors are large (Fig. 7's 300 KB), and
    // the two passes were a fifth of the subdivision's time.
    const double slack = slack_of(x);
    bool proves = true;
    std::size_t worst = 0;
    double lowest = std::numeric_limits<double>::infinity();
    for (std::size_t i = 0; i < n; ++i) {
      const double raw = x.dot(Eigen::Map<const Vec4>(c + 4 * i));
      proves = proves && raw > slack;
      const double dot = raw * inverse_norm[i];
      if (dot < lowest) {
        lowest = dot;
        worst = i;
      }
    }
    if (proves) return true;
    if (x.squaredNorm() < kOrigin * kOrigin) return false;
    // x is the minimum-norm point of the whole hull: the hull misses the origin only by less
    // than the rounding, or accept() refused x for its margins.
    if (lowest >= x.squaredNorm() * (1 - 1e-12)) return false;
    if (std::find(active.begin(), active.end(), worst) != active.end()) return false;
    // Five affinely independent vectors span R^4's affine hull; more means rounding kept a
    // dependent one: give up rather than grow the system.
    if (active.size() >= 5) return false;
    active.push_back(worst);
    weight.push_back(0.0);
    for (int minor = 0; minor < 8; ++minor) {
      // The affine hull's minimum-norm point: min |U a|^2 with sum a = 1 (a KKT system).
      const Eigen::Index m = static_cast<Eigen::Index>(active.size());
      // At most five active vectors in R^4 (and one more just added): fixed-capacity storage, no
      // allocation in this hot loop.
      using Active = Eigen::Matrix<double, 4, Eigen::Dynamic, 0, 4, 6>;
      using System = Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, 0, 7, 7>;
      using Column = Eigen::Matrix<double, Eigen::Dynamic, 1, 0, 7, 1>;
      Active u(4, m);
      for (Eigen::Index k = 0; k < m; ++k) u.col(k) = unit(active[static_cast<std::size_t>(k)]);
      System kkt = System::Zero(m + 1, m + 1);
      kkt.topLeftCorner(m, m) = u.transpose() * u;
      kkt.block(0, m, m, 1).setOnes();
      kkt.block(m, 0, 1, m).setOnes();
      Column rhs = Column::Zero(m + 1);
      rhs(m) = 1;
      const Column solution = kkt.completeOrthogonalDecomposition().solve(rhs);
      const Column a = solution.head(m);
      if (!a.allFinite()) return false;
      if ((a.array() > 1e-14).all()) {
        x = u * a;
        for (Eigen::Index k = 0; k < m; ++k) weight[static_cast<std::size_t>(k)] = a(k);
        break;
      }
      // Step from the current weights towards a as far as the weights stay non-negative, and drop
      // the vectors whose weight reaches zero.
      double theta = 1;
      for (Eigen::Index k = 0; k < m; ++k) {
        const double w = weight[static_cast<std::size_t>(k)];
        if (a(k) <= 1e-14 && w - a(k) > 0) theta = std::min(theta, w / (w - a(k)));
      }
      std::vector<std::size_t> kept_active;
      std::vector<double> kept_weight;
      x.setZero();
      for (Eigen::Index k = 0; k < m; ++k) {
        const double w = theta * a(k) + (1 - theta) * weight[static_cast<std::size_t>(k)];
        if (w > 1e-14) {
          kept_active.push_back(active[static_cast<std::size_t>(k)]);
          kept_weight.push_back(w);
          x += w * u.col(k);
        }
      }
      if (kept_active.empty()) return false;
      active = std::move(kept_active);
      weight = std::move(kept_weight);
      const double total = std::accumulate(weight.begin(), weight.end(), 0.0);
      for (double& w : weight) w /= total;
      x /= total;
    }
  }
  return accept(x);
}

}  // namespace

SubJacobiansBernstein sub_jacobian_coefficients(const BSplineHypervolume& cell) {
  if (cell.dimension() != 3) {
    throw InvalidInput("the sub-Jacobians need control points in R^3, got dimension " + std::to_string(cell.dimension()));
  }
  for (int d = 0; d < 4; ++d) {
    if (!cell.knot_vector(d).is_bezier()) {
      throw InvalidInput("sub_jacobian_coefficients needs a single Bézier cell; direction " + std::to_string(d) +
                         " has interior knots (split it with bezier_pieces first)");
    }
  }
  BernsteinTensor<4> h;
  h.degrees = cell.degrees();
  h.components = cell.coefficient_size();
  h.coefficients = cell.translated_to_local_origin().homogeneous();  // J is translation invariant

  const bool rational = cell.is_rational();
  // Homogeneous storage is (wx, wy, wz, w); the determinant identity wants w first.
  const std::array<int, 4> columns = rational ? std::array<int, 4>{3, 0, 1, 2} : std::array<int, 4>{0, 1, 2, 0};
  const int n = rational ? 4 : 3;
  const Row du = scaled_row(cell, h, 0, columns, n), dv = scaled_row(cell, h, 1, columns, n),
            dw = scaled_row(cell, h, 2, columns, n), dt = scaled_row(cell, h, 3, columns, n);
  // J123 = u . (v x w), J124 = u . (v x t), J134 = u . (w x t), J234 = v . (w x t): three
  // cross products (2 x 2 minors) serve the four.
  const auto m_vw = minors2(dv, dw, n), m_vt = minors2(dv, dt, n), m_wt = minors2(dw, dt, n);
  std::array<Scaled, 4> scaled;
  if (!rational) {
    const std::array<std::size_t, 3> xyz{0, 1, 2};
    scaled = {det3(du, m_vw, xyz), det3(du, m_vt, xyz), det3(du, m_wt, xyz), det3(dv, m_wt, xyz)};
  } else {
    const Row p = scaled_row(cell, h, -1, columns, 4);
    scaled = {det4(p, du, m_vw), det4(p, du, m_vt), det4(p, du, m_wt), det4(p, dv, m_wt)};
  }
  std::array<int, 4> common{0, 0, 0, 0};
  for (const auto& s : scaled) {
    for (std::size_t d = 0; d < 4; ++d) common[d] = std::max(common[d], s.degrees[d]);
  }
  SubJacobiansBernstein result;
  result.homogeneous = rational;
  result.minors = BernsteinTensor<4>(common, 4);
  for (std::size_t k = 0; k < 4; ++k) {
    const BernsteinTensor<4> elevated = bernstein_elevate(bernstein_unscaled(std::move(scaled[k])), common);
    for (std::size_t i = 0; i < elevated.count(); ++i) result.minors.coefficients[4 * i + k] = elevated.coefficients[i];
  }
  return result;
}

std::array<double, 4> sub_jacobians_at(const BSplineHypervolume& map, const std::array<double, 4>& t) {
  if (map.dimension() != 3) {
    throw InvalidInput("the sub-Jacobians need a map into R^3, got dimension " + std::to_string(map.dimension()));
  }
  const std::vector<double> d = map.evaluate_derivatives(t, 1);
  // Rows 1..4 are s_u, s_v, s_w, s_t (derivative_multi_indices order).
  const auto row = [&](int a) { return Eigen::Vector3d(Eigen::Map<const Eigen::Vector3d>(d.data() + 3 * a)); };
  const Eigen::Vector3d su = row(1), sv = row(2), sw = row(3), st = row(4);
  return {jacobian_determinant(su, sv, sw), jacobian_determinant(su, sv, st), jacobian_determinant(su, sw, st),
          jacobian_determinant(sv, sw, st)};
}

}  // namespace volspline

namespace volspline {


RankCertificate bernstein_rank_certificate(const BernsteinTensor<4>& minors, const std::array<double, 4>& margins) {
  const std::size_t n = minors.count();
  const double* c = minors.coefficients.data();
  for (std::size_t k = 0; k < 4; ++k) {
    bool positive = true, negative = true;
    for (std::size_t i = 0; i < n && (positive || negative); ++i) {
      const double x = c[4 * i + k];
      positive = positive && x > margins[k];
      negative = negative && x < -margins[k];
    }
    if (positive || negative) return RankCertificate::Sign;
  }
  {
    bool weakly_positive = true, weakly_negative = true;
    for (std::size_t i = 0; i < n && (weakly_positive || weakly_negative); ++i) {
      const double x = c[4 * i];
      weakly_positive = weakly_positive && x >= -margins[0];
      weakly_negative = weakly_negative && x <= margins[0];
    }
    if (weakly_positive || weakly_negative) return RankCertificate::NoFold;
  }
  const auto slack_of = [&](const Eigen::Vector4d& x) {
    double slack = 0;
    for (std::size_t k = 0; k < 4; ++k) slack += std::abs(x[static_cast<Eigen::Index>(k)]) * margins[k];
    return slack;
  };
  // Inverse lengths of the 4-vectors. A vector zero to the margins (|c_ik| <= margin_k for every
  // k) cannot be separated from the origin: x . c_i <= sum |x_k| margin_k for every direction x,
  // which is exactly what a proof must exceed, so there is no certificate and no search is
  // needed. Such a vector is the value of the minors at a point of the cell where they all
  // vanish (a corner on the set): on Fig. 7 this was 21,760 of the 21,824 tests that found no
  // certificate, each of which had run the whole search below in vain.
  std::vector<double> inverse_norm(n);
  std::array<double, 4> d{0, 0, 0, 0};
  for (std::size_t i = 0; i < n; ++i) {
    const double* e = c + 4 * i;
    if (std::abs(e[0]) <= margins[0] && std::abs(e[1]) <= margins[1] && std::abs(e[2]) <= margins[2] && std::abs(e[3]) <= margins[3]) {
      return RankCertificate::None;
    }
    const double norm = std::sqrt(e[0] * e[0] + e[1] * e[1] + e[2] * e[2] + e[3] * e[3]);
    inverse_norm[i] = 1 / norm;
    for (std::size_t k = 0; k < 4; ++k) d[k] += e[k] * inverse_norm[i];
  }
  // A direction proves when d . c_i > sum |d_k| margin_k on the unnormalised coefficients, which
  // keeps d . c > 0 for every perturbation of c within the margins. Tried: the mean of the unit
  // vectors (one pass; it separates most cells away from the set), then the point of their hull
  // nearest the origin (Wolfe), which separates the unit vectors whenever their hull misses the
  // origin. The margins are not part of that search, so where the vectors' lengths differ by
  // many orders a direction it finds can fail the margin test while another would pass; that
  // costs a split, never a wrong certificate (the margins are 1e-10 of the scale). Eight
  // perceptron steps between the two, tried before, certified no cell the two miss on the
  // examples and cost a third of the subdivision's time (docs/envelopes.md).
  const auto proves = [&](const Eigen::Vector4d& x) {
    const double slack = slack_of(x);
    for (std::size_t i = 0; i < n; ++i) {
      if (!(x.dot(Eigen::Map<const Eigen::Vector4d>(c + 4 * i)) > slack)) return false;
    }
    return true;
  };
  if (proves(Eigen::Vector4d(d[0], d[1], d[2], d[3]))) return RankCertificate::Hull;
  if (minimum_norm_separation(c, inverse_norm, slack_of, proves)) return RankCertificate::Hull;
  return RankCertificate::None;
}

RankCertificate cone_rank_certificate(const BernsteinTensor<4>& geometry, const std::array<double, 4>& lengths) {
  if (geometry.components != 3) throw InvalidInput("cone_rank_certificate needs a map into R^3 (three components)");
  std::array<std::vector<Eigen::Vector3d>, 4> partials;
  for (int d = 0; d < 4; ++d) {
    const BernsteinTensor<4> derivative = bernstein_derivative(geometry, d, lengths[static_cast<std::size_t>(d)]);
    auto& vectors = partials[static_cast<std::size_t>(d)];
    vectors.reserve(derivative.count());
    for (std::size_t i = 0; i < derivative.count(); ++i) {
      vectors.emplace_back(derivative.coefficients[3 * i], derivative.coefficients[3 * i + 1], derivative.coefficients[3 * i + 2]);
    }
  }
  constexpr std::array<std::array<std::size_t, 3>, 4> kTriples{{{0, 1, 2}, {0, 1, 3}, {0, 2, 3}, {1, 2, 3}}};
  for (const auto& triple : kTriples) {
    const auto [lo, hi] = cone_jacobian_bound(partials[triple[0]], partials[triple[1]], partials[triple[2]]);
    if (lo > 0 || hi < 0) return RankCertificate::Cone;
  }
  return RankCertificate::None;
}

}  // namespace volspline
