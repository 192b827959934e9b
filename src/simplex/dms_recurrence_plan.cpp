#include "dms_recurrence_plan.h"

#include <algorithm>
#include <bit>
#include <cmath>
#include <limits>
#include <string>

#include "volspline/core/error.h"

namespace volspline::simplex_detail {
namespace {

// W for a subset of a DMS tetrahedron's knots (cloud c holds knots c(n+1)..c(n+1)+n): the last
// knot of each cloud, (p_i, q_j, r_k, s_l) for V_β — non-degenerate by the DMS conditions (§3.2)
// and, with the sub-knots near their vertex, close to the largest |det| of the subset. A subset
// that misses a cloud completes the last knots of its clouds greedily: the knot farthest from the
// point, line or plane of those taken (column pivoting, a cheap stand-in for the largest |det|:
// the last pick has |λ| <= 1 at every knot of the subset). The four of largest |det| when the
// greedy four are degenerate (a flat subset then has none).
bool choose_dms_knots(const std::array<Eigen::Vector3d, kMaxRecurrenceKnots>& knots, int cloud_size, KnotMask subset,
                      std::array<int, 4>& w, BarycentricFrame& frame, const KnotBinding& fallback) {
  const KnotMask cloud = (KnotMask{1} << cloud_size) - 1;
  int taken = 0;
  KnotMask used = 0;
  for (int c = 0; c < 4; ++c) {
    const KnotMask members = (subset >> (c * cloud_size)) & cloud;
    if (members != 0) {
      w[taken] = c * cloud_size + 31 - std::countl_zero(members);
      used |= KnotMask{1} << w[taken];
      ++taken;
    }
  }
  for (; taken < 4; ++taken) {
    double best = 0;
    int pick = -1;
    for (KnotMask rest = subset & ~used; rest != 0; rest &= rest - 1) {
      const int t = std::countr_zero(rest);
      const Eigen::Vector3d r = knots[t] - knots[w[0]];
      double measure = 0;
      if (taken == 1) {
        measure = r.squaredNorm();
      } else if (taken == 2) {
        measure = (knots[w[1]] - knots[w[0]]).cross(r).squaredNorm();
      } else {
        const double det = (knots[w[1]] - knots[w[0]]).cross(knots[w[2]] - knots[w[0]]).dot(r);
        measure = det * det;
      }
      if (measure > best) {
        best = measure;
        pick = t;
      }
    }
    if (pick < 0) break;
    w[taken] = pick;
    used |= KnotMask{1} << pick;
  }
  if (taken == 4 && make_frame(knots[w[0]], knots[w[1]], knots[w[2]], knots[w[3]], frame)) return true;
  return fallback.choose(subset, nullptr, w, frame);
}

}  // namespace

void DmsRecurrencePlan::build(const Eigen::Vector3d* knots, int degree, const std::vector<std::array<int, 4>>& betas,
                              SubsetMemo& index) {
  const int cloud_size = degree + 1;
  knot_count_ = 4 * cloud_size;
  for (int i = 0; i < knot_count_; ++i) {
    if (!knots[i].allFinite()) {
      throw InvalidInput("knot " + std::to_string(i % cloud_size) + " of cloud " + std::to_string(i / cloud_size) +
                         " is not finite");
    }
  }
  built_ = false;
  std::copy(knots, knots + knot_count_, knots_.begin());
  lo_ = knots_[0];
  hi_ = knots_[0];
  for (int i = 1; i < knot_count_; ++i) {
    lo_ = lo_.cwiseMin(knots_[i]);
    hi_ = hi_.cwiseMax(knots_[i]);
  }
  cloud_size_ = cloud_size;
  // The largest-|det| choice only for degenerate greedy picks (invalid or repeated knots).
  KnotBinding binding;
  const std::array<int, 4> vertices = {0, cloud_size, 2 * cloud_size, 3 * cloud_size};
  binding.bind(knots_.data(), knot_count_, BarycentricChoice::kLargest, &vertices);
  index.reserve(expected_dms_subsets(degree));
  index.clear();
  leaves_.clear();
  interior_.clear();
  tops_.clear();
  scales_.clear();
  for (const auto& beta : betas) {
    KnotMask mask = 0;
    for (int c = 0; c < 4; ++c) mask |= ((KnotMask{1} << (beta[c] + 1)) - 1) << (c * cloud_size);
    tops_.push_back(add(mask, binding, index));
    scales_.push_back(std::abs(oriented_det(knots_[beta[0]], knots_[cloud_size + beta[1]],
                                            knots_[2 * cloud_size + beta[2]], knots_[3 * cloud_size + beta[3]])));
  }
  // Number leaves first, then the larger subsets (which already come children first).
  const int leaf_count = this->leaf_count();
  const auto number = [leaf_count](int code) { return code < 0 ? -1 - code : leaf_count + code; };
  for (PlanNode& n : interior_) {
    if (!n.flat) {
      for (auto& c : n.child) c = number(c);
    }
  }
  for (int& t : tops_) t = number(t);
  built_ = true;
}

bool DmsRecurrencePlan::matches(const Eigen::Vector3d* knots) const {
  return built_ && std::equal(knots, knots + knot_count_, knots_.begin());
}

// Depth first, so that a node's children precede it; returns the node of `subset`.
int DmsRecurrencePlan::add(KnotMask subset, const KnotBinding& binding, SubsetMemo& index) {
  if (const double* known = index.find(subset)) return static_cast<int>(*known);
  std::array<int, 4> w{};
  int code;
  const int knots_in_subset = std::popcount(subset);
  if (knots_in_subset == 4) {
    KnotMask rest = subset;
    for (int& k : w) {
      k = std::countr_zero(rest);
      rest &= rest - 1;
    }
    BarycentricFrame frame;
    PlanLeaf leaf{};
    if (make_frame(knots_[w[0]], knots_[w[1]], knots_[w[2]], knots_[w[3]], frame)) {
      leaf.origin = {frame.origin.x(), frame.origin.y(), frame.origin.z()};
      for (int j = 0; j < 3; ++j) {
        for (int k = 0; k < 3; ++k) leaf.g[3 * j + k] = frame.g[j + 1][k];
      }
      leaf.inverse_volume = 1.0 / std::abs(frame.det);
    }
    leaf.mask = subset;
    for (int j = 0; j < 4; ++j) leaf.w[j] = static_cast<std::int8_t>(w[j]);
    code = -1 - static_cast<int>(leaves_.size());
    leaves_.push_back(leaf);
  } else {
    PlanNode node;
    node.mask = subset;
    node.degree = static_cast<std::int8_t>(knots_in_subset - 4);
    node.flat = !choose_dms_knots(knots_, cloud_size_, subset, w, node.frame, binding);
    if (!node.flat) {
      for (int j = 0; j < 4; ++j) node.child[j] = add(subset & ~(KnotMask{1} << w[j]), binding, index);
    }
    for (int j = 0; j < 4; ++j) node.w[j] = static_cast<std::int8_t>(w[j]);
    code = static_cast<int>(interior_.size());
    interior_.push_back(node);
  }
  index.store(subset, code);
  return code;
}

void DmsRecurrencePlan::values(const Eigen::Vector3d& x, double* out, int knot) const {
  constexpr double kUndecided = 1e-9;  // as half_open_contains
  const int leaf_count = this->leaf_count();
  // At a knot, faces of other knots are decided as make_frame decides their fours (flat within
  // rounding); elsewhere exactly.
  for (int i = 0; i < leaf_count; ++i) {
    const PlanLeaf& f = leaves_[i];
    const auto l = f.lambda(x);
    const double smallest = std::min(std::min(l[0], l[1]), std::min(l[2], l[3]));
    if (smallest > kUndecided) {
      out[i] = f.inverse_volume;
    } else if (!(smallest >= -kUndecided) || f.inverse_volume == 0) {
      out[i] = 0;
    } else {
      const Eigen::Vector3d& a = knots_[f.w[0]];
      const Eigen::Vector3d& b = knots_[f.w[1]];
      const Eigen::Vector3d& c = knots_[f.w[2]];
      const Eigen::Vector3d& d = knots_[f.w[3]];
      const bool inside =
          knot >= 0 ? in_half_open_tetrahedron_at_knot(x, a, b, c, d) : in_half_open_tetrahedron(x, a, b, c, d);
      out[i] = inside ? f.inverse_volume : 0.0;
    }
  }
  double* interior_out = out + leaf_count;
  for (const PlanNode& n : interior_) {
    double v = 0;
    if (!n.flat) {
      const auto l = n.frame.lambda(x);
      for (int j = 0; j < 4; ++j) v += l[j] * out[n.child[j]];
    }
    *interior_out++ = v;
  }
}

void DmsRecurrencePlan::line_integrals(const Eigen::Vector3d& origin, const Eigen::Vector3d& direction, double a,
                                       double b, double* out, double* scratch) const {
  const int count = size();
  std::fill(out, out + count, 0.0);
  if (!(a < b)) return;
  double* at_lower = scratch;
  double* at_upper = scratch + count;
  if (direction.squaredNorm() == 0) {
    values(origin, at_lower);
    for (int i = 0; i < count; ++i) out[i] = at_lower[i] == 0 ? 0.0 : (b - a) * at_lower[i];
    return;
  }
  // Clipped to the padded bounding box and re-parametrised about the middle (LineRecurrence).
  double t_lo = a;
  double t_hi = b;
  if (!clip_to_padded_box(lo_, hi_, origin, direction, t_lo, t_hi)) return;
  const double middle = 0.5 * (t_lo + t_hi);
  const Eigen::Vector3d o = origin + middle * direction;
  const double lower = t_lo - middle;
  const double upper = t_hi - middle;
  // The ends of a line clipped by the padded box lie outside every support: no values to compute.
  for (const auto& [end, at] : {std::pair{o + lower * direction, at_lower}, std::pair{o + upper * direction, at_upper}}) {
    if (outside_box(end)) {
      std::fill(at, at + count, 0.0);
    } else {
      values(end, at);
    }
  }
  const int leaf_count = this->leaf_count();
  for (int i = 0; i < leaf_count; ++i) {
    const PlanLeaf& f = leaves_[i];
    if (f.inverse_volume == 0) {
      out[i] = flat_line_integral(knots_.data(), f.mask, o, direction, lower, upper);
      continue;
    }
    double s_lo = lower;
    double s_hi = upper;
    clip_to_chord(f.lambda(o), f.mu(direction), s_lo, s_hi);
    out[i] = s_hi > s_lo ? (s_hi - s_lo) * f.inverse_volume : 0.0;
  }
  for (int i = leaf_count; i < count; ++i) {
    const PlanNode& n = interior(i);
    if (n.flat) {
      out[i] = flat_line_integral(knots_.data(), n.mask, o, direction, lower, upper);
      continue;
    }
    // Eq. 16 about the middle of the chord of W's tetrahedron (recurrence_shift).
    const auto m = n.frame.mu(direction);
    const auto l0 = n.frame.lambda(o);
    const Eigen::Vector3d centroid = 0.25 * (knots_[n.w[0]] + knots_[n.w[1]] + knots_[n.w[2]] + knots_[n.w[3]]);
    const double shift = recurrence_shift(l0, m, centroid, o, direction, lower, upper);
    double sum = 0;
    for (int j = 0; j < 4; ++j) sum += (l0[j] + shift * m[j]) * out[n.child[j]];
    const double boundary = (upper - shift) * at_upper[i] - (lower - shift) * at_lower[i];
    out[i] = (n.degree * sum + boundary) / (n.degree + 1);
  }
}

}  // namespace volspline::simplex_detail
