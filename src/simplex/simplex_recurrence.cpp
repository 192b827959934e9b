#include "simplex_recurrence.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace volspline::simplex_detail {
namespace {

KnotMask bit(int i) { return KnotMask{1} << i; }

// Barycentric coordinates of a point are compared with those of knots up to this margin, far
// above their rounding, so that pruning never drops a subset whose support holds the point.
constexpr double kPruneMargin = 1e-9;

}  // namespace

bool KnotBinding::bind(const Eigen::Vector3d* knots, int count, BarycentricChoice choice,
                       const std::array<int, 4>* reference) {
  count_ = count;
  choice_ = choice;
  std::copy(knots, knots + count, knots_.begin());
  bool found = false;
  if (reference != nullptr) {
    const auto& r = *reference;
    found = make_frame(knots_[r[0]], knots_[r[1]], knots_[r[2]], knots_[r[3]], reference_);
  }
  if (!found) {
    std::array<int, 4> w{};
    const KnotMask all = count >= 32 ? ~KnotMask{0} : (bit(count) - 1);
    found = choose_largest(all, nullptr, w, reference_);
  }
  if (!found) {
    // Every four knots are coplanar: every subset is flat. The unit frame keeps excludes() defined.
    reference_ = BarycentricFrame{};
    reference_.g[1] = Eigen::Vector3d::UnitX();
    reference_.g[2] = Eigen::Vector3d::UnitY();
    reference_.g[3] = Eigen::Vector3d::UnitZ();
    reference_.g[0] = -Eigen::Vector3d::Ones();
    reference_.det = 1;
  }
  for (int i = 0; i < count; ++i) coordinates_[i] = reference_.lambda(knots_[i]);
  return found;
}

bool KnotBinding::excludes(KnotMask subset, const std::array<double, 4>& lo, const std::array<double, 4>& hi) const {
  std::array<double, 4> low;
  std::array<double, 4> high;
  low.fill(std::numeric_limits<double>::infinity());
  high.fill(-std::numeric_limits<double>::infinity());
  for (KnotMask rest = subset; rest != 0; rest &= rest - 1) {
    const auto& c = coordinates_[std::countr_zero(rest)];
    for (int k = 0; k < 4; ++k) {
      low[k] = std::min(low[k], c[k]);
      high[k] = std::max(high[k], c[k]);
    }
  }
  for (int k = 0; k < 4; ++k) {
    if (lo[k] > high[k] + kPruneMargin || hi[k] < low[k] - kPruneMargin) return true;
  }
  return false;
}

bool KnotBinding::choose_largest(KnotMask subset, const Eigen::Vector3d* x, std::array<int, 4>& w,
                                 BarycentricFrame& frame) const {
  std::array<int, kMaxRecurrenceKnots> index{};
  const int m = subset_indices(subset, index);
  // Every four with its |det|; at most C(9, 4) = 126 when x matters (single splines).
  struct Candidate {
    double size;
    std::array<int, 4> w;
  };
  constexpr int kMaxCandidates = 126;
  std::array<Candidate, kMaxCandidates> candidates;
  const bool rank_by_containment = x != nullptr && m <= 9;
  int count = 0;
  double best = 0;
  for (int i0 = 0; i0 < m; ++i0) {
    for (int i1 = i0 + 1; i1 < m; ++i1) {
      for (int i2 = i1 + 1; i2 < m; ++i2) {
        for (int i3 = i2 + 1; i3 < m; ++i3) {
          const std::array<int, 4> q = {index[i0], index[i1], index[i2], index[i3]};
          const double size = std::abs(oriented_det(knots_[q[0]], knots_[q[1]], knots_[q[2]], knots_[q[3]]));
          if (size == 0) continue;
          if (rank_by_containment) {
            candidates[count++] = {size, q};
          } else if (size > best) {
            // The exact flatness check only for a four that would win.
            BarycentricFrame candidate;
            if (!make_frame(knots_[q[0]], knots_[q[1]], knots_[q[2]], knots_[q[3]], candidate)) continue;
            best = size;
            w = q;
            frame = candidate;
          }
        }
      }
    }
  }
  if (!rank_by_containment) return best > 0;
  // By decreasing |det|, the first whose tetrahedron contains x (floating barycentrics suffice:
  // this is only a preference for stability), else the largest.
  std::sort(candidates.begin(), candidates.begin() + count,
            [](const Candidate& a, const Candidate& b) { return a.size > b.size; });
  bool found = false;
  for (int c = 0; c < count; ++c) {
    const auto& q = candidates[c].w;
    BarycentricFrame candidate;
    if (!make_frame(knots_[q[0]], knots_[q[1]], knots_[q[2]], knots_[q[3]], candidate)) continue;
    if (!found) {
      found = true;
      w = q;
      frame = candidate;
    }
    const auto l = candidate.lambda(*x);
    if (l[0] >= 0 && l[1] >= 0 && l[2] >= 0 && l[3] >= 0) {
      w = q;
      frame = candidate;
      return true;
    }
  }
  return found;
}

bool KnotBinding::choose(KnotMask subset, const Eigen::Vector3d* x, std::array<int, 4>& w,
                         BarycentricFrame& frame) const {
  if (custom_ != nullptr) {
    if (!(*custom_)(subset, w)) return false;
    return make_frame(knots_[w[0]], knots_[w[1]], knots_[w[2]], knots_[w[3]], frame);
  }
  return choose_largest(subset, choice_ == BarycentricChoice::kContainingThenLargest ? x : nullptr, w, frame);
}

void SubsetMemo::reserve(int expected) {
  std::size_t size = 64;
  while (size < static_cast<std::size_t>(expected) * 2) size *= 2;
  if (entries_.size() < size) {
    entries_.assign(size, Entry{});
    used_ = 0;
    stamp_ = 1;
  }
}

void SubsetMemo::clear() {
  used_ = 0;
  if (++stamp_ == 0) {
    // The stamp wrapped around: old entries could look current.
    std::fill(entries_.begin(), entries_.end(), Entry{});
    stamp_ = 1;
  }
}

double* SubsetMemo::find(KnotMask subset) {
  const std::size_t mask = entries_.size() - 1;
  for (std::size_t s = slot(subset);; s = (s + 1) & mask) {
    Entry& e = entries_[s];
    if (e.stamp != stamp_) return nullptr;
    if (e.mask == subset) return &e.value;
  }
}

void SubsetMemo::store(KnotMask subset, double value) {
  if (4 * (used_ + 1) > 3 * entries_.size()) grow();
  const std::size_t mask = entries_.size() - 1;
  for (std::size_t s = slot(subset);; s = (s + 1) & mask) {
    Entry& e = entries_[s];
    if (e.stamp != stamp_) {
      e = Entry{subset, stamp_, value};
      ++used_;
      return;
    }
    if (e.mask == subset) {
      e.value = value;
      return;
    }
  }
}

void SubsetMemo::grow() {
  std::vector<Entry> old;
  old.swap(entries_);
  const std::uint32_t stamp = stamp_;
  entries_.assign(std::max<std::size_t>(64, old.size() * 2), Entry{});
  used_ = 0;
  stamp_ = 1;
  for (const Entry& e : old) {
    if (e.stamp == stamp) store(e.mask, e.value);
  }
}

void clip_to_chord(const std::array<double, 4>& lambda, const std::array<double, 4>& mu, double& lo, double& hi) {
  for (int j = 0; j < 4; ++j) {
    if (mu[j] == 0) {
      if (lambda[j] < 0) hi = lo;
    } else if (mu[j] > 0) {
      lo = std::max(lo, -lambda[j] / mu[j]);
    } else {
      hi = std::min(hi, -lambda[j] / mu[j]);
    }
  }
}

bool clip_to_padded_box(const Eigen::Vector3d& lo, const Eigen::Vector3d& hi, const Eigen::Vector3d& origin,
                        const Eigen::Vector3d& direction, double& t_lo, double& t_hi) {
  const double pad = 1e-6 * (hi - lo).norm() + 1e-300;
  for (int k = 0; k < 3; ++k) {
    const double low = lo[k] - pad;
    const double high = hi[k] + pad;
    if (direction[k] == 0) {
      if (origin[k] < low || origin[k] > high) return false;
      continue;
    }
    double t0 = (low - origin[k]) / direction[k];
    double t1 = (high - origin[k]) / direction[k];
    if (t0 > t1) std::swap(t0, t1);
    t_lo = std::max(t_lo, t0);
    t_hi = std::min(t_hi, t1);
  }
  return t_lo < t_hi;
}

double recurrence_shift(const std::array<double, 4>& lambda, const std::array<double, 4>& mu,
                        const Eigen::Vector3d& centroid, const Eigen::Vector3d& origin,
                        const Eigen::Vector3d& direction, double lower, double upper) {
  double lo = -std::numeric_limits<double>::infinity();
  double hi = std::numeric_limits<double>::infinity();
  clip_to_chord(lambda, mu, lo, hi);
  const double shift = lo < hi ? 0.5 * (lo + hi) : (centroid - origin).dot(direction) / direction.squaredNorm();
  return std::clamp(shift, lower, upper);
}

double flat_line_integral(const Eigen::Vector3d* knots, KnotMask subset, const Eigen::Vector3d& origin,
                          const Eigen::Vector3d& direction, double lo, double hi) {
  std::array<int, kMaxRecurrenceKnots> idx{};
  const int m = subset_indices(subset, idx);
  if (m > kMaxSimplexSplineDegree + 5) return 0;
  // The plane through the first knot and the two that span the largest triangle with it.
  const Eigen::Vector3d& a = knots[idx[0]];
  Eigen::Vector3d normal = Eigen::Vector3d::Zero();
  Eigen::Vector3d edge = Eigen::Vector3d::Zero();
  for (int i = 1; i < m; ++i) {
    for (int j = i + 1; j < m; ++j) {
      const Eigen::Vector3d n = (knots[idx[i]] - a).cross(knots[idx[j]] - a);
      if (n.squaredNorm() > normal.squaredNorm()) {
        normal = n;
        edge = knots[idx[i]] - a;
      }
    }
  }
  if (normal.squaredNorm() == 0) return 0;
  const Eigen::Vector3d unit_normal = normal.normalized();
  const double across = direction.dot(unit_normal);
  if (across == 0) return 0;
  const double s = (a - origin).dot(unit_normal) / across;
  if (!(s >= lo && s < hi)) return 0;
  const Eigen::Vector3d e1 = edge.normalized();
  const Eigen::Vector3d e2 = unit_normal.cross(e1);
  std::array<Eigen::Vector2d, kMaxSimplexSplineDegree + 5> planar;
  for (int i = 0; i < m; ++i) {
    const Eigen::Vector3d r = knots[idx[i]] - a;
    planar[i] = Eigen::Vector2d(r.dot(e1), r.dot(e2));
  }
  const Eigen::Vector3d r = origin + s * direction - a;
  const double density =
      bivariate_simplex_spline_value(Eigen::Vector2d(r.dot(e1), r.dot(e2)),
                                     std::span<const Eigen::Vector2d>(planar.data(), static_cast<std::size_t>(m)));
  return density / ((m - 3) * std::abs(across));
}

int expected_dms_subsets(int degree) {
  // Counted for generic knot clouds (docs/simplex-splines.md); the memo grows if a configuration
  // reaches more.
  constexpr std::array<int, kMaxSimplexSplineDegree + 1> kCounts = {1, 17, 102, 364, 1111, 2715};
  return kCounts[std::clamp(degree, 0, kMaxSimplexSplineDegree)] + 16;
}

void PointRecurrence::attach(const KnotBinding* binding, int expected_subsets) {
  binding_ = binding;
  memo_.reserve(expected_subsets);
}

void PointRecurrence::set_point(const Eigen::Vector3d& x) {
  x_ = x;
  knot_ = knot_at(x, &binding_->knot(0), binding_->count());
  coordinates_ = binding_->reference_frame().lambda(x);
  memo_.clear();
}


double PointRecurrence::value(KnotMask subset) {
  if (const double* known = memo_.find(subset)) return *known;
  double v = 0;
  if (!pruned(subset)) {
    if (std::popcount(subset) == 4) {
      std::array<int, kMaxRecurrenceKnots> idx{};
      subset_indices(subset, idx);
      const auto& a = binding_->knot(idx[0]);
      const auto& b = binding_->knot(idx[1]);
      const auto& c = binding_->knot(idx[2]);
      const auto& d = binding_->knot(idx[3]);
      BarycentricFrame frame;
      if (make_frame(a, b, c, d, frame) &&
          half_open_contains(face_barycentric(x_, a, b, c, d, frame.det), x_, knot_ >= 0, a, b, c, d)) {
        v = 1.0 / std::abs(frame.det);
      }
    } else {
      std::array<int, 4> w{};
      BarycentricFrame frame;
      if (binding_->choose(subset, &x_, w, frame)) {
        auto l = face_barycentric(x_, binding_->knot(w[0]), binding_->knot(w[1]), binding_->knot(w[2]),
                                  binding_->knot(w[3]), frame.det);
        if (knot_ >= 0) snap_to_knot(l, w, knot_);
        for (int j = 0; j < 4; ++j) {
          if (l[j] != 0) v += l[j] * value(subset & ~bit(w[j]));
        }
      }
    }
  }
  memo_.store(subset, v);
  return v;
}

Eigen::Vector3d PointRecurrence::gradient(KnotMask subset) {
  const int degree = std::popcount(subset) - 4;
  Eigen::Vector3d g = Eigen::Vector3d::Zero();
  if (degree <= 0 || pruned(subset)) return g;
  std::array<int, 4> w{};
  BarycentricFrame frame;
  if (!binding_->choose(subset, &x_, w, frame)) return g;
  for (int j = 0; j < 4; ++j) g += frame.g[j] * value(subset & ~bit(w[j]));
  return degree * g;
}

SimplexSplineJet PointRecurrence::jet(KnotMask subset, int order) {
  SimplexSplineJet out;
  const int degree = std::popcount(subset) - 4;
  if (degree == 0 || pruned(subset)) {
    out.value = value(subset);
    return out;
  }
  std::array<int, 4> w{};
  BarycentricFrame frame;
  if (!binding_->choose(subset, &x_, w, frame)) return out;
  auto l = face_barycentric(x_, binding_->knot(w[0]), binding_->knot(w[1]), binding_->knot(w[2]), binding_->knot(w[3]),
                            frame.det);
  if (knot_ >= 0) snap_to_knot(l, w, knot_);
  for (int j = 0; j < 4; ++j) {
    const KnotMask child = subset & ~bit(w[j]);
    const double child_value = value(child);
    out.value += l[j] * child_value;
    if (order >= 1) out.gradient += frame.g[j] * child_value;
    // Eq. 2 twice: the Hessian is n Σ_j g_j ⊗ ∇M(V \ w_j).
    if (order >= 2 && degree >= 2) out.hessian += frame.g[j] * gradient(child).transpose();
  }
  out.gradient *= degree;
  out.hessian = 0.5 * degree * (out.hessian + out.hessian.transpose()).eval();
  return out;
}

double PointRecurrence::directional_derivative(KnotMask subset, const Eigen::Vector3d& v) {
  return gradient(subset).dot(v);
}

void LineRecurrence::attach(const KnotBinding* binding, int expected_subsets) {
  binding_ = binding;
  memo_.reserve(expected_subsets);
  at_lower_.attach(binding, expected_subsets);
  at_upper_.attach(binding, expected_subsets);
}

void LineRecurrence::set_line(const Eigen::Vector3d& origin, const Eigen::Vector3d& direction, double a, double b) {
  memo_.clear();
  empty_ = true;
  constant_ = false;
  if (!(a < b)) return;
  if (direction.squaredNorm() == 0) {
    // M(origin) over an interval of length b - a.
    constant_ = true;
    at_lower_.set_point(origin);
    constant_factor_ = b - a;
    empty_ = false;
    return;
  }
  Eigen::Vector3d lo = binding_->knot(0);
  Eigen::Vector3d hi = lo;
  for (int i = 1; i < binding_->count(); ++i) {
    lo = lo.cwiseMin(binding_->knot(i));
    hi = hi.cwiseMax(binding_->knot(i));
  }
  double t_lo = a;
  double t_hi = b;
  if (!clip_to_padded_box(lo, hi, origin, direction, t_lo, t_hi)) return;
  // Re-parametrise about the middle of the clipped interval: the barycentric coordinates of the
  // new origin stay of order 1 (eq. 16 multiplies them by the sub-integrals).
  const double middle = 0.5 * (t_lo + t_hi);
  origin_ = origin + middle * direction;
  direction_ = direction;
  lower_ = t_lo - middle;
  upper_ = t_hi - middle;
  empty_ = false;
  at_lower_.set_point(origin_ + lower_ * direction_);
  at_upper_.set_point(origin_ + upper_ * direction_);
  const auto c0 = binding_->reference_frame().lambda(origin_ + lower_ * direction_);
  const auto c1 = binding_->reference_frame().lambda(origin_ + upper_ * direction_);
  for (int k = 0; k < 4; ++k) {
    coordinates_lo_[k] = std::min(c0[k], c1[k]);
    coordinates_hi_[k] = std::max(c0[k], c1[k]);
  }
}

double LineRecurrence::integral(KnotMask subset) {
  if (empty_) return 0;
  if (constant_) return constant_factor_ == 0 ? 0 : constant_factor_ * at_lower_.value(subset);
  if (const double* known = memo_.find(subset)) return *known;
  const double v = compute(subset);
  memo_.store(subset, v);
  return v;
}


double LineRecurrence::compute(KnotMask subset) {
  if (binding_->excludes(subset, coordinates_lo_, coordinates_hi_)) return 0;
  const int degree = std::popcount(subset) - 4;
  std::array<int, 4> w{};
  BarycentricFrame frame;
  if (degree == 0) {
    std::array<int, kMaxRecurrenceKnots> idx{};
    subset_indices(subset, idx);
    w = {idx[0], idx[1], idx[2], idx[3]};
    if (!make_frame(binding_->knot(w[0]), binding_->knot(w[1]), binding_->knot(w[2]), binding_->knot(w[3]), frame)) {
      return flat_line_integral(&binding_->knot(0), subset, origin_, direction_, lower_, upper_);
    }
  } else if (!binding_->choose(subset, nullptr, w, frame)) {
    return flat_line_integral(&binding_->knot(0), subset, origin_, direction_, lower_, upper_);
  }
  const auto m = frame.mu(direction_);
  const Eigen::Vector3d centroid =
      0.25 * (binding_->knot(w[0]) + binding_->knot(w[1]) + binding_->knot(w[2]) + binding_->knot(w[3]));
  const double shift = recurrence_shift(frame.lambda(origin_), m, centroid, origin_, direction_, lower_, upper_);
  const auto l = frame.lambda(origin_ + shift * direction_);
  if (degree == 0) {
    double lo = lower_ - shift;
    double hi = upper_ - shift;
    clip_to_chord(l, m, lo, hi);
    return hi > lo ? (hi - lo) / std::abs(frame.det) : 0.0;
  }
  double sum = 0;
  for (int j = 0; j < 4; ++j) {
    if (l[j] != 0) sum += l[j] * integral(subset & ~bit(w[j]));
  }
  // Eq. 16 with the boundary terms of the integration by parts (docs/simplex-splines.md).
  const double boundary =
      (upper_ - shift) * at_upper_.value(subset) - (lower_ - shift) * at_lower_.value(subset);
  return (degree * sum + boundary) / (degree + 1);
}

}  // namespace volspline::simplex_detail
