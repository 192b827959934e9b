#pragma once
// A trivariate C² function given by coefficients on a regular lattice: the field
//   f(x) = Σ_j c_j M_c((x − o)/h − j),  j ∈ [0, n_x) x [0, n_y) x [0, n_z),
// where M_c(x) = M(x + (1/2, 1/2, 5/2)) is the 7-direction box spline (seven_direction_box_spline.h)
// moved so that its support is centred on the origin. Coefficient c_j therefore "sits" at the
// lattice point o + h j, the centre of its basis function; this is where the paper's control
// values live (§7), and where quasi-interpolation samples (§6). (The issue writes the same
// field with the uncentred M; the shift (1/2, 1/2, 5/2) is absorbed in o.)
//
// The coefficients are finite, so f equals the infinite spline only where every basis function
// touching a point has its coefficient: the *domain* o + h [1.5, n − 2.5]³ (per axis). Evaluation
// outside it is refused, refinement keeps exactly this domain, and builders size lattices so the
// region of interest lies inside.
#include <array>
#include <functional>
#include <vector>

#include <Eigen/Core>

namespace volspline {

struct LatticeField {
  Eigen::Vector3d origin = Eigen::Vector3d::Zero();
  double spacing = 1.0;
  std::array<int, 3> size{0, 0, 0};
  /// size[0] * size[1] * size[2] coefficients, x fastest.
  std::vector<double> coefficients;

  /// A field of `size` zero coefficients. \throw InvalidInput if the spacing is not positive and
  /// finite, a size is below 5 (no domain) or the lattice has more than kMaxLatticePoints (2^26)
  /// points.
  LatticeField(const Eigen::Vector3d& origin, double spacing, std::array<int, 3> size);
  LatticeField() = default;

  std::size_t index(int i, int j, int k) const {
    return static_cast<std::size_t>(i) + size[0] * (static_cast<std::size_t>(j) + size[1] * static_cast<std::size_t>(k));
  }
  double& at(int i, int j, int k) { return coefficients[index(i, j, k)]; }
  double at(int i, int j, int k) const { return coefficients[index(i, j, k)]; }
  Eigen::Vector3d lattice_point(int i, int j, int k) const { return origin + spacing * Eigen::Vector3d(i, j, k); }

  /// The box where f is defined: o + h [1.5, n − 2.5] per axis.
  std::pair<Eigen::Vector3d, Eigen::Vector3d> domain() const;
  bool in_domain(const Eigen::Vector3d& x) const;

  /// f(x) with optional gradient and Hessian (world units), exactly: the BB form of the piece
  /// containing x is assembled from the 53 nearby coefficients, using the symmetry of M so that
  /// one table of 53 pieces serves all 24 tetrahedra (seven_direction_box_spline.h), and
  /// evaluated by de Casteljau. The fast path for scattered points (docs/performance.md).
  /// \throw InvalidInput if x is not in domain().
  double evaluate(const Eigen::Vector3d& x, Eigen::Vector3d* gradient = nullptr, Eigen::Matrix3d* hessian = nullptr) const;
  double value(const Eigen::Vector3d& x) const { return evaluate(x); }
};

/// Code paths of LatticeField::evaluate: the same arithmetic for vectors of 8, 4 or 2 lanes.
/// Best (what evaluate uses) is the widest this processor runs; Avx512 and Avx2 exist for GCC
/// on x86-64 only and may differ from Portable in the last bits (fused multiply-adds).
enum class EvaluationCode { Best, Avx512, Avx2, Portable };
bool evaluation_code_available(EvaluationCode code);
/// LatticeField::evaluate through a given code path (for tests and benchmarks).
/// \throw InvalidInput if this processor cannot run it, or as LatticeField::evaluate.
double evaluate_with_code(const LatticeField& field, EvaluationCode code, const Eigen::Vector3d& x, Eigen::Vector3d* gradient = nullptr,
                          Eigen::Matrix3d* hessian = nullptr);

/// f(x) as LatticeField::evaluate, but from the pieces of M on x's own tetrahedron (24 tables,
/// no symmetry used): the independent reference for tests and the baseline for benchmarks.
/// \throw InvalidInput if x is not in the field's domain.
double evaluate_by_own_pieces(const LatticeField& field, const Eigen::Vector3d& x, Eigen::Vector3d* gradient = nullptr,
                              Eigen::Matrix3d* hessian = nullptr);

/// The same function on the lattice of half the spacing (§7: copy each coefficient to its 8
/// children, then average along the four diagonal directions one after the other, i.e. the mask
/// 2⁻⁴ ∏_ξ (1 + z^ξ)). The fine lattice has 2n − 4 points per axis, origin o + (3/4) h (the
/// centred lattices are not nested: the fine points sit a quarter spacing off the coarse ones),
/// and the same domain. Fine coefficients that would need coefficients beyond the coarse lattice
/// are not produced. \throw InvalidInput if the result would have more than kMaxLatticePoints
/// points.
LatticeField refine(const LatticeField& field);
/// `levels` refinements. \throw InvalidInput if levels < 0, or as refine.
LatticeField refine(const LatticeField& field, int levels);

/// The exact values f(o + h (j + offset)) for every j whose point lies in the domain, where
/// offset ∈ (1/2)Z³ is (0,0,0) (lattice points), a face centre such as (1/2,1/2,0), or the cube
/// centre (1/2,1/2,1/2). Returned on the full coefficient array layout; entries whose point is
/// outside the domain are NaN. \throw InvalidInput for an offset outside [0,1)³ ∩ (1/2)Z³.
std::vector<double> point_values(const LatticeField& field, const Eigen::Vector3d& offset);

/// The weights w_m with f(o + h (j + offset)) = Σ_m w_m c_{j−m}: the centred spline's values at
/// m + offset. Offsets as in point_values.
std::vector<std::pair<std::array<int, 3>, double>> point_value_stencil(const Eigen::Vector3d& offset);

/// Quasi-interpolation (§6, Marsden's identity): c_j = p(x_j) − (5/24) Δ_h p(x_j) with Δ_h the
/// discrete Laplacian in lattice units (p at the six neighbours). Reproduces every cubic exactly
/// and approximates smooth functions to O(h⁴). `function` is sampled on the lattice and one layer
/// around it.
void quasi_interpolate(LatticeField& field, const std::function<double(const Eigen::Vector3d&)>& function);

/// A lattice whose domain contains the box [lo, hi], with lattice points on lo + h Z³:
/// origin lo − 2h, ceil((hi − lo)/h) + 5 points per axis, coefficients zero.
/// \throw InvalidInput for an empty box or bad spacing, or a lattice of more than
/// kMaxLatticePoints points.
LatticeField lattice_covering(const Eigen::Vector3d& lo, const Eigen::Vector3d& hi, double spacing);

/// Most lattice points a field may have (2^26, 512 MiB of coefficients).
inline constexpr std::size_t kMaxLatticePoints = std::size_t{1} << 26;

}  // namespace volspline
