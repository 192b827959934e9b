#include "volspline/simplex/dms_tetrahedron_basis.h"

#include <algorithm>
#include <cmath>
#include <string>

#include "dms_recurrence_plan.h"
#include "volspline/core/error.h"

namespace volspline {
namespace simplex_detail {

// The scratch of one DmsTetrahedronBasis: compiled plans of the last few tetrahedra (a plan
// depends only on the knots, so points of one tetrahedron in a row reuse it), node values.
class DmsRecurrenceState {
 public:
  static constexpr int kCachedPlans = 8;

  explicit DmsRecurrenceState(int degree) : degree_(degree), plans_(kCachedPlans) {}

  const DmsRecurrencePlan& plan(const std::array<const Eigen::Vector3d*, 4>& clouds,
                                const std::vector<std::array<int, 4>>& betas) {
    const int cloud_size = degree_ + 1;
    for (int c = 0; c < 4; ++c) std::copy(clouds[c], clouds[c] + cloud_size, knots_.begin() + c * cloud_size);
    for (int k = 0; k < kCachedPlans; ++k) {
      const int i = (last_ + kCachedPlans - k) % kCachedPlans;
      if (plans_[i].matches(knots_.data())) {
        last_ = i;
        return plans_[i];
      }
    }
    last_ = (last_ + 1) % kCachedPlans;
    DmsRecurrencePlan& fresh = plans_[last_];
    fresh.build(knots_.data(), degree_, betas, index_);
    return fresh;
  }

  // Room for the node values of `plan` (grows only for a plan larger than any before).
  void fit(const DmsRecurrencePlan& plan) {
    if (node_values_.size() < static_cast<std::size_t>(plan.size())) node_values_.resize(plan.size());
    const std::size_t scratch = 2 * static_cast<std::size_t>(plan.size()) + static_cast<std::size_t>(plan.work_size());
    if (scratch_.size() < scratch) scratch_.resize(scratch);
  }

  double* node_values() { return node_values_.data(); }
  double* scratch() { return scratch_.data(); }

  // The memoised recurrence over the knots of `plan` with W containing x, for points that are
  // knots (evaluate_plan).
  PointRecurrence& recurrence_at(const DmsRecurrencePlan& plan, const Eigen::Vector3d& x) {
    const int cloud_size = degree_ + 1;
    const std::array<int, 4> vertices = {0, cloud_size, 2 * cloud_size, 3 * cloud_size};
    binding_.bind(plan.knots(), plan.knot_count(), BarycentricChoice::kContainingThenLargest, &vertices);
    if (!attached_) {
      recurrence_.attach(&binding_, expected_dms_subsets(degree_));
      attached_ = true;
    }
    recurrence_.set_point(x);
    return recurrence_;
  }

 private:
  int degree_;
  std::vector<DmsRecurrencePlan> plans_;
  int last_ = 0;
  std::array<Eigen::Vector3d, kMaxRecurrenceKnots> knots_{};
  std::vector<double> node_values_;
  std::vector<double> scratch_;
  SubsetMemo index_;
  KnotBinding binding_;
  PointRecurrence recurrence_;
  bool attached_ = false;
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
  if (!x.allFinite()) throw InvalidInput("the point must be finite");
  evaluate_plan(x, state_->plan(clouds, multi_indices_), order, out);
}

void DmsTetrahedronBasis::evaluate(const Eigen::Vector3d& x, const DmsTetrahedronPlan& plan, int order,
                                   DmsBasisValues& out) {
  if (order < 0 || order > 2) throw InvalidInput("derivative order must be 0, 1 or 2, got " + std::to_string(order));
  if (!x.allFinite()) throw InvalidInput("the point must be finite");
  evaluate_plan(x, checked(plan), order, out);
}

void DmsTetrahedronBasis::evaluate(const Eigen::Vector3d& x, const DmsTetrahedronPlan& plan, int order,
                                   DmsBasisValues& out, DmsLastKnotFrames& frames) {
  if (order < 0 || order > 2) throw InvalidInput("derivative order must be 0, 1 or 2, got " + std::to_string(order));
  if (!x.allFinite()) throw InvalidInput("the point must be finite");
  const simplex_detail::DmsRecurrencePlan& p = checked(plan);
  if (!plan.has_last_knot_frames()) throw InvalidInput("the DMS plan has a flat four of last knots (p_i, q_j, r_k, s_l)");
  const std::size_t count = multi_indices_.size();
  frames.lambdas.resize(count);
  frames.gradients.resize(order >= 1 ? count : 0);
  if (order == 1 && !p.outside_box(x) && p.knot_at(x) < 0) {
    // The common case in one pass: W_β is the four of V_β's node, so ∇λ(W_β) serves both eq. 2
    // for ∇N_β and the frame.
    out.values.resize(count);
    out.gradients.resize(count);
    out.hessians.clear();
    state_->fit(p);
    double* m = state_->node_values();
    double* d = state_->scratch();
    p.values(x, m, -1, d);
    const int n = degree_;
    for (std::size_t b = 0; b < count; ++b) {
      const int top = p.top(static_cast<int>(b));
      const int four = p.node_four(top);
      const double scale = p.scale(static_cast<int>(b));
      const std::array<Eigen::Vector3d, 4> g = p.four_lambda_gradients(four);
      frames.lambdas[b] = p.four_lambda(four, d);
      frames.gradients[b] = g;
      out.values[b] = scale * m[top];
      if (n == 0) {
        out.gradients[b].setZero();
        continue;
      }
      const auto& node = p.interior(top);
      out.gradients[b] = (scale * n) * (g[0] * m[node.child[0]] + g[1] * m[node.child[1]] + g[2] * m[node.child[2]] +
                                         g[3] * m[node.child[3]]);
    }
    return;
  }
  evaluate_plan(x, p, order, out);
  if (p.outside_box(x)) {
    const Eigen::Vector3d zero = Eigen::Vector3d::Zero();
    std::fill(frames.lambdas.begin(), frames.lambdas.end(), std::array<double, 4>{});
    std::fill(frames.gradients.begin(), frames.gradients.end(), std::array<Eigen::Vector3d, 4>{zero, zero, zero, zero});
    return;
  }
  // evaluate_plan left the face determinants of x in the scratch, except at a knot.
  double* d = state_->scratch();
  if (p.knot_at(x) >= 0) {
    state_->fit(p);
    d = state_->scratch();
    p.face_determinants(x, d);
  }
  for (std::size_t b = 0; b < count; ++b) {
    const int four = p.node_four(p.top(static_cast<int>(b)));
    frames.lambdas[b] = p.four_lambda(four, d);
    if (order >= 1) frames.gradients[b] = p.four_lambda_gradients(four);
  }
}

const simplex_detail::DmsRecurrencePlan& DmsTetrahedronBasis::checked(const DmsTetrahedronPlan& plan) const {
  if (plan.degree() != degree_ || !plan.plan_) {
    throw InvalidInput("DMS plan of degree " + std::to_string(plan.degree()) + " for a basis of degree " +
                       std::to_string(degree_));
  }
  return *plan.plan_;
}

void DmsTetrahedronBasis::evaluate_plan(const Eigen::Vector3d& x, const simplex_detail::DmsRecurrencePlan& plan,
                                        int order, DmsBasisValues& out) {
  const std::size_t count = multi_indices_.size();
  out.values.assign(count, 0.0);
  out.gradients.assign(order >= 1 ? count : 0, Eigen::Vector3d::Zero());
  out.hessians.assign(order >= 2 ? count : 0, Eigen::Matrix3d::Zero());
  if (plan.outside_box(x)) return;
  if (plan.knot_at(x) >= 0) {
    // At a knot the plan's fixed W, which need not contain x, make eq. 1 cancel among children as
    // large as 1/|det| of a cloud's small tetrahedra; W containing x (all λ_j >= 0, exactly e_j
    // where x is one of W's knots) does not (docs/simplex-splines.md, "Knots coplanar within
    // rounding"). Only at knots: choosing W per subset and point is slower.
    auto& recurrence = state_->recurrence_at(plan, x);
    for (std::size_t b = 0; b < count; ++b) {
      const double scale = plan.scale(static_cast<int>(b));
      const SimplexSplineJet jet = recurrence.jet(plan.top_mask(static_cast<int>(b)), order);
      out.values[b] = scale * jet.value;
      if (order >= 1) out.gradients[b] = scale * jet.gradient;
      if (order >= 2) out.hessians[b] = scale * jet.hessian;
    }
    return;
  }
  state_->fit(plan);
  double* m = state_->node_values();
  plan.values(x, m, -1, state_->scratch());
  const int n = degree_;
  for (std::size_t b = 0; b < count; ++b) {
    const int top = plan.top(static_cast<int>(b));
    const double scale = plan.scale(static_cast<int>(b));
    out.values[b] = scale * m[top];
    if (order == 0 || n == 0 || !plan.has_frame(top)) continue;
    const auto& node = plan.interior(top);
    const auto g = plan.lambda_gradients(top);
    // Eq. 2: ∇M(V) = n Σ_j ∇λ_j M(V \ w_j); for the Hessian eq. 2 again on each M(V \ w_j).
    Eigen::Vector3d gradient = Eigen::Vector3d::Zero();
    Eigen::Matrix3d hessian = Eigen::Matrix3d::Zero();
    for (int j = 0; j < 4; ++j) {
      const int c = node.child[j];
      gradient += g[j] * m[c];
      if (order == 2 && n >= 2 && plan.has_frame(c)) {
        const auto& child = plan.interior(c);
        const auto gc = plan.lambda_gradients(c);
        Eigen::Vector3d child_gradient = Eigen::Vector3d::Zero();
        for (int k = 0; k < 4; ++k) child_gradient += gc[k] * m[child.child[k]];
        hessian += g[j] * child_gradient.transpose();
      }
    }
    out.gradients[b] = (scale * n) * gradient;
    if (order == 2) out.hessians[b] = (0.5 * scale * n * (n - 1)) * (hessian + hessian.transpose());
  }
}

void DmsTetrahedronBasis::line_integrals(const Eigen::Vector3d& origin, const Eigen::Vector3d& direction, double a,
                                         double b, const std::array<const Eigen::Vector3d*, 4>& clouds,
                                         std::vector<double>& out) {
  if (!(a <= b)) throw InvalidInput("line integral bounds must satisfy a <= b");
  if (!origin.allFinite() || !direction.allFinite()) throw InvalidInput("the line must be finite");
  line_integrals_plan(origin, direction, a, b, state_->plan(clouds, multi_indices_), out);
}

void DmsTetrahedronBasis::line_integrals(const Eigen::Vector3d& origin, const Eigen::Vector3d& direction, double a,
                                         double b, const DmsTetrahedronPlan& plan, std::vector<double>& out) {
  if (!(a <= b)) throw InvalidInput("line integral bounds must satisfy a <= b");
  if (!origin.allFinite() || !direction.allFinite()) throw InvalidInput("the line must be finite");
  line_integrals_plan(origin, direction, a, b, checked(plan), out);
}

void DmsTetrahedronBasis::line_integrals_plan(const Eigen::Vector3d& origin, const Eigen::Vector3d& direction,
                                              double a, double b, const simplex_detail::DmsRecurrencePlan& plan,
                                              std::vector<double>& out) {
  const std::size_t count = multi_indices_.size();
  out.assign(count, 0.0);
  state_->fit(plan);
  double* integrals = state_->node_values();
  plan.line_integrals(origin, direction, a, b, integrals, state_->scratch());
  for (std::size_t i = 0; i < count; ++i) {
    const int top = plan.top(static_cast<int>(i));
    if (integrals[top] != 0) out[i] = plan.scale(static_cast<int>(i)) * integrals[top];
  }
}

DmsTetrahedronPlan::DmsTetrahedronPlan() = default;
DmsTetrahedronPlan::~DmsTetrahedronPlan() = default;
DmsTetrahedronPlan::DmsTetrahedronPlan(DmsTetrahedronPlan&&) noexcept = default;
DmsTetrahedronPlan& DmsTetrahedronPlan::operator=(DmsTetrahedronPlan&&) noexcept = default;

DmsTetrahedronPlan::DmsTetrahedronPlan(int degree, const std::array<const Eigen::Vector3d*, 4>& clouds) {
  if (degree < 0 || degree > kMaxSimplexSplineDegree) {
    throw InvalidInput("DMS degree must be 0.." + std::to_string(kMaxSimplexSplineDegree) + ", got " +
                       std::to_string(degree));
  }
  std::array<Eigen::Vector3d, simplex_detail::kMaxRecurrenceKnots> knots{};
  for (int c = 0; c < 4; ++c) std::copy(clouds[c], clouds[c] + degree + 1, knots.begin() + c * (degree + 1));
  plan_ = std::make_unique<simplex_detail::DmsRecurrencePlan>();
  simplex_detail::SubsetMemo index;
  const std::vector<std::array<int, 4>> betas = dms_multi_indices(degree);
  plan_->build(knots.data(), degree, betas, index);
  plan_->shrink_to_fit();
  degree_ = degree;
  last_knot_frames_ = true;
  for (std::size_t b = 0; b < betas.size(); ++b) {
    const int four = plan_->node_four(plan_->top(static_cast<int>(b)));
    bool last_knots = four >= 0 && !plan_->four_is_flat(four);
    for (int c = 0; c < 4 && last_knots; ++c)
      last_knots = plan_->four_knots(four)[static_cast<std::size_t>(c)] == c * (degree + 1) + betas[b][static_cast<std::size_t>(c)];
    last_knot_frames_ = last_knots && last_knot_frames_;
  }
}

bool DmsTetrahedronPlan::matches(const std::array<const Eigen::Vector3d*, 4>& clouds) const {
  if (!plan_) return false;
  std::array<Eigen::Vector3d, simplex_detail::kMaxRecurrenceKnots> knots{};
  for (int c = 0; c < 4; ++c) std::copy(clouds[c], clouds[c] + degree_ + 1, knots.begin() + c * (degree_ + 1));
  return plan_->matches(knots.data());
}

void DmsTetrahedronPlan::prefetch() const {
  if (plan_) plan_->prefetch();
}

std::size_t DmsTetrahedronPlan::memory_bytes() const {
  return sizeof(*this) + (plan_ ? plan_->memory_bytes() : 0);
}

}  // namespace volspline
