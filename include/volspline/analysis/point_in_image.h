#pragma once
// Membership in the image of spline maps: is x in s_1(domain_1) u ... u s_n(domain_n) for maps
// s_i : R^D -> R^3? D = 3: trivariate solids, folded ones included (Joy–Duchaineau 1999, whose
// boundary is a superset of faces and the surface J = 0); D = 4: a solid swept along a path,
// s(u, v, w, t) (Conkey–Joy 2000), whose swept volume is the image. Trimming such supersets of
// a boundary to the boundary asks this question of points just off each piece.
//
// Outside is certified by the convex hull property: the domain is cut into cells (Bézier pieces,
// then de Casteljau halves), and every cell whose control points could enclose x is split until
// none does, where "enclose" is tested against the axis-aligned box of the control points and
// against the plane through x normal to x - s(p*) for the closest point s(p*) Newton found.
// Inside is a parameter p in the closed domain with |s(p) - x| <= tolerance (Gauss–Newton with
// minimum-norm steps, bounded to the domain). Undecided only when the split depth runs out with
// neither: x is then within Query::distance_bound (about 2^(-max_depth / D) of a Bézier piece's
// extent) of the image. docs/envelopes.md, "Membership in the image of a spline map".
#include <array>
#include <cstddef>
#include <cstdint>
#include <optional>
#include <vector>

#include <Eigen/Core>
#include <Eigen/Geometry>

#include "volspline/core/bernstein_tensor.h"
#include "volspline/spline/tensor_spline.h"

namespace volspline {

enum class ImageMembership {
  /// Some p in the closed domain has |s(p) - x| <= the tolerance (points on the boundary of the
  /// image are Inside).
  Inside,
  /// Certified: the control points of every cell were separated from x (by their box or by a
  /// plane through x), so by the convex hull property no s(p) equals x.
  Outside,
  /// Neither, down to the depth limit (or within max_cells): x is within a tiny distance of
  /// the image (Query::distance_bound).
  Undecided,
};

struct PointInImageOptions {
  /// Binary splits of a cell below its Bézier piece, all directions together, before a query
  /// gives up with Undecided; 0 means 26 D (about 26 halvings per direction: cells of 1.5e-8 of
  /// their piece, whose boxes then bound the distance to the image).
  int max_depth = 0;
  /// |s(p) - x| accepted for Inside, relative to the size of the model (the diagonal of the box
  /// of all control points).
  double tolerance = 1e-12;
  /// Cells one query may test before it gives up with Undecided: a point within about 1e-10 of
  /// the size outside a curved boundary can otherwise need exponentially many cells at the
  /// depth limit (a cell costs about a microsecond).
  int max_cells = 1 << 14;
  /// Memory for the cells split at construction (their Bernstein coefficients), so that queries
  /// start from small cells; every Bézier piece is at least one cell whatever this says.
  std::size_t precomputed_bytes = std::size_t{4} << 20;
};

/// The union of the images of one or more maps R^D -> R^3 (D = 3 or 4), polynomial or rational,
/// and the membership oracle for it. Immutable after construction: every const member may be
/// called from many threads at once (the scratch memory of a query is thread-local).
template <int D>
class SplineImage {
  static_assert(D == 3 || D == 4, "images of maps with 3 or 4 parameters");

 public:
  using Parameter = std::array<double, D>;

  /// A parameter of patch `patch` in its closed domain.
  struct Preimage {
    std::size_t patch = 0;
    Parameter parameter{};
  };

  /// Everything one query learned.
  struct Query {
    ImageMembership membership = ImageMembership::Undecided;
    /// Inside: the parameter found, with residual |s(p) - x|.
    std::optional<Preimage> preimage;
    double residual = 0;
    /// Undecided: the distance from x to the image is at most this (the smallest residual
    /// Newton reached, or the diagonal of the smallest cell box still containing x at the
    /// depth limit). 0 otherwise.
    double distance_bound = 0;
    /// Cells whose control points were tested against x, and Newton runs started.
    int cells_tested = 0;
    int newton_runs = 0;
  };

  /// Extracts the Bézier pieces of every patch, splits the largest cells until
  /// options.precomputed_bytes are used (or cells are 1/1024 of the model), and builds a
  /// bounding volume hierarchy over the cells. Rational pieces with weight-0 control points are
  /// degree-elevated until every weight is positive, so that the Euclidean control points bound
  /// the piece.
  /// \throw InvalidInput if there are no patches, a patch does not map into R^3, an option is
  /// out of range (max_depth < 0 or > 60 D, tolerance not positive and finite, max_cells < 1),
  /// or a weight stays zero after elevation.
  explicit SplineImage(std::vector<TensorSpline<D>> patches, PointInImageOptions options = {});

  /// Inside, Outside (certified) or Undecided. \throw InvalidInput if x is not finite.
  ImageMembership classify(const Eigen::Vector3d& x) const;
  /// A parameter p with |s(p) - x| <= tolerance() if classify(x) is Inside, else nothing.
  /// \throw InvalidInput if x is not finite.
  std::optional<Preimage> preimage(const Eigen::Vector3d& x) const;
  /// classify and preimage together, with the bound of an Undecided answer and the work done.
  /// \throw InvalidInput if x is not finite.
  Query query(const Eigen::Vector3d& x) const;
  /// query(x), starting with Newton from `hint` (a preimage of a point near x, say the last
  /// grid neighbour found inside): if that converges to |s(p) − x| <= tolerance() with p in the
  /// closed domain, x is Inside by the same criterion as the search's, and the search is
  /// skipped. Otherwise, or for a hint that names no patch, the full search. Outside and
  /// Undecided come from the search only, so the certificate is unchanged.
  Query query(const Eigen::Vector3d& x, const Preimage& hint) const;
  /// A parameter of `start`'s patch whose image lies within `distance` of x, by Newton towards
  /// the closest point of the image from `start` (clamped into the domain): for x on or just off
  /// the image's boundary, the (u, v, w, t) of the boundary point x stands for. Nothing if Newton
  /// ends farther (a start on another branch of the preimage). \throw InvalidInput if x is not
  /// finite, `start` names no patch or `distance` is not positive.
  std::optional<Preimage> preimage_near(const Eigen::Vector3d& x, const Preimage& start, double distance) const;

  const std::vector<TensorSpline<D>>& patches() const { return patches_; }
  /// The box of all control points (Euclidean, after elevation of weight-0 points).
  const Eigen::AlignedBox3d& bounding_box() const { return bounds_; }
  /// The diagonal of bounding_box() (1 for an image that is a single point).
  double size() const { return size_; }
  /// The absolute residual accepted for Inside: options.tolerance * size().
  double tolerance() const { return tolerance_; }
  int max_depth() const { return max_depth_; }
  /// A number no other SplineImage made in this process has (for caches keyed by image).
  std::uint64_t generation() const { return generation_; }
  /// Cells kept from construction (the leaves of the precomputed splitting).
  std::size_t precomputed_cells() const { return cells_.size(); }

 private:
  struct Cell {
    std::size_t patch = 0;
    /// The cell's parameter box inside its patch's domain.
    Parameter low{}, high{};
    int depth = 0;
    /// Homogeneous Bernstein coefficients (x, y, z, and w for a rational patch).
    BernsteinTensor<D> coefficients;
    /// The box of the Euclidean control points, and the rounding margin it is widened by.
    Eigen::AlignedBox3d box;
    double margin = 0;
  };
  struct Node {
    Eigen::AlignedBox3d box;
    /// Children (internal node) or a range of cell_order_ (leaf: right < 0, cells [left, left + count)).
    int left = -1, right = -1, count = 0;
  };
  struct Search;

  void precompute(std::vector<Cell> roots, std::size_t budget);
  int build_hierarchy(int first, int count);
  void search(const Eigen::Vector3d& x, Query& result) const;

  std::vector<TensorSpline<D>> patches_;
  int max_depth_ = 0;
  std::uint64_t generation_ = 0;
  int max_cells_ = 0;
  double size_ = 1;
  double tolerance_ = 0;
  Eigen::AlignedBox3d bounds_;
  std::vector<Cell> cells_;
  std::vector<int> cell_order_;
  std::vector<Node> nodes_;
};

extern template class SplineImage<3>;
extern template class SplineImage<4>;

}  // namespace volspline
