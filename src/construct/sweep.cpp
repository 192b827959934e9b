#include "volspline/construct/sweep.h"

#include <algorithm>
#include <limits>
#include <string>
#include <utility>

#include <Eigen/Dense>

#include "path_geometry.h"
#include "piecewise_bernstein.h"
#include "volspline/core/error.h"
#include "volspline/core/format.h"
#include "volspline/spline/affine_map.h"

namespace volspline {

namespace {

using namespace detail;
using Eigen::Matrix3d;
using Eigen::Vector3d;

void require_common_domain(const BSplineCurve& path, const std::array<BSplineCurve, 3>& frame) {
  const double a = path.domain_min(0), b = path.domain_max(0);
  for (std::size_t k = 0; k < 3; ++k) {
    require_dimension(frame[k].dimension(), "frame curve " + std::to_string(k));
    if (frame[k].domain_min(0) != a || frame[k].domain_max(0) != b)
      throw InvalidInput("frame curve " + std::to_string(k) + " has the domain [" + format_double(frame[k].domain_min(0)) + ", " +
                         format_double(frame[k].domain_max(0)) + "], the path [" + format_double(a) + ", " + format_double(b) +
                         "]: they must be equal");
  }
}

// M(w) = [[delta R, delta c], [0, delta]] (Lasser 1994, eq. 6) as 13 components per span: the
// three frame columns, the path, then delta. `rational` says whether delta is not constant.
struct FrameMatrix {
  PiecewiseBernstein entries;
  bool rational = false;
};

FrameMatrix frame_matrix(const std::array<const BSplineCurve*, 4>& curves, const std::vector<double>& breaks) {
  // Numerators and denominators of the homogeneous forms. Denominators that are equal as
  // functions (a frame fitted with the path's weights, the cos/sin columns of one rational
  // rotation) form one class, so they are not multiplied into the common denominator twice.
  std::array<PiecewiseBernstein, 4> numerators;
  std::array<int, 4> denominator_class{-1, -1, -1, -1};
  std::vector<PiecewiseBernstein> classes;
  for (std::size_t k = 0; k < 4; ++k) {
    const PiecewiseBernstein h = homogeneous_pieces(*curves[k], breaks);
    numerators[k] = components(h, 0, 3);
    if (!curves[k]->is_rational()) continue;
    PiecewiseBernstein w = components(h, 3, 1);
    const double w0 = w.front().coefficients.front();
    bool constant = w0 > 0.0;
    for (const auto& piece : w)
      for (double x : piece.coefficients) constant = constant && std::abs(x - w0) <= 1e-15 * w0;
    if (constant) {  // a rational curve with equal weights is polynomial
      for (auto& piece : numerators[k])
        for (double& x : piece.coefficients) x /= w0;
      continue;
    }
    for (std::size_t c = 0; c < classes.size() && denominator_class[k] < 0; ++c)
      if (same_function(classes[c], w)) denominator_class[k] = static_cast<int>(c);
    if (denominator_class[k] < 0) {
      denominator_class[k] = static_cast<int>(classes.size());
      classes.push_back(std::move(w));
    }
  }
  // delta is the product of the classes: each column is its numerator times the denominators of
  // the other classes.
  const std::size_t spans = breaks.size() - 1;
  PiecewiseBernstein delta = constant_one(spans);
  for (const auto& c : classes) delta = multiply(c, delta);
  std::array<PiecewiseBernstein, 4> entries;
  for (std::size_t k = 0; k < 4; ++k) {
    PiecewiseBernstein factor = constant_one(spans);
    for (std::size_t c = 0; c < classes.size(); ++c)
      if (static_cast<int>(c) != denominator_class[k]) factor = multiply(classes[c], factor);
    entries[k] = multiply(factor, numerators[k]);
  }
  int q = delta.front().degrees[0];
  for (const auto& e : entries) q = std::max(q, e.front().degrees[0]);
  delta = elevate(delta, q);
  for (auto& e : entries) e = elevate(e, q);
  FrameMatrix m{PiecewiseBernstein(spans, BernsteinTensor<1>({q}, 13)), !classes.empty()};
  for (std::size_t s = 0; s < spans; ++s) {
    for (std::size_t i = 0; i <= static_cast<std::size_t>(q); ++i) {
      double* row = m.entries[s].coefficients.data() + 13 * i;
      for (std::size_t k = 0; k < 4; ++k) std::copy_n(entries[k][s].coefficients.data() + 3 * i, 3, row + 3 * k);
      row[12] = delta[s].coefficients[i];
    }
  }
  return m;
}

// V_ijk = M_k F_ij (Lasser 1994, eq. 6, with M_k the k-th B-spline coefficient of M(w)); for a
// volume generator the same with F_ijk and a fourth index (Conkey-Joy §4). The profile's control
// points are one block (u fastest), so the sweep direction is the slowest index either way.
template <int D>
std::vector<double> swept_coefficients(const TensorSpline<D>& profile, const Eigen::MatrixXd& mk, bool rational) {
  const int nuv = profile.num_control_points_total(), nw = static_cast<int>(mk.rows());
  const int pcs = profile.coefficient_size(), vcs = rational ? 4 : 3;
  const auto& fh = profile.homogeneous();
  std::vector<double> coefficients(static_cast<std::size_t>(nuv) * static_cast<std::size_t>(nw) * static_cast<std::size_t>(vcs));
  for (int k = 0; k < nw; ++k) {
    Matrix3d r;
    for (int a2 = 0; a2 < 3; ++a2) r.col(a2) = mk.row(k).segment<3>(3 * a2).transpose();
    const Vector3d c = mk.row(k).segment<3>(9).transpose();
    // Rounding may leave -1e-17 where a product of weights is exactly 0.
    const double d = std::max(0.0, mk(k, 12));
    for (int ij = 0; ij < nuv; ++ij) {
      const double* f = &fh[static_cast<std::size_t>(ij * pcs)];
      const double weight = pcs == 4 ? f[3] : 1.0;
      const Vector3d x = r * Vector3d(f[0], f[1], f[2]) + weight * c;
      double* out = &coefficients[(static_cast<std::size_t>(k) * static_cast<std::size_t>(nuv) + static_cast<std::size_t>(ij)) *
                                  static_cast<std::size_t>(vcs)];
      for (int e = 0; e < 3; ++e) out[e] = x(e);
      if (rational) out[3] = d * weight;
    }
  }
  return coefficients;
}

// The profile (D parameters) moved by the frame curves: D + 1 parameters, the path's last.
template <int D>
TensorSpline<D + 1> sweep_profile(const TensorSpline<D>& profile, const BSplineCurve& path, const std::array<BSplineCurve, 3>& frame,
                                  const std::string& profile_name) {
  require_dimension(profile.dimension(), profile_name);
  require_dimension(path.dimension(), "the sweep path");
  require_common_domain(path, frame);
  // The sweep-direction functions in the order of M's columns: frame columns, then the path.
  const std::array<const BSplineCurve*, 4> curves{&frame[0], &frame[1], &frame[2], &path};
  const auto [breaks, smoothness] = merged_breakpoints({curves.begin(), curves.end()});
  const FrameMatrix m = frame_matrix(curves, breaks);
  // Named, not a structured binding: clang 14 (the fuzz build) does not let a lambda capture one.
  auto sweep_spline = to_bspline(m.entries, breaks, smoothness);
  KnotVector& k_sweep = sweep_spline.first;
  const auto& mk = sweep_spline.second;
  const bool rational = profile.is_rational() || m.rational;
  std::array<KnotVector, D + 1> knots = [&]<std::size_t... I>(std::index_sequence<I...>) {
    return std::array<KnotVector, D + 1>{profile.knot_vector(static_cast<int>(I))..., std::move(k_sweep)};
  }(std::make_index_sequence<D>{});
  return TensorSpline<D + 1>::from_homogeneous(std::move(knots), 3, rational, swept_coefficients(profile, mk, rational));
}

}  // namespace

BSplineVolume sweep_with_frame_curves(const BSplineSurface& profile, const BSplineCurve& path,
                                      const std::array<BSplineCurve, 3>& frame) {
  return sweep_profile(profile, path, frame, "the sweep profile");
}

BSplineHypervolume sweep_with_frame_curves(const BSplineVolume& generator, const BSplineCurve& path,
                                           const std::array<BSplineCurve, 3>& frame) {
  return sweep_profile(generator, path, frame, "the generator solid");
}

BSplineVolume sweep(const BSplineSurface& profile, const BSplineCurve& path, SweepFrame frame) {
  require_dimension(profile.dimension(), "the sweep profile");
  require_dimension(path.dimension(), "the sweep path");
  const SweepFrameFit fit = fit_sweep_frame(path, frame);
  const double a = path.domain_min(0);
  // Profile coordinates are world coordinates at the path's start: express them in the start
  // frame, F' = R(a)^T (F - c(a)), so that V(u, v, a) = c(a) + R(a) F' = F.
  const Matrix3d r0 = evaluate_frame(fit.curves, a);
  const Vector3d c0 = point_at(path, a);
  const BSplineSurface local = transform_affine(profile, r0.transpose(), -(r0.transpose() * c0));
  return sweep_with_frame_curves(local, fit.path, fit.curves);
}

BSplineVolume translation_along_conic(const BSplineSurface& profile, Vector3d start, double angle_deg, double s2,
                                      Vector3d axis_point, Vector3d axis_direction) {
  return sweep(profile, conic_arc(start, angle_deg, s2, axis_point, axis_direction), SweepFrame::Fixed);
}

}  // namespace volspline
