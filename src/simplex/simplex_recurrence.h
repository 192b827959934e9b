#pragma once
// The recurrence of eq. 1 (Hua, He and Qin 2004) over subsets of a knot set, shared by the
// single-spline routines (simplex_spline.cpp) and the DMS basis of one tetrahedron
// (dms_tetrahedron_basis.cpp). A subset is a bitmask over at most 32 knots; a memo (an open
// addressing table cleared by a generation stamp) evaluates each subset once per point or line.
// docs/simplex-splines.md explains the choices.
#include <Eigen/Core>
#include <Eigen/Geometry>
#include <array>
#include <bit>
#include <cstdint>
#include <functional>
#include <limits>
#include <vector>

#include "volspline/simplex/simplex_spline.h"

namespace volspline::simplex_detail {

using KnotMask = std::uint32_t;

/// At most 4(n + 1) knots: the knot clouds of one domain tetrahedron of degree n.
inline constexpr int kMaxRecurrenceKnots = 4 * (kMaxSimplexSplineDegree + 1);

/// Barycentric coordinates with respect to four knots a, b, c, d:
/// λ_j(x) = g[j]·(x - a) + [j == 0]. The g[j] = ∇λ_j are the μ_j(e_x, e_y, e_z) of eq. 2.
struct BarycentricFrame {
  Eigen::Vector3d origin = Eigen::Vector3d::Zero();
  std::array<Eigen::Vector3d, 4> g{};
  double det = 0;  // det[b - a, c - a, d - a]

  std::array<double, 4> lambda(const Eigen::Vector3d& x) const {
    const Eigen::Vector3d r = x - origin;
    const double l1 = g[1].dot(r);
    const double l2 = g[2].dot(r);
    const double l3 = g[3].dot(r);
    return {1.0 - l1 - l2 - l3, l1, l2, l3};
  }
  std::array<double, 4> mu(const Eigen::Vector3d& v) const {
    return {g[0].dot(v), g[1].dot(v), g[2].dot(v), g[3].dot(v)};
  }
};

/// λ(x) with respect to (a, b, c, d) by Cramer's rule, det = det[b - a, c - a, d - a]: λ_j is det W
/// with w_j replaced by x over det W, and each numerator is taken as det[q - p, r - p, x - p] of
/// the other three knots (p, q, r), relative to a knot of that face. Near a cloud's small
/// tetrahedra this keeps digits that g·(x - a) and λ_0 = 1 - λ_1 - λ_2 - λ_3 lose.
inline std::array<double, 4> face_barycentric(const Eigen::Vector3d& x, const Eigen::Vector3d& a,
                                              const Eigen::Vector3d& b, const Eigen::Vector3d& c,
                                              const Eigen::Vector3d& d, double det) {
  const auto face = [&x](const Eigen::Vector3d& p, const Eigen::Vector3d& q, const Eigen::Vector3d& r) {
    return (q - p).cross(r - p).dot(x - p);
  };
  const double inverse = 1.0 / det;
  return {-face(b, c, d) * inverse, face(a, c, d) * inverse, -face(a, b, d) * inverse, face(a, b, c) * inverse};
}

/// det[b - a, c - a, d - a] in floating point.
inline double oriented_det(const Eigen::Vector3d& a, const Eigen::Vector3d& b, const Eigen::Vector3d& c,
                           const Eigen::Vector3d& d) {
  return (b - a).dot((c - a).cross(d - a));
}

/// Whether a, b, c, d are coplanar, decided exactly (CGAL's filtered orientation predicate).
bool exactly_coplanar(const Eigen::Vector3d& a, const Eigen::Vector3d& b, const Eigen::Vector3d& c,
                      const Eigen::Vector3d& d);

/// Whether a, b, c are collinear, decided exactly.
bool exactly_collinear(const Eigen::Vector2d& a, const Eigen::Vector2d& b, const Eigen::Vector2d& c);

/// The relative rounding assumed in the coordinates of knots and points (64 units in the last
/// place): four points whose determinant could vanish under such a change count as coplanar.
inline constexpr double kCoordinateRounding = 64 * std::numeric_limits<double>::epsilon() / 2;

/// Whether a, b, c, d are coplanar within the rounding of their coordinates: |det| <=
/// kCoordinateRounding · max|coordinate| · (sum of the pairwise products of the edge lengths from
/// the lexicographically smallest point), the determinant taken in that order, so that the
/// decision does not depend on the order of the arguments. Exactly coplanar points always are.
bool coplanar_within_rounding(const Eigen::Vector3d& a, const Eigen::Vector3d& b, const Eigen::Vector3d& c,
                              const Eigen::Vector3d& d);

/// in_half_open_tetrahedron for x that is itself a knot, with coplanar_within_rounding in place
/// of exact coplanarity: a four that is flat within rounding contains nothing, and x counts as on
/// a face's plane where x and the face's knots are a flat four, so that the perturbation decides,
/// as make_frame decides that four (docs/simplex-splines.md, "Knots coplanar within rounding").
bool in_half_open_tetrahedron_at_knot(const Eigen::Vector3d& x, const Eigen::Vector3d& a, const Eigen::Vector3d& b,
                                      const Eigen::Vector3d& c, const Eigen::Vector3d& d);

/// The index of the first of knots[0..count) that equals x, or -1.
inline int knot_at(const Eigen::Vector3d& x, const Eigen::Vector3d* knots, int count) {
  for (int i = 0; i < count; ++i) {
    if (knots[i] == x) return i;
  }
  return -1;
}

/// Where x is the knot `knot` and that knot is w[j], its barycentric coordinates are exactly e_j;
/// the floating ones are off by the rounding times W's aspect ratio, and eq. 1 multiplies them by
/// children that can be large near a cloud (1/|det| of its small tetrahedra), so the exact ones
/// replace them. A knot repeated in W keeps the floating coordinates (W is then flat).
template <typename Indices>
inline void snap_to_knot(std::array<double, 4>& lambda, const Indices& w, int knot) {
  for (int j = 0; j < 4; ++j) {
    if (static_cast<int>(w[j]) == knot) {
      lambda = {0, 0, 0, 0};
      lambda[j] = 1;
      return;
    }
  }
}

/// The frame of four knots, or false when they are coplanar within rounding
/// (coplanar_within_rounding; checked only where the floating determinant is tiny relative to
/// the edge lengths).
bool make_frame(const Eigen::Vector3d& a, const Eigen::Vector3d& b, const Eigen::Vector3d& c,
                const Eigen::Vector3d& d, BarycentricFrame& frame);

/// The half-open rule for x with barycentric coordinates `lambda` with respect to (a, b, c, d):
/// decided by the signs of lambda where they are clearly away from 0, by the exact predicates
/// (in_half_open_tetrahedron, or in_half_open_tetrahedron_at_knot where x is a knot) otherwise. The rounding error of a barycentric coordinate is a few
/// units in the last place times the tetrahedron's aspect ratio; 1e-9 leaves room for aspect
/// ratios up to about 1e6.
inline bool half_open_contains(const std::array<double, 4>& lambda, const Eigen::Vector3d& x, bool x_is_knot,
                               const Eigen::Vector3d& a, const Eigen::Vector3d& b, const Eigen::Vector3d& c,
                               const Eigen::Vector3d& d) {
  constexpr double kUndecided = 1e-9;
  bool clearly_inside = true;
  for (const double l : lambda) {
    if (!(l >= -kUndecided)) return false;  // NaN too
    if (l <= kUndecided) clearly_inside = false;
  }
  if (clearly_inside) return true;
  return x_is_knot ? in_half_open_tetrahedron_at_knot(x, a, b, c, d) : in_half_open_tetrahedron(x, a, b, c, d);
}

/// The parameters s where every λ_j + s·μ_j >= 0 (the chord of a frame's tetrahedron along a line
/// with λ = λ(origin), μ = μ(direction)), intersected with [lo, hi]; empty when lo >= hi on return.
void clip_to_chord(const std::array<double, 4>& lambda, const std::array<double, 4>& mu, double& lo, double& hi);

/// Intersects [t_lo, t_hi] with the parameters where origin + t·direction lies in the box
/// [lo, hi] padded by 1e-6 of its diagonal: clipped ends then lie outside every support in the box,
/// so their boundary terms in eq. 16 are exactly 0. False when the intersection is empty.
bool clip_to_padded_box(const Eigen::Vector3d& lo, const Eigen::Vector3d& hi, const Eigen::Vector3d& origin,
                        const Eigen::Vector3d& direction, double& t_lo, double& t_hi);

/// The parameter about which eq. 16 is applied for W (any point of the line will do): the middle
/// of the chord of W's tetrahedron, where every λ_j >= 0 and the sum does not cancel, or the point
/// nearest W's centroid when the line misses it; within [lower, upper]. `lambda` and `mu` are
/// λ(origin) and μ(direction) in W's frame.
double recurrence_shift(const std::array<double, 4>& lambda, const std::array<double, 4>& mu,
                        const Eigen::Vector3d& centroid, const Eigen::Vector3d& origin,
                        const Eigen::Vector3d& direction, double lower, double upper);

/// ∫_lo^hi of M(origin + s·direction | subset) ds for a flat subset (all knots on one plane Π):
/// M is then a measure on Π, with area density M_2(y | subset)/(m + 1) (M_2 the bivariate simplex
/// spline of the knots in orthonormal coordinates of Π, m = #knots - 4; both are images of the
/// simplex measure, normalised as in simplex_spline.h), so the integral is that density at the
/// crossing y of the line with Π divided by |direction · unit normal|. 0 for collinear knots, a line
/// parallel to Π, or a crossing outside [lo, hi). Eq. 16 needs these: its integration by parts
/// takes the derivative of M as a distribution, whose flat parts are where M jumps.
double flat_line_integral(const Eigen::Vector3d* knots, KnotMask subset, const Eigen::Vector3d& origin,
                          const Eigen::Vector3d& direction, double lo, double hi);

/// How eq. 1 picks its four knots W in a subset.
enum class BarycentricChoice {
  /// Those whose half-open tetrahedron contains the point, the largest |det| among them (the
  /// largest |det| overall when none does): no cancellation, λ_j in [0, 1].
  kContainingThenLargest,
  /// The largest |det|: independent of the point, and every knot of the subset (so every point of
  /// its hull, the support) has |λ_j| <= 1.
  kLargest,
};

/// A test's own choice of W (returns false for "no independent four"); replaces the choice rule.
using CustomChoice = std::function<bool(KnotMask subset, std::array<int, 4>& w)>;

/// The knots a recurrence runs on, with the bounds that prune subsets whose support misses the
/// point or line: each knot's barycentric coordinates in a reference frame (the first four knots
/// of the largest |det|, or a DMS tetrahedron's vertices), so that a subset's hull lies in the
/// intersection of four slabs min..max of its knots' coordinates.
class KnotBinding {
 public:
  /// `reference` (four knot
  /// indices) fixes the pruning frame; empty picks the largest |det| four. Returns false when
  /// every four knots are coplanar (then every subset is flat and every spline 0).
  bool bind(const Eigen::Vector3d* knots, int count, BarycentricChoice choice,
            const std::array<int, 4>* reference = nullptr);

  const Eigen::Vector3d& knot(int i) const { return knots_[i]; }
  int count() const { return count_; }
  const BarycentricFrame& reference_frame() const { return reference_; }
  void set_custom_choice(const CustomChoice* custom) { custom_ = custom; }

  /// W and its frame for `subset` (at least 5 knots); `x` is the point for
  /// kContainingThenLargest (nullptr: kLargest). False when the subset is flat.
  bool choose(KnotMask subset, const Eigen::Vector3d* x, std::array<int, 4>& w, BarycentricFrame& frame) const;

  /// Whether the slabs of `subset` exclude the reference coordinates range lo..hi (per direction).
  bool excludes(KnotMask subset, const std::array<double, 4>& lo, const std::array<double, 4>& hi) const;

 private:
  bool choose_largest(KnotMask subset, const Eigen::Vector3d* x, std::array<int, 4>& w,
                      BarycentricFrame& frame) const;

  std::array<Eigen::Vector3d, kMaxRecurrenceKnots> knots_{};
  std::array<std::array<double, 4>, kMaxRecurrenceKnots> coordinates_{};
  int count_ = 0;
  BarycentricChoice choice_ = BarycentricChoice::kLargest;
  BarycentricFrame reference_;
  const CustomChoice* custom_ = nullptr;
};

/// A memo from subsets to one double, cleared in O(1) by a generation stamp.
class SubsetMemo {
 public:
  /// Room for about `expected` subsets without growing.
  void reserve(int expected);
  void clear();
  /// The value stored for `subset` in this generation, or nullptr.
  double* find(KnotMask subset);
  /// Stores `value` for `subset` (grows the table when it is 3/4 full).
  void store(KnotMask subset, double value);

 private:
  struct Entry {
    KnotMask mask = 0;
    std::uint32_t stamp = 0;
    double value = 0;
  };
  std::size_t slot(KnotMask subset) const {
    return (static_cast<std::size_t>(subset) * 0x9E3779B1u >> 7) & (entries_.size() - 1);
  }
  void grow();
  std::vector<Entry> entries_;
  std::uint32_t stamp_ = 1;
  std::size_t used_ = 0;
};

/// The number of subsets a DMS tetrahedron of degree n reaches (to size the memos).
int expected_dms_subsets(int degree);

/// M(x | subset) by eq. 1, memoised, for one point.
class PointRecurrence {
 public:
  void attach(const KnotBinding* binding, int expected_subsets);
  void set_point(const Eigen::Vector3d& x);
  double value(KnotMask subset);
  /// Value, gradient and (order 2) Hessian of M(x | subset) by eqs. 1-2.
  SimplexSplineJet jet(KnotMask subset, int order);
  /// D_v M(x | subset) by eq. 2.
  double directional_derivative(KnotMask subset, const Eigen::Vector3d& v);

 private:
  bool pruned(KnotMask subset) const { return binding_->excludes(subset, coordinates_, coordinates_); }
  Eigen::Vector3d gradient(KnotMask subset);

  const KnotBinding* binding_ = nullptr;
  SubsetMemo memo_;
  Eigen::Vector3d x_ = Eigen::Vector3d::Zero();
  int knot_ = -1;  // the knot that x is, or -1
  std::array<double, 4> coordinates_{};
};

/// ∫_a^b M(origin + t·direction | subset) dt by eq. 16 with boundary terms, memoised, for one line.
class LineRecurrence {
 public:
  void attach(const KnotBinding* binding, int expected_subsets);
  void set_line(const Eigen::Vector3d& origin, const Eigen::Vector3d& direction, double a, double b);
  double integral(KnotMask subset);

 private:
  double compute(KnotMask subset);

  const KnotBinding* binding_ = nullptr;
  SubsetMemo memo_;
  PointRecurrence at_lower_;
  PointRecurrence at_upper_;
  // The line re-parametrised about the point nearest the knots: origin_ + s·direction_, s in
  // [lower_, upper_] (clipped to the padded bounding box of the knots).
  Eigen::Vector3d origin_ = Eigen::Vector3d::Zero();
  Eigen::Vector3d direction_ = Eigen::Vector3d::Zero();
  double lower_ = 0;
  double upper_ = 0;
  bool empty_ = true;
  double constant_factor_ = 0;  // direction 0: the integral is (b - a)·M(origin)
  bool constant_ = false;
  std::array<double, 4> coordinates_lo_{};
  std::array<double, 4> coordinates_hi_{};
};

/// The subset's knot indices in increasing order; returns their number.
inline int subset_indices(KnotMask subset, std::array<int, kMaxRecurrenceKnots>& indices) {
  int count = 0;
  while (subset != 0) {
    indices[count++] = std::countr_zero(subset);
    subset &= subset - 1;
  }
  return count;
}

}  // namespace volspline::simplex_detail
