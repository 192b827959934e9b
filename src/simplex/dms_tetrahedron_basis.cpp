#include "volspline/simplex/dms_tetrahedron_basis.h"

#include <cmath>
#include <string>

#include "simplex_recurrence.h"
#include "volspline/core/error.h"

namespace volspline {
namespace simplex_detail {

// The scratch of one DmsTetrahedronBasis: the knots of the current tetrahedron and the memos.
class DmsRecurrenceState {
 public:
  explicit DmsRecurrenceState(int degree) : degree_(degree) {
    const int expected = expected_dms_subsets(degree);
    point_.attach(&binding_, expected);
    line_.attach(&binding_, expected);
  }

  // Copies the clouds into the binding; false when x (or the segment) is outside their bounding
  // box, where every basis function vanishes.
  void bind(const std::array<const Eigen::Vector3d*, 4>& clouds) {
    const int cloud_size = degree_ + 1;
    for (int c = 0; c < 4; ++c) {
      for (int i = 0; i < cloud_size; ++i) knots_[c * cloud_size + i] = clouds[c][i];
    }
    lo_ = knots_[0];
    hi_ = knots_[0];
    for (int i = 1; i < 4 * cloud_size; ++i) {
      lo_ = lo_.cwiseMin(knots_[i]);
      hi_ = hi_.cwiseMax(knots_[i]);
    }
    const std::array<int, 4> vertices = {0, cloud_size, 2 * cloud_size, 3 * cloud_size};
    binding_.bind(knots_.data(), 4 * cloud_size, BarycentricChoice::kDmsLastOfEachCloud, cloud_size, &vertices);
  }
  bool outside_box(const Eigen::Vector3d& x) const {
    return (x.array() < lo_.array()).any() || (x.array() > hi_.array()).any();
  }

  // The knots of V_β (eq. 4) and |d(p_i, q_j, r_k, s_l)| of eq. 5.
  KnotMask subset(const std::array<int, 4>& beta) const {
    const int cloud_size = degree_ + 1;
    KnotMask mask = 0;
    for (int c = 0; c < 4; ++c) mask |= ((KnotMask{1} << (beta[c] + 1)) - 1) << (c * cloud_size);
    return mask;
  }
  double scale(const std::array<int, 4>& beta) const {
    const int cloud_size = degree_ + 1;
    return std::abs(oriented_det(knots_[beta[0]], knots_[cloud_size + beta[1]], knots_[2 * cloud_size + beta[2]],
                                 knots_[3 * cloud_size + beta[3]]));
  }

  PointRecurrence& point() { return point_; }
  LineRecurrence& line() { return line_; }

 private:
  int degree_;
  std::array<Eigen::Vector3d, kMaxRecurrenceKnots> knots_{};
  Eigen::Vector3d lo_ = Eigen::Vector3d::Zero();
  Eigen::Vector3d hi_ = Eigen::Vector3d::Zero();
  KnotBinding binding_;
  PointRecurrence point_;
  LineRecurrence line_;
};

}  // namespace simplex_detail

std::vector<std::array<int, 4>> dms_multi_indices(int degree) {
  if (degree < 0) throw InvalidInput("DMS degree must be >= 0, got " + std::to_string(degree));
  std::vector<std::array<int, 4>> out;
  out.reserve(static_cast<std::size_t>((degree + 1) * (degree + 2) * (degree + 3) / 6));
  for (int i = degree; i >= 0; --i) {
    for (int j = degree - i; j >= 0; --j) {
      for (int k = degree - i - j; k >= 0; --k) out.push_back({i, j, k, degree - i - j - k});
    }
  }
  return out;
}

int dms_multi_index_position(const std::array<int, 4>& beta, int degree) {
  const auto [i, j, k, l] = beta;
  if (i < 0 || j < 0 || k < 0 || l < 0 || i + j + k + l != degree) {
    throw InvalidInput("multi-index (" + std::to_string(i) + ", " + std::to_string(j) + ", " + std::to_string(k) +
                       ", " + std::to_string(l) + ") does not have degree " + std::to_string(degree));
  }
  // The multi-indices before β: those with a larger i (C(n-i+2, 3) of them), then those with
  // this i and a larger j (C(n-i-j+1, 2)), then those with a larger k (l).
  const int a = degree - i;
  const int b = degree - i - j;
  return (a + 2) * (a + 1) * a / 6 + (b + 1) * b / 2 + l;
}

DmsTetrahedronBasis::DmsTetrahedronBasis(int degree) : degree_(degree) {
  if (degree < 0 || degree > kMaxSimplexSplineDegree) {
    throw InvalidInput("DMS degree must be 0.." + std::to_string(kMaxSimplexSplineDegree) + ", got " +
                       std::to_string(degree));
  }
  multi_indices_ = dms_multi_indices(degree);
  state_ = std::make_unique<simplex_detail::DmsRecurrenceState>(degree);
}

DmsTetrahedronBasis::~DmsTetrahedronBasis() = default;
DmsTetrahedronBasis::DmsTetrahedronBasis(DmsTetrahedronBasis&&) noexcept = default;
DmsTetrahedronBasis& DmsTetrahedronBasis::operator=(DmsTetrahedronBasis&&) noexcept = default;

void DmsTetrahedronBasis::evaluate(const Eigen::Vector3d& x, const std::array<const Eigen::Vector3d*, 4>& clouds,
                                   int order, DmsBasisValues& out) {
  if (order < 0 || order > 2) throw InvalidInput("derivative order must be 0, 1 or 2, got " + std::to_string(order));
  const std::size_t count = multi_indices_.size();
  out.values.assign(count, 0.0);
  out.gradients.assign(order >= 1 ? count : 0, Eigen::Vector3d::Zero());
  out.hessians.assign(order >= 2 ? count : 0, Eigen::Matrix3d::Zero());
  auto& state = *state_;
  state.bind(clouds);
  if (state.outside_box(x)) return;
  auto& point = state.point();
  point.set_point(x);
  for (std::size_t b = 0; b < count; ++b) {
    const auto& beta = multi_indices_[b];
    const SimplexSplineJet jet = point.jet(state.subset(beta), order);
    if (jet.value == 0 && order == 0) continue;
    const double scale = state.scale(beta);
    out.values[b] = scale * jet.value;
    if (order >= 1) out.gradients[b] = scale * jet.gradient;
    if (order >= 2) out.hessians[b] = scale * jet.hessian;
  }
}

void DmsTetrahedronBasis::line_integrals(const Eigen::Vector3d& origin, const Eigen::Vector3d& direction, double a,
                                         double b, const std::array<const Eigen::Vector3d*, 4>& clouds,
                                         std::vector<double>& out) {
  if (!(a <= b)) throw InvalidInput("line integral bounds must satisfy a <= b");
  const std::size_t count = multi_indices_.size();
  out.assign(count, 0.0);
  auto& state = *state_;
  state.bind(clouds);
  auto& line = state.line();
  line.set_line(origin, direction, a, b);
  for (std::size_t i = 0; i < count; ++i) {
    const auto& beta = multi_indices_[i];
    const double integral = line.integral(state.subset(beta));
    if (integral != 0) out[i] = state.scale(beta) * integral;
  }
}

}  // namespace volspline
