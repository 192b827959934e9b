#include "volspline/construct/sweep.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>
#include <string>
#include <utility>

#include <Eigen/Dense>
#include <Eigen/SparseCore>
#include <Eigen/SparseLU>

#include "volspline/core/bernstein_tensor.h"
#include "volspline/core/error.h"
#include "volspline/core/format.h"
#include "volspline/spline/affine_map.h"
#include "volspline/spline/bezier_extraction.h"
#include "volspline/spline/knot_insertion.h"

namespace volspline {

namespace {

using Eigen::Matrix3d;
using Eigen::MatrixXd;
using Eigen::Vector3d;


// A piecewise polynomial on common breakpoints, each piece in Bernstein form on its own span:
// pieces[s] is (degree + 1) x components, row k the coefficient of B_k^degree.
struct Piecewise {
  int degree = 0;
  std::vector<MatrixXd> pieces;
};

// Bernstein degree elevation from p to q: b'_k = sum_i C(p,i) C(q-p,k-i) / C(q,k) b_i.
MatrixXd elevate(const MatrixXd& b, int q) {
  const int p = static_cast<int>(b.rows()) - 1;
  if (p == q) return b;
  MatrixXd e = MatrixXd::Zero(q + 1, b.cols());
  for (int k = 0; k <= q; ++k)
    for (int i = std::max(0, k - (q - p)); i <= std::min(p, k); ++i)
      e.row(k) += binomial_coefficient(p, i) * binomial_coefficient(q - p, k - i) / binomial_coefficient(q, k) * b.row(i);
  return e;
}

Piecewise elevate(const Piecewise& f, int q) {
  Piecewise e{q, {}};
  for (const auto& b : f.pieces) e.pieces.push_back(elevate(b, q));
  return e;
}

// The product of a scalar piecewise polynomial and a vector-valued one, span by span:
// B_i^m B_j^n = C(m,i) C(n,j) / C(m+n,i+j) B_{i+j}^{m+n}, exact up to rounding.
Piecewise multiply(const Piecewise& scalar, const Piecewise& f) {
  const int m = scalar.degree, n = f.degree;
  Piecewise r{m + n, {}};
  for (std::size_t s = 0; s < f.pieces.size(); ++s) {
    const MatrixXd& a = scalar.pieces[s];
    const MatrixXd& b = f.pieces[s];
    MatrixXd c = MatrixXd::Zero(m + n + 1, b.cols());
    for (int i = 0; i <= m; ++i)
      for (int j = 0; j <= n; ++j) c.row(i + j) += binomial_coefficient(m, i) * binomial_coefficient(n, j) / binomial_coefficient(m + n, i + j) * a(i, 0) * b.row(j);
    r.pieces.push_back(std::move(c));
  }
  return r;
}

Piecewise constant_one(std::size_t spans) {
  Piecewise one{0, {}};
  for (std::size_t s = 0; s < spans; ++s) one.pieces.push_back(MatrixXd::Ones(1, 1));
  return one;
}

// The homogeneous form of `curve` (Lasser 1994, eq. 4) on the merged breakpoints.
Piecewise extract(const BSplineCurve& curve, const std::vector<double>& breaks) {
  std::vector<double> missing;
  for (std::size_t i = 1; i + 1 < breaks.size(); ++i)
    if (curve.knot_vector(0).multiplicity(breaks[i]) == 0) missing.push_back(breaks[i]);
  const BSplineCurve refined = missing.empty() ? curve : refine_knots(curve, 0, missing);
  const auto pieces = bezier_pieces(refined);
  if (pieces.size() + 1 != breaks.size()) throw Error("sweep: Bézier extraction gave an unexpected number of pieces");
  Piecewise f{curve.knot_vector(0).degree(), {}};
  const int cs = curve.coefficient_size();
  for (const auto& piece : pieces) {
    const auto& h = piece.homogeneous();
    MatrixXd b(f.degree + 1, cs);
    for (int k = 0; k <= f.degree; ++k)
      for (int c = 0; c < cs; ++c) b(k, c) = h[static_cast<std::size_t>(k * cs + c)];
    f.pieces.push_back(std::move(b));
  }
  return f;
}

// The column `c` of a piecewise polynomial.
Piecewise column(const Piecewise& f, int first, int count) {
  Piecewise r{f.degree, {}};
  for (const auto& b : f.pieces) r.pieces.push_back(b.middleCols(first, count));
  return r;
}

double max_abs(const Piecewise& f) {
  double m = 0.0;
  for (const auto& b : f.pieces) m = std::max(m, b.cwiseAbs().maxCoeff());
  return m;
}

// Equal as functions: same Bernstein coefficients after elevation to a common degree.
bool same_function(const Piecewise& a, const Piecewise& b) {
  const int q = std::max(a.degree, b.degree);
  const Piecewise ea = elevate(a, q), eb = elevate(b, q);
  const double scale = std::max(max_abs(a), max_abs(b));
  for (std::size_t s = 0; s < ea.pieces.size(); ++s)
    if ((ea.pieces[s] - eb.pieces[s]).cwiseAbs().maxCoeff() > 1e-13 * scale) return false;
  return true;
}

// The blossom of the Bernstein polynomial b on [lo, hi] at `args` (de Casteljau with one
// argument per level; Ramshaw's multi-affine form).
Eigen::RowVectorXd blossom(const MatrixXd& b, double lo, double hi, const double* args) {
  MatrixXd work = b;
  const int q = static_cast<int>(b.rows()) - 1;
  for (int r = 1; r <= q; ++r) {
    const double lambda = (args[r - 1] - lo) / (hi - lo);
    for (int j = 0; j <= q - r; ++j) work.row(j) = (1.0 - lambda) * work.row(j) + lambda * work.row(j + 1);
  }
  return work.row(0);
}

// Smoothness of `curve` at t: C^(p - multiplicity); a value that is no knot imposes nothing.
int continuity(const BSplineCurve& curve, double t) {
  const KnotVector& kv = curve.knot_vector(0);
  const int m = kv.multiplicity(t);
  return m == 0 ? std::numeric_limits<int>::max() : kv.degree() - m;
}

// The B-spline of degree q with the given breakpoint continuities that equals the piecewise
// polynomial f. Its coefficients are blossoms of the pieces at consecutive knots (de Boor-Fix:
// x_i = blossom of any piece in the support of N_i at t_{i+1}, ..., t_{i+q}), which is exact
// because f really has that smoothness; no linear system is solved.
std::pair<KnotVector, MatrixXd> assemble(const Piecewise& f, const std::vector<double>& breaks,
                                         const std::vector<int>& smoothness) {
  const int q = f.degree;
  std::vector<double> knots(static_cast<std::size_t>(q + 1), breaks.front());
  std::vector<int> span_of_knot(static_cast<std::size_t>(q + 1), 0);
  for (std::size_t i = 1; i + 1 < breaks.size(); ++i) {
    const int mult = std::clamp(q - smoothness[i], 1, q + 1);
    knots.insert(knots.end(), static_cast<std::size_t>(mult), breaks[i]);
    span_of_knot.insert(span_of_knot.end(), static_cast<std::size_t>(mult), static_cast<int>(i));
  }
  knots.insert(knots.end(), static_cast<std::size_t>(q + 1), breaks.back());
  span_of_knot.insert(span_of_knot.end(), static_cast<std::size_t>(q + 1), static_cast<int>(breaks.size()) - 1);
  KnotVector kv(q, knots);
  const int n = kv.num_basis();
  MatrixXd coefficients(n, f.pieces.front().cols());
  for (int i = 0; i < n; ++i) {
    const double* args = &knots[static_cast<std::size_t>(i + 1)];
    double mean = 0.0;
    for (int r = 0; r < q; ++r) mean += args[r];
    mean /= q;
    // Any nonempty span s in [i, i + q] works in exact arithmetic; the one nearest the
    // arguments keeps the blossom an interpolation rather than an extrapolation.
    int best = -1;
    double best_distance = std::numeric_limits<double>::infinity();
    for (int s = std::max(i, q); s <= std::min(i + q, n - 1); ++s) {
      if (!(knots[static_cast<std::size_t>(s)] < knots[static_cast<std::size_t>(s + 1)])) continue;
      const double d = std::abs(0.5 * (knots[static_cast<std::size_t>(s)] + knots[static_cast<std::size_t>(s + 1)]) - mean);
      if (d < best_distance) best_distance = d, best = s;
    }
    const int piece = span_of_knot[static_cast<std::size_t>(best)];
    coefficients.row(i) = blossom(f.pieces[static_cast<std::size_t>(piece)], breaks[static_cast<std::size_t>(piece)],
                                  breaks[static_cast<std::size_t>(piece) + 1], args);
  }
  return {std::move(kv), std::move(coefficients)};
}

void require_dimension(int dimension, const std::string& what) {
  if (dimension != 3) throw InvalidInput(what + " must be 3-dimensional, got dimension " + std::to_string(dimension));
}

double path_scale(const BSplineCurve& path) {
  double m = 0.0;
  const int n = path.num_control_points_total();
  for (int i = 0; i < n; ++i) {
    if (path.is_rational() && path.weights()[static_cast<std::size_t>(i)] == 0.0) continue;
    for (int c = 0; c < 3; ++c) m = std::max(m, std::abs(path.points()[static_cast<std::size_t>(3 * i + c)]));
  }
  return std::max(m, 1.0);
}

// A path that is a single point makes every sweep flat (zero volume).
void require_nonzero_length(const BSplineCurve& path) {
  const int n = path.num_control_points_total();
  const double tol = 1e-14 * path_scale(path);
  Vector3d first = Vector3d::Constant(std::numeric_limits<double>::quiet_NaN());
  for (int i = 0; i < n; ++i) {
    const Vector3d p = Eigen::Map<const Vector3d>(&path.points()[static_cast<std::size_t>(3 * i)]);
    if (path.is_rational() && path.weights()[static_cast<std::size_t>(i)] == 0.0) {
      if (p.norm() > 0.0) return;  // a point at infinity with a direction: the curve moves
      continue;
    }
    if (std::isnan(first.x())) first = p;
    else if ((p - first).norm() > tol) return;
  }
  throw InvalidInput("the sweep path has zero length (all its control points coincide)");
}

Vector3d point_at(const BSplineCurve& curve, double t) {
  const auto x = curve.evaluate({t});
  return {x[0], x[1], x[2]};
}

// Position and first two derivatives.
std::array<Vector3d, 3> derivatives_at(const BSplineCurve& curve, double t, int order) {
  const auto d = curve.evaluate_derivatives({t}, order);
  std::array<Vector3d, 3> r{Vector3d::Zero(), Vector3d::Zero(), Vector3d::Zero()};
  for (int k = 0; k <= order; ++k) r[static_cast<std::size_t>(k)] = Eigen::Map<const Vector3d>(&d[static_cast<std::size_t>(3 * k)]);
  return r;
}

// Speeds below this are a vanishing tangent: relative to the average speed over the domain.
double speed_floor(const BSplineCurve& path) {
  return 1e-10 * path_scale(path) / (path.domain_max(0) - path.domain_min(0));
}

Vector3d unit_tangent(const BSplineCurve& path, double t) {
  const Vector3d d = derivatives_at(path, t, 1)[1];
  if (!(d.norm() > speed_floor(path)))
    throw InvalidInput("the sweep path's tangent vanishes at w = " + format_double(t) + ": no frame is defined there");
  return d.normalized();
}

// Rotation-minimising and Frenet frames need a tangent that neither vanishes nor jumps; at
// breakpoints the two one-sided tangents come from the neighbouring Bézier pieces.
void require_continuous_tangent(const BSplineCurve& path) {
  const auto pieces = bezier_pieces(path);
  for (std::size_t s = 0; s + 1 < pieces.size(); ++s) {
    const double t = pieces[s].domain_max(0);
    const Vector3d left = derivatives_at(pieces[s], t, 1)[1], right = derivatives_at(pieces[s + 1], t, 1)[1];
    if (!(left.norm() > speed_floor(path)) || !(right.norm() > speed_floor(path)))
      throw InvalidInput("the sweep path's tangent vanishes at w = " + format_double(t) + ": no frame is defined there");
    if ((left.normalized() - right.normalized()).norm() > 1e-9)
      throw InvalidInput("the sweep path's tangent jumps at w = " + format_double(t) + ": a moving frame needs a G1 path");
  }
}

// A unit normal to the path's plane if its control points (and directions) span one.
bool plane_normal(const BSplineCurve& path, Vector3d& normal) {
  const int n = path.num_control_points_total();
  Matrix3d scatter = Matrix3d::Zero();
  Vector3d origin = Vector3d::Zero();
  bool have_origin = false;
  for (int i = 0; i < n; ++i) {
    const Vector3d p = Eigen::Map<const Vector3d>(&path.points()[static_cast<std::size_t>(3 * i)]);
    Vector3d v;
    if (path.is_rational() && path.weights()[static_cast<std::size_t>(i)] == 0.0) {
      v = p;
    } else if (!have_origin) {
      origin = p, have_origin = true;
      continue;
    } else {
      v = p - origin;
    }
    scatter += v * v.transpose();
  }
  Eigen::SelfAdjointEigenSolver<Matrix3d> eig(scatter);
  const Vector3d lambda = eig.eigenvalues();  // ascending
  if (!(lambda(2) > 0.0) || lambda(0) > 1e-24 * lambda(2) || lambda(1) <= 1e-20 * lambda(2)) return false;
  normal = eig.eigenvectors().col(0).normalized();
  return true;
}

Vector3d initial_normal(const BSplineCurve& path, double t0, const Vector3d& tangent) {
  try {
    return frenet_frame(path, t0).col(0);
  } catch (const InvalidInput&) {
  }
  Vector3d n;
  if (plane_normal(path, n)) return n.cross(tangent).normalized();
  Eigen::Index axis = 0;
  tangent.cwiseAbs().minCoeff(&axis);
  const Vector3d e = Vector3d::Unit(axis);
  return (e - e.dot(tangent) * tangent).normalized();
}

double length_scale(const BSplineCurve& path) {
  const int n = path.num_control_points_total();
  Vector3d lo = Vector3d::Constant(std::numeric_limits<double>::infinity()), hi = -lo;
  for (int i = 0; i < n; ++i) {
    if (path.is_rational() && path.weights()[static_cast<std::size_t>(i)] == 0.0) continue;
    const Vector3d p = Eigen::Map<const Vector3d>(&path.points()[static_cast<std::size_t>(3 * i)]);
    lo = lo.cwiseMin(p), hi = hi.cwiseMax(p);
  }
  const double d = (hi - lo).norm();
  return d > 0.0 ? d : 1.0;
}

Matrix3d evaluate_frame(const std::array<BSplineCurve, 3>& curves, double t) {
  Matrix3d r;
  for (int a = 0; a < 3; ++a) r.col(a) = point_at(curves[static_cast<std::size_t>(a)], t);
  return r;
}

// The Frenet frame must exist on the whole path, not only at the fit's samples: on a fine
// sampling, a zero curvature throws in frenet_frame, and a binormal (or tangent) that reverses
// between neighbouring samples means the curvature (or the speed) passed through zero there.
void require_frenet_frame(const BSplineCurve& path) {
  const double a = path.domain_min(0), b = path.domain_max(0);
  std::vector<double> samples;
  for (int i = 0; i <= 4096; ++i) samples.push_back(a + (b - a) * i / 4096.0);
  const auto breaks = path.knot_vector(0).breakpoints();
  samples.insert(samples.end(), breaks.begin(), breaks.end());
  std::sort(samples.begin(), samples.end());
  Matrix3d previous = frenet_frame(path, samples.front());
  for (std::size_t i = 1; i < samples.size(); ++i) {
    const Matrix3d f = frenet_frame(path, samples[i]);
    if (f.col(1).dot(previous.col(1)) < 0.0 || f.col(2).dot(previous.col(2)) < 0.0)
      throw InvalidInput("the sweep path's curvature vanishes between w = " + format_double(samples[i - 1]) + " and " +
                         format_double(samples[i]) + ": the Frenet frame is undefined there");
    previous = f;
  }
  // The Frenet frame depends on c'', which may jump at a breakpoint: compare the one-sided
  // frames of the neighbouring Bézier pieces.
  const auto pieces = bezier_pieces(path);
  for (std::size_t i = 0; i + 1 < pieces.size(); ++i) {
    const double t = pieces[i].domain_max(0);
    if ((frenet_frame(pieces[i], t) - frenet_frame(pieces[i + 1], t)).cwiseAbs().maxCoeff() > 1e-9)
      throw InvalidInput("the sweep path's Frenet frame jumps at w = " + format_double(t) +
                         " (its curvature vector changes direction there); use the rotation-minimising frame");
  }
}

// The frame is less smooth than the path at its breakpoints: where the path is C^k, its tangent
// is C^(k-1), the rotation-minimising frame (r' = -(r . t') t) C^(k-1) and the Frenet frame,
// built from c'', C^(k-2). Interpolating it with the path's own continuity would force a
// smoothness it lacks and the fit would converge like O(h) instead of O(h^(p+1)), so those
// knots get one (RMF) or two (Frenet) more copies, keeping at least C^0.
BSplineCurve frame_knots(const BSplineCurve& path, SweepFrame frame) {
  const KnotVector& kv = path.knot_vector(0);
  const int p = kv.degree(), extra = frame == SweepFrame::Frenet ? 2 : 1;
  const auto breaks = kv.breakpoints();
  std::vector<double> insert;
  for (std::size_t i = 1; i + 1 < breaks.size(); ++i) {
    const int m = kv.multiplicity(breaks[i]);
    for (int k = m; k < std::min(p, m + extra); ++k) insert.push_back(breaks[i]);
  }
  return insert.empty() ? path : refine_knots(path, 0, insert);
}

}  // namespace

BSplineVolume sweep_with_frame_curves(const BSplineSurface& profile, const BSplineCurve& path,
                                      const std::array<BSplineCurve, 3>& frame) {
  require_dimension(profile.dimension(), "the sweep profile");
  require_dimension(path.dimension(), "the sweep path");
  const double a = path.domain_min(0), b = path.domain_max(0);
  for (int k = 0; k < 3; ++k) {
    require_dimension(frame[static_cast<std::size_t>(k)].dimension(), "frame curve " + std::to_string(k));
    if (frame[static_cast<std::size_t>(k)].domain_min(0) != a || frame[static_cast<std::size_t>(k)].domain_max(0) != b)
      throw InvalidInput("frame curve " + std::to_string(k) + " has the domain [" + format_double(frame[static_cast<std::size_t>(k)].domain_min(0)) +
                         ", " + format_double(frame[static_cast<std::size_t>(k)].domain_max(0)) + "], the path [" + format_double(a) +
                         ", " + format_double(b) + "]: they must be equal");
  }
  // The w-direction functions in the order of M's columns: frame columns, then the path.
  const std::array<const BSplineCurve*, 4> curves{&frame[0], &frame[1], &frame[2], &path};
  std::vector<double> breaks;
  for (const auto* c : curves) {
    const auto bp = c->knot_vector(0).breakpoints();
    breaks.insert(breaks.end(), bp.begin(), bp.end());
  }
  std::sort(breaks.begin(), breaks.end());
  breaks.erase(std::unique(breaks.begin(), breaks.end()), breaks.end());
  std::vector<int> smoothness(breaks.size(), std::numeric_limits<int>::max());
  for (std::size_t i = 1; i + 1 < breaks.size(); ++i)
    for (const auto* c : curves) smoothness[i] = std::min(smoothness[i], continuity(*c, breaks[i]));

  // Numerators and denominators of the homogeneous forms. Denominators that are equal as
  // functions (a frame fitted with the path's weights, the cos/sin columns of one rational
  // rotation) form one class, so they are not multiplied into the common denominator twice.
  std::array<Piecewise, 4> numerators;
  std::array<int, 4> denominator_class{-1, -1, -1, -1};
  std::vector<Piecewise> classes;
  for (std::size_t k = 0; k < 4; ++k) {
    const Piecewise h = extract(*curves[k], breaks);
    numerators[k] = column(h, 0, 3);
    if (!curves[k]->is_rational()) continue;
    Piecewise w = column(h, 3, 1);
    const double w0 = w.pieces.front()(0, 0);
    bool constant = w0 > 0.0;
    for (const auto& piece : w.pieces) constant = constant && (piece.array() - w0).abs().maxCoeff() <= 1e-15 * w0;
    if (constant) {  // a rational curve with equal weights is polynomial
      for (auto& piece : numerators[k].pieces) piece /= w0;
      continue;
    }
    for (std::size_t c = 0; c < classes.size() && denominator_class[k] < 0; ++c)
      if (same_function(classes[c], w)) denominator_class[k] = static_cast<int>(c);
    if (denominator_class[k] < 0) {
      denominator_class[k] = static_cast<int>(classes.size());
      classes.push_back(std::move(w));
    }
  }
  // M(w) = [[delta R, delta c], [0, delta]] with delta the product of the classes: each column
  // is its numerator times the denominators of the other classes.
  const std::size_t spans = breaks.size() - 1;
  Piecewise delta = constant_one(spans);
  for (const auto& c : classes) delta = multiply(c, delta);
  std::array<Piecewise, 4> entries;
  for (std::size_t k = 0; k < 4; ++k) {
    Piecewise factor = constant_one(spans);
    for (std::size_t c = 0; c < classes.size(); ++c)
      if (static_cast<int>(c) != denominator_class[k]) factor = multiply(classes[c], factor);
    entries[k] = multiply(factor, numerators[k]);
  }
  int q = delta.degree;
  for (const auto& e : entries) q = std::max(q, e.degree);
  Piecewise m{q, {}};
  for (std::size_t s = 0; s < spans; ++s) {
    MatrixXd piece(q + 1, 13);
    for (std::size_t k = 0; k < 4; ++k) piece.middleCols(static_cast<Eigen::Index>(3 * k), 3) = elevate(entries[k].pieces[s], q);
    piece.col(12) = elevate(delta.pieces[s], q);
    m.pieces.push_back(std::move(piece));
  }
  auto [kw, mk] = assemble(m, breaks, smoothness);

  // V_ijk = M_k F_ij (Lasser 1994, eq. 6, with M_k the k-th B-spline coefficient of M(w)).
  const bool rational = profile.is_rational() || !classes.empty();
  const int nuv = profile.num_control_points_total(), nw = kw.num_basis();
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
  return BSplineVolume::from_homogeneous({profile.knot_vector(0), profile.knot_vector(1), std::move(kw)}, 3, rational,
                                         std::move(coefficients));
}

Matrix3d frenet_frame(const BSplineCurve& path, double t) {
  require_dimension(path.dimension(), "the sweep path");
  const auto d = derivatives_at(path, t, 2);
  if (!(d[1].norm() > speed_floor(path)))
    throw InvalidInput("the sweep path's tangent vanishes at w = " + format_double(t) + ": no Frenet frame there");
  const Vector3d cross = d[1].cross(d[2]);
  const double curvature = cross.norm() / std::pow(d[1].norm(), 3);
  // Curvature times the path's size: dimensionless, so the test does not depend on scale.
  if (!(curvature * length_scale(path) > 1e-9))
    throw InvalidInput("the sweep path's curvature vanishes at w = " + format_double(t) + ": the Frenet frame is undefined there");
  Matrix3d r;
  r.col(2) = d[1].normalized();
  r.col(1) = cross.normalized();
  r.col(0) = r.col(1).cross(r.col(2));
  return r;
}

std::vector<Matrix3d> rotation_minimizing_frames(const BSplineCurve& path, const std::vector<double>& parameters,
                                                 const Matrix3d& start) {
  require_dimension(path.dimension(), "the sweep path");
  std::vector<Matrix3d> frames;
  if (parameters.empty()) return frames;
  for (std::size_t i = 0; i < parameters.size(); ++i) {
    path.check_in_domain({parameters[i]});
    if (i > 0 && parameters[i] < parameters[i - 1]) throw InvalidInput("parameters must be ascending", "[" + std::to_string(i) + "]");
  }
  const double h_max = (path.domain_max(0) - path.domain_min(0)) / 4096.0;
  double t = parameters.front();
  Vector3d x = point_at(path, t), tangent = unit_tangent(path, t);
  Vector3d r = start.isZero(0.0) ? initial_normal(path, t, tangent) : Vector3d(start.col(0));
  r = (r - r.dot(tangent) * tangent).normalized();
  auto push = [&] {
    Matrix3d f;
    f.col(0) = r, f.col(1) = tangent.cross(r), f.col(2) = tangent;
    frames.push_back(f);
  };
  push();
  for (std::size_t i = 1; i < parameters.size(); ++i) {
    const double t1 = parameters[i];
    const int steps = std::max(1, static_cast<int>(std::ceil((t1 - t) / h_max)));
    const double t0 = t;
    for (int s = 1; s <= steps; ++s) {
      const double tn = s == steps ? t1 : t0 + (t1 - t0) * s / steps;
      const Vector3d xn = point_at(path, tn), tn_vec = unit_tangent(path, tn);
      // Steps are tiny, so a tangent that turns by more than 90 degrees in one is a cusp.
      if (tn_vec.dot(tangent) < 0.0)
        throw InvalidInput("the sweep path's tangent vanishes between w = " + format_double(t0 + (t1 - t0) * (s - 1) / steps) +
                           " and " + format_double(tn) + " (a cusp): no frame is defined there");
      // Double reflection (Wang et al. 2008, Algorithm "double reflection"): reflect in the
      // bisecting plane of x_i x_{i+1}, then in the plane that carries the reflected tangent
      // onto the new one. Each step is exactly a rotation, so r stays a unit normal.
      const Vector3d v1 = xn - x;
      const double c1 = v1.squaredNorm();
      Vector3d r_l = r, t_l = tangent;
      if (c1 > 0.0) {
        r_l = r - (2.0 / c1) * v1.dot(r) * v1;
        t_l = tangent - (2.0 / c1) * v1.dot(tangent) * v1;
      }
      const Vector3d v2 = tn_vec - t_l;
      const double c2 = v2.squaredNorm();
      r = c2 > 0.0 ? Vector3d(r_l - (2.0 / c2) * v2.dot(r_l) * v2) : r_l;
      // Rounding only: keep r exactly normal to the tangent and of unit length.
      r = (r - r.dot(tn_vec) * tn_vec).normalized();
      x = xn, tangent = tn_vec;
    }
    t = t1;
    push();
  }
  return frames;
}

SweepFrameFit fit_sweep_frame(const BSplineCurve& path, SweepFrame frame, double tolerance) {
  require_dimension(path.dimension(), "the sweep path");
  if (!(tolerance > 0.0)) throw InvalidInput("the frame tolerance must be positive, got " + format_double(tolerance));
  require_nonzero_length(path);
  if (frame != SweepFrame::Fixed) require_continuous_tangent(path);
  const double a = path.domain_min(0);
  BSplineCurve current = clamp(frame == SweepFrame::Fixed ? path : frame_knots(path, frame));
  if (frame == SweepFrame::Fixed) {
    // R = I exactly: numerators gamma(w) e_a, i.e. the path's weights times e_a, which is
    // Lasser's translation matrix M_k of Theorem 1 once the sweep multiplies it out.
    SweepFrameFit fit{{current, current, current}, current, 0.0, 0.0, current.knot_vector(0).num_spans()};
    const int n = current.num_control_points_total();
    for (int col = 0; col < 3; ++col) {
      std::vector<double> h;
      for (int i = 0; i < n; ++i) {
        const double w = current.is_rational() ? current.weights()[static_cast<std::size_t>(i)] : 1.0;
        for (int e = 0; e < 3; ++e) h.push_back(e == col ? w : 0.0);
        if (current.is_rational()) h.push_back(w);
      }
      fit.curves[static_cast<std::size_t>(col)] =
          BSplineCurve::from_homogeneous({current.knot_vector(0)}, 3, current.is_rational(), std::move(h));
    }
    return fit;
  }
  if (frame == SweepFrame::Frenet) require_frenet_frame(path);
  Matrix3d start = Matrix3d::Zero();
  if (frame == SweepFrame::RotationMinimizing) start = rotation_minimizing_frames(path, {a}).front();

  for (int halvings = 0; halvings <= 12; ++halvings) {
    const KnotVector& kv = current.knot_vector(0);
    const int p = kv.degree(), n = kv.num_basis();
    const auto& knots = kv.knots();
    std::vector<double> sites(static_cast<std::size_t>(n));
    for (int i = 0; i < n; ++i) {
      double g = 0.0;
      for (int r = 1; r <= p; ++r) g += knots[static_cast<std::size_t>(i + r)];
      sites[static_cast<std::size_t>(i)] = g / p;
    }
    const auto breaks = kv.breakpoints();
    std::vector<double> checks;
    for (std::size_t s = 0; s + 1 < breaks.size(); ++s)
      for (double f : {0.125, 0.375, 0.5, 0.625, 0.875}) checks.push_back(breaks[s] + f * (breaks[s + 1] - breaks[s]));
    std::vector<double> all = sites;
    all.insert(all.end(), checks.begin(), checks.end());
    std::sort(all.begin(), all.end());
    all.erase(std::unique(all.begin(), all.end()), all.end());

    std::vector<Matrix3d> exact;
    if (frame == SweepFrame::RotationMinimizing) {
      exact = rotation_minimizing_frames(current, all, start);
    } else {
      for (double t : all) exact.push_back(frenet_frame(current, t));
    }
    auto exact_at = [&](double t) {
      return exact[static_cast<std::size_t>(std::lower_bound(all.begin(), all.end(), t) - all.begin())];
    };

    // Interpolate the numerators gamma(w) R(w) at the Greville abscissae with the path's own
    // weights as denominators: the frame curves then share the path's weight function, so
    // the sweep's common denominator is the path's and its degree stays deg(path).
    Eigen::SparseMatrix<double> collocation(n, n);
    std::vector<Eigen::Triplet<double>> entries;
    MatrixXd rhs(n, 9);
    std::vector<double> basis(static_cast<std::size_t>(p + 1));
    for (int j = 0; j < n; ++j) {
      const double t = sites[static_cast<std::size_t>(j)];
      const int span = kv.find_span(t);
      kv.basis(span, t, basis.data());
      double gamma = 0.0;
      for (int r = 0; r <= p; ++r) {
        entries.emplace_back(j, span - p + r, basis[static_cast<std::size_t>(r)]);
        if (current.is_rational()) gamma += basis[static_cast<std::size_t>(r)] * current.weights()[static_cast<std::size_t>(span - p + r)];
      }
      if (!current.is_rational()) gamma = 1.0;
      const Matrix3d f = exact_at(t);
      for (int col = 0; col < 3; ++col) rhs.block(j, 3 * col, 1, 3) = gamma * f.col(col).transpose();
    }
    collocation.setFromTriplets(entries.begin(), entries.end());
    Eigen::SparseLU<Eigen::SparseMatrix<double>> lu;
    lu.compute(collocation);
    if (lu.info() != Eigen::Success) throw Error("sweep: the frame interpolation matrix is singular");
    const MatrixXd numerators = lu.solve(rhs);

    SweepFrameFit fit{{current, current, current}, current, 0.0, 0.0, kv.num_spans()};
    for (int col = 0; col < 3; ++col) {
      std::vector<double> h;
      for (int i = 0; i < n; ++i) {
        for (int e = 0; e < 3; ++e) h.push_back(numerators(i, 3 * col + e));
        if (current.is_rational()) h.push_back(current.weights()[static_cast<std::size_t>(i)]);
      }
      fit.curves[static_cast<std::size_t>(col)] = BSplineCurve::from_homogeneous({kv}, 3, current.is_rational(), std::move(h));
    }
    for (double t : checks) {
      const Matrix3d r = evaluate_frame(fit.curves, t);
      fit.orthonormality_error = std::max(fit.orthonormality_error, (r.transpose() * r - Matrix3d::Identity()).cwiseAbs().maxCoeff());
      fit.frame_error = std::max(fit.frame_error, (r - exact_at(t)).cwiseAbs().maxCoeff());
    }
    if (fit.orthonormality_error <= tolerance) return fit;
    std::vector<double> midpoints;
    for (std::size_t s = 0; s + 1 < breaks.size(); ++s) midpoints.push_back(0.5 * (breaks[s] + breaks[s + 1]));
    current = refine_knots(current, 0, midpoints);
  }
  throw NotConverged("the sweep frame fit did not reach the orthonormality tolerance " + format_double(tolerance) +
                     " after 12 halvings of the path's spans");
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

BSplineCurve conic_arc(Vector3d start, double angle_deg, double s2, Vector3d axis_point, Vector3d axis_direction) {
  if (!start.allFinite() || !axis_point.allFinite() || !axis_direction.allFinite() || !std::isfinite(angle_deg) ||
      !std::isfinite(s2))
    throw InvalidInput("conic arc: every number must be finite");
  if (!(axis_direction.norm() > 0.0)) throw InvalidInput("conic arc: the axis direction is zero");
  if (!(angle_deg != 0.0 && std::abs(angle_deg) <= 180.0))
    throw InvalidInput("conic arc: the angle must satisfy 0 < |angle| <= 180 degrees (Lasser 1994, Theorem 2), got " +
                       format_double(angle_deg));
  if (!(s2 > 0.0)) throw InvalidInput("conic arc: s2 must be positive, got " + format_double(s2));
  const Vector3d axis = axis_direction.normalized();
  const Vector3d d = start - axis_point;
  const Vector3d along = d.dot(axis) * axis, radial = d - along;
  if (!(radial.norm() > 1e-14 * std::max(1.0, d.norm()))) throw InvalidInput("conic arc: the start point lies on the axis");
  const double alpha = angle_deg * std::numbers::pi / 180.0;
  const Vector3d side = axis.cross(radial);  // radial turned by +90 degrees about the axis
  const double half_cos = std::abs(angle_deg) == 180.0 ? 0.0 : std::cos(alpha / 2);
  const double half_sin = std::sin(alpha / 2);
  const double end_cos = std::abs(angle_deg) == 180.0 ? -1.0 : std::cos(alpha);
  const double end_sin = std::abs(angle_deg) == 180.0 ? 0.0 : std::sin(alpha);
  const Vector3d end = axis_point + along + end_cos * radial + end_sin * side;
  // Lasser's M_1 K_0 = (rot(alpha/2) radial + cos(alpha/2) (axis_point + along), cos(alpha/2))
  // homogeneously; scaled by s2 it keeps its Cartesian point (where the end tangents meet) and
  // gets the weight s2 cos(alpha/2), which alone decides the type of conic (eq. 9).
  const Vector3d turned = half_cos * radial + half_sin * side;
  std::vector<double> points{start.x(), start.y(), start.z()}, weights{1.0, s2 * half_cos, 1.0};
  Vector3d middle;
  if (half_cos == 0.0) middle = s2 * turned;  // a point at infinity: its direction (Lasser, after eq. 5)
  else middle = axis_point + along + turned / half_cos;
  points.insert(points.end(), {middle.x(), middle.y(), middle.z(), end.x(), end.y(), end.z()});
  return BSplineCurve({KnotVector::bezier(2)}, 3, std::move(points), std::move(weights));
}

BSplineVolume translation_along_conic(const BSplineSurface& profile, Vector3d start, double angle_deg, double s2,
                                      Vector3d axis_point, Vector3d axis_direction) {
  return sweep(profile, conic_arc(start, angle_deg, s2, axis_point, axis_direction), SweepFrame::Fixed);
}

}  // namespace volspline
