#pragma once
// Trivariate DMS spline volumes (Hua–He–Qin §3.2–3.3, eqs. 4–7): over a tetrahedral domain Ω with
// one knot cloud per vertex,
//   s(x) = Σ_{I ∈ Ω} Σ_{|β| = n} c_β^I N_β^I(x),   N_β^I = |d(p_i, q_j, r_k, s_l)| M(x | V_β^I),
// where each control vector c holds the geometry (x, y, z) and the attributes (g_1, ..., g_k) of
// eq. 7, so geometry and every material attribute are one spline over one domain.
//
// Decisions (docs/simplex-splines.md, "DMS spline volumes"):
// * Outside Ω the spline is zero: the basis functions' supports reach beyond Ω (boundary knot
//   clouds lie outside it, §3.2), but they only sum to 1 on Ω, so values there mean nothing.
//   Ω is closed: a point on ∂Ω is inside.
// * Degree 0 is the piecewise constant spline; a point on a face shared by two tetrahedra takes
//   the tetrahedron the half-open rule gives inside Ω, and a point of ∂Ω the tetrahedron that
//   contains it (the lowest index), so that the basis sums to 1 on the closed domain.
// * Shared control vectors: one per domain point ξ = (i p + j q + k r + l s) / n of the degree-n
//   lattice of each tetrahedron; two tetrahedra share those on their common face, edge or vertex
//   (the class of §3.2 and §4.2). They are numbered in order of first appearance, tetrahedra in
//   order and β in dms_multi_indices order, so that a model file needs no numbering of its own.
#include <array>
#include <functional>
#include <memory>
#include <span>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "volspline/mesh/tetrahedral_mesh.h"
#include "volspline/simplex/knot_clouds.h"

namespace volspline {

/// Which control vectors two tetrahedra of Ω have in common.
enum class DmsControlSharing {
  /// One control vector per domain point, shared along common faces, edges and vertices (§3.2:
  /// "sharing respective control points along common triangles"). Needs degree >= 1.
  Shared,
  /// One control vector per (tetrahedron, β), none shared (eq. 6 in general).
  PerTetrahedron,
};

/// A DMS spline volume: the domain, its knot clouds, the degree, and one control vector
/// (x, y, z, g_1, ..., g_k) per control row.
class DmsSplineVolume {
 public:
  /// A volume whose geometry is the identity s(x) = x (control points from the blossom of x, see
  /// set_column_from_blossom) and whose attributes are 0; for degree 0 the control point of a
  /// tetrahedron is its centroid.
  /// \throw InvalidInput if the domain is not a valid tetrahedral mesh (validate_tetrahedral_mesh),
  /// the clouds are not valid for it (validate_knot_clouds), sharing is Shared with degree 0, or
  /// an attribute name is empty, repeated, or one of "x", "y", "z".
  DmsSplineVolume(TetrahedralMesh domain, KnotClouds knots, DmsControlSharing sharing,
                  std::vector<std::string> attribute_names = {});

  int degree() const { return knots_.degree; }
  const TetrahedralMesh& domain() const { return domain_; }
  const KnotClouds& knots() const { return knots_; }
  DmsControlSharing sharing() const { return sharing_; }
  const std::vector<std::string>& attribute_names() const { return attribute_names_; }
  /// Entries of a control vector: 3 + the number of attributes.
  int dimension() const { return 3 + static_cast<int>(attribute_names_.size()); }
  /// Basis functions per tetrahedron: (n + 1)(n + 2)(n + 3) / 6.
  int basis_per_tetrahedron() const { return basis_per_tetrahedron_; }
  int control_vector_count() const { return static_cast<int>(control_.rows()); }
  /// The control row of N_β^I, β given by its position in dms_multi_indices(degree()).
  int control_row(int tetrahedron, int beta_position) const {
    return control_index_[static_cast<std::size_t>(tetrahedron) * basis_per_tetrahedron_ + beta_position];
  }
  /// One row per control vector: x, y, z, g_1, ..., g_k.
  const Eigen::MatrixXd& control_vectors() const { return control_; }
  /// For editing: moving control points (§4.2), changing control coefficients (§4.3). The shape
  /// (rows, columns) must not change.
  Eigen::MatrixXd& control_vectors() { return control_; }
  /// The domain point ξ = (i p + j q + k r + l s) / n of a control row (the centroid for degree 0):
  /// where §4.3 evaluates a skeleton field for a control coefficient.
  Eigen::Vector3d domain_point(int row) const;
  /// The column of an attribute in control_vectors().
  /// \throw InvalidInput naming the attributes the volume has.
  int attribute_column(const std::string& name) const;
  /// The (tetrahedron, β position) pairs of each control row (one for PerTetrahedron, all the
  /// tetrahedra around a shared domain point for Shared).
  const std::vector<std::vector<std::array<int, 2>>>& control_row_uses() const { return uses_; }

  /// Adds an attribute column (values 0). \throw InvalidInput as the constructor's names.
  void add_attribute(const std::string& name);

 private:
  TetrahedralMesh domain_;
  KnotClouds knots_;
  DmsControlSharing sharing_;
  std::vector<std::string> attribute_names_;
  int basis_per_tetrahedron_ = 1;
  std::vector<int> control_index_;
  std::vector<std::vector<std::array<int, 2>>> uses_;
  Eigen::MatrixXd control_;
};

/// The blossom arguments of N_β^I (Dahmen–Micchelli–Seidel 1992): p_0..p_{i−1}, q_0..q_{j−1},
/// r_0..r_{k−1}, s_0..s_{l−1} (n points; the last knot of each cloud never appears, which is why
/// the knots t_{v,n} do not change s, §3.2).
std::vector<Eigen::Vector3d> dms_blossom_arguments(const DmsSplineVolume& volume, int tetrahedron, int beta_position);

/// Sets column `column` of every control vector to F(arguments of its β), where F is the blossom
/// (the symmetric multi-affine polar form of n arguments) of a polynomial f of degree <= n: the
/// spline then reproduces f exactly on Ω. For Shared volumes the arguments of a shared domain
/// point are the same from every tetrahedron around it, so the assignment is well defined.
/// \throw InvalidInput if the column is out of range.
void set_column_from_blossom(DmsSplineVolume& volume, int column,
                             const std::function<double(std::span<const Eigen::Vector3d>)>& blossom);

}  // namespace volspline
