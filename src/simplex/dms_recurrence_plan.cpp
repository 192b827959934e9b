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

// clip_to_chord for [lo, hi] (finite, lo < hi): the parameters in [lo, hi] where every
// λ_j + s·μ_j >= 0; false when there are none. Divides only for the j whose λ_j changes sign
// within [lo, hi] (about two for a chord that crosses the tetrahedron, none for most that miss).
[[gnu::always_inline]] inline bool clip_to_chord_within(const std::array<double, 4>& lambda, const std::array<double, 4>& mu, double& lo,
                          double& hi) {
  const double lower = lo;
  const double upper = hi;
  for (int j = 0; j < 4; ++j) {
    const double at_lower = lambda[j] + lower * mu[j];
    const double at_upper = lambda[j] + upper * mu[j];
    if (at_lower < 0 && at_upper < 0) return false;
    if (at_lower < 0 || at_upper < 0) {
      const double crossing = -lambda[j] / mu[j];
      if (mu[j] > 0) {
        lo = std::max(lo, crossing);
      } else {
        hi = std::min(hi, crossing);
      }
    }
  }
  return lo < hi;
}

}  // namespace

struct DmsRecurrencePlan::Builder {
  struct Four {
    double inverse_det;
    std::array<int, 4> face;
    std::array<int, 4> w;
  };
  struct Interior {
    std::array<int, 4> child;  // codes of add()
    int four;                  // -1: flat
    int degree;
    KnotMask mask;
  };
  SubsetMemo& index;  // subset -> code
  SubsetMemo faces;   // three-knot mask -> face
  SubsetMemo fours;   // four-knot mask -> four
  std::vector<std::array<int, 3>> face_knots;
  std::vector<Four> four_list;
  std::vector<int> leaf_four;
  std::vector<KnotMask> leaf_masks;
  std::vector<Interior> interior;

  explicit Builder(SubsetMemo& subsets) : index(subsets) {}

  int face_of(int a, int b, int c) {
    const KnotMask mask = (KnotMask{1} << a) | (KnotMask{1} << b) | (KnotMask{1} << c);
    if (const double* known = faces.find(mask)) return static_cast<int>(*known);
    const int id = static_cast<int>(face_knots.size());
    face_knots.push_back({a, b, c});
    faces.store(mask, id);
    return id;
  }

  // The four of knots w (any order), sorted; flat (inverse_det 0) where make_frame says so.
  int four_of(std::array<int, 4> w, const std::array<Eigen::Vector3d, kMaxRecurrenceKnots>& knots) {
    std::sort(w.begin(), w.end());
    KnotMask mask = 0;
    for (const int k : w) mask |= KnotMask{1} << k;
    if (const double* known = fours.find(mask)) return static_cast<int>(*known);
    Four four{};
    four.w = w;
    BarycentricFrame frame;
    if (make_frame(knots[w[0]], knots[w[1]], knots[w[2]], knots[w[3]], frame)) four.inverse_det = 1.0 / frame.det;
    four.face = {face_of(w[1], w[2], w[3]), face_of(w[0], w[2], w[3]), face_of(w[0], w[1], w[3]),
                 face_of(w[0], w[1], w[2])};
    const int id = static_cast<int>(four_list.size());
    four_list.push_back(four);
    fours.store(mask, id);
    return id;
  }
};

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
  Builder builder(index);
  builder.faces.reserve(4 * expected_dms_subsets(degree));
  builder.fours.reserve(2 * expected_dms_subsets(degree));
  std::vector<int> top_codes;
  scales_.clear();
  for (const auto& beta : betas) {
    KnotMask mask = 0;
    for (int c = 0; c < 4; ++c) mask |= ((KnotMask{1} << (beta[c] + 1)) - 1) << (c * cloud_size);
    top_codes.push_back(add(mask, binding, builder));
    scales_.push_back(std::abs(oriented_det(knots_[beta[0]], knots_[cloud_size + beta[1]],
                                            knots_[2 * cloud_size + beta[2]], knots_[3 * cloud_size + beta[3]])));
  }
  // Fours: the leaves' first (leaf i is four i), then the other W.
  leaf_count_ = static_cast<int>(builder.leaf_four.size());
  std::vector<int> four_number(builder.four_list.size(), -1);
  for (int i = 0; i < leaf_count_; ++i) four_number[static_cast<std::size_t>(builder.leaf_four[static_cast<std::size_t>(i)])] = i;
  int next_four = leaf_count_;
  for (int& n : four_number) {
    if (n < 0) n = next_four++;
  }
  // Faces grouped by their first knot.
  const std::size_t face_count = builder.face_knots.size();
  std::vector<int> face_order(face_count);
  for (std::size_t f = 0; f < face_count; ++f) face_order[f] = static_cast<int>(f);
  std::stable_sort(face_order.begin(), face_order.end(), [&](int a, int b) {
    return builder.face_knots[static_cast<std::size_t>(a)][0] < builder.face_knots[static_cast<std::size_t>(b)][0];
  });
  std::vector<int> face_number(face_count);
  face_count_ = static_cast<int>(face_count);
  normals_.resize(3 * face_count);
  face_begin_.assign(static_cast<std::size_t>(knot_count_) + 1, 0);
  for (std::size_t i = 0; i < face_count; ++i) {
    const auto& [a, b, c] = builder.face_knots[static_cast<std::size_t>(face_order[i])];
    face_number[static_cast<std::size_t>(face_order[i])] = static_cast<int>(i);
    const Eigen::Vector3d n = (knots_[b] - knots_[a]).cross(knots_[c] - knots_[a]);
    normals_[i] = n.x();
    normals_[face_count + i] = n.y();
    normals_[2 * face_count + i] = n.z();
    ++face_begin_[static_cast<std::size_t>(a) + 1];
  }
  for (int k = 0; k < knot_count_; ++k) face_begin_[static_cast<std::size_t>(k) + 1] += face_begin_[static_cast<std::size_t>(k)];
  fours_.resize(builder.four_list.size());
  for (std::size_t q = 0; q < builder.four_list.size(); ++q) {
    const Builder::Four& f = builder.four_list[q];
    PlanFour& out = fours_[static_cast<std::size_t>(four_number[q])];
    out.inverse_det = f.inverse_det;
    for (int j = 0; j < 4; ++j) {
      out.face[j] = static_cast<std::uint16_t>(face_number[static_cast<std::size_t>(f.face[j])]);
      out.w[j] = static_cast<std::int8_t>(f.w[j]);
    }
  }
  const auto number = [this](int code) { return code < 0 ? -1 - code : leaf_count_ + code; };
  interior_.resize(builder.interior.size());
  masks_ = builder.leaf_masks;
  for (std::size_t i = 0; i < builder.interior.size(); ++i) {
    const Builder::Interior& n = builder.interior[i];
    PlanNode& out = interior_[i];
    out.degree = static_cast<std::int8_t>(n.degree);
    out.four = n.four < 0 ? kFlatNode : static_cast<std::uint16_t>(four_number[static_cast<std::size_t>(n.four)]);
    for (int j = 0; j < 4; ++j) out.child[j] = n.four < 0 ? 0 : static_cast<std::uint16_t>(number(n.child[j]));
    masks_.push_back(n.mask);
  }
  tops_.clear();
  for (const int code : top_codes) tops_.push_back(number(code));
  built_ = true;
}

bool DmsRecurrencePlan::matches(const Eigen::Vector3d* knots) const {
  return built_ && std::equal(knots, knots + knot_count_, knots_.begin());
}

void DmsRecurrencePlan::shrink_to_fit() {
  normals_.shrink_to_fit();
  face_begin_.shrink_to_fit();
  fours_.shrink_to_fit();
  interior_.shrink_to_fit();
  masks_.shrink_to_fit();
  tops_.shrink_to_fit();
  scales_.shrink_to_fit();
}

std::size_t DmsRecurrencePlan::memory_bytes() const {
  return sizeof(*this) + normals_.capacity() * sizeof(double) + face_begin_.capacity() * sizeof(std::uint16_t) +
         fours_.capacity() * sizeof(PlanFour) + interior_.capacity() * sizeof(PlanNode) +
         masks_.capacity() * sizeof(KnotMask) + tops_.capacity() * sizeof(int) + scales_.capacity() * sizeof(double);
}

// Depth first, so that a node's children precede it; returns the code of `subset`.
int DmsRecurrencePlan::add(KnotMask subset, const KnotBinding& binding, Builder& builder) {
  if (const double* known = builder.index.find(subset)) return static_cast<int>(*known);
  std::array<int, 4> w{};
  int code;
  const int knots_in_subset = std::popcount(subset);
  if (knots_in_subset == 4) {
    KnotMask rest = subset;
    for (int& k : w) {
      k = std::countr_zero(rest);
      rest &= rest - 1;
    }
    code = -1 - static_cast<int>(builder.leaf_four.size());
    builder.leaf_four.push_back(builder.four_of(w, knots_));
    builder.leaf_masks.push_back(subset);
  } else {
    Builder::Interior node{};
    node.mask = subset;
    node.degree = knots_in_subset - 4;
    node.four = -1;
    BarycentricFrame frame;
    if (choose_dms_knots(knots_, cloud_size_, subset, w, frame, binding)) {
      std::sort(w.begin(), w.end());
      const int four = builder.four_of(w, knots_);
      if (builder.four_list[static_cast<std::size_t>(four)].inverse_det != 0) {
        node.four = four;
        for (int j = 0; j < 4; ++j) node.child[j] = add(subset & ~(KnotMask{1} << w[j]), binding, builder);
      }
    }
    code = static_cast<int>(builder.interior.size());
    builder.interior.push_back(node);
  }
  builder.index.store(subset, code);
  return code;
}

std::array<Eigen::Vector3d, 4> DmsRecurrencePlan::four_lambda_gradients(int q) const {
  const PlanFour& f = fours_[static_cast<std::size_t>(q)];
  std::array<Eigen::Vector3d, 4> g;
  for (int j = 0; j < 4; ++j) {
    const std::size_t k = f.face[j];
    const std::size_t stride = static_cast<std::size_t>(face_count_);
    const double s = (j % 2 == 0 ? -1.0 : 1.0) * f.inverse_det;
    g[j] = Eigen::Vector3d(s * normals_[k], s * normals_[stride + k], s * normals_[2 * stride + k]);
  }
  return g;
}

void DmsRecurrencePlan::face_determinants(const Eigen::Vector3d& x, double* d) const {
  const double* nx = normals_.data();
  const double* ny = nx + face_count_;
  const double* nz = ny + face_count_;
  for (int k = 0; k < knot_count_; ++k) {
    const int end = face_begin_[static_cast<std::size_t>(k) + 1];
    int f = face_begin_[static_cast<std::size_t>(k)];
    if (f == end) continue;
    const double rx = x.x() - knots_[k].x();
    const double ry = x.y() - knots_[k].y();
    const double rz = x.z() - knots_[k].z();
    for (; f < end; ++f) d[f] = nx[f] * rx + ny[f] * ry + nz[f] * rz;
  }
}

void DmsRecurrencePlan::values(const Eigen::Vector3d& x, double* out, int knot, double* work) const {
  constexpr double kUndecided = 1e-9;  // as half_open_contains
  double* d = work;
  face_determinants(x, d);
  // At a knot, faces of other knots are decided as make_frame decides their fours (flat within
  // rounding); elsewhere exactly.
  for (int i = 0; i < leaf_count_; ++i) {
    const PlanFour& f = fours_[static_cast<std::size_t>(i)];
    const auto l = lambda(i, d);
    const double smallest = std::min(std::min(l[0], l[1]), std::min(l[2], l[3]));
    const double inverse_volume = std::abs(f.inverse_det);
    if (smallest > kUndecided) {
      out[i] = inverse_volume;
    } else if (!(smallest >= -kUndecided) || inverse_volume == 0) {
      out[i] = 0;
    } else {
      const Eigen::Vector3d& a = knots_[f.w[0]];
      const Eigen::Vector3d& b = knots_[f.w[1]];
      const Eigen::Vector3d& c = knots_[f.w[2]];
      const Eigen::Vector3d& e = knots_[f.w[3]];
      const bool inside =
          knot >= 0 ? in_half_open_tetrahedron_at_knot(x, a, b, c, e) : in_half_open_tetrahedron(x, a, b, c, e);
      out[i] = inside ? inverse_volume : 0.0;
    }
  }
  double* interior_out = out + leaf_count_;
  for (const PlanNode& n : interior_) {
    double v = 0;
    const double c0 = out[n.child[0]], c1 = out[n.child[1]], c2 = out[n.child[2]], c3 = out[n.child[3]];
    // All children 0 (x outside every child's support, the usual case far from a subset): 0.
    if (n.four != kFlatNode && (c0 != 0 || c1 != 0 || c2 != 0 || c3 != 0)) {
      const auto l = lambda(n.four, d);
      v = l[0] * c0 + l[1] * c1 + l[2] * c2 + l[3] * c3;
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
  double* work = scratch + 2 * count;
  if (direction.squaredNorm() == 0) {
    values(origin, at_lower, knot_at(origin), work);
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
      values(end, at, knot_at(end), work);
    }
  }
  // λ(o) and μ(direction) of every four from the faces: D(o) and n·direction.
  double* d = work;
  double* e = work + face_count();
  face_determinants(o, d);
  for (int f = 0; f < face_count(); ++f) {
    const auto k = static_cast<std::size_t>(f);
    const auto stride = static_cast<std::size_t>(face_count_);
    e[f] = normals_[k] * direction.x() + normals_[stride + k] * direction.y() + normals_[2 * stride + k] * direction.z();
  }
  for (int i = 0; i < leaf_count_; ++i) {
    const PlanFour& f = fours_[static_cast<std::size_t>(i)];
    if (f.inverse_det == 0) {
      out[i] = flat_line_integral(knots_.data(), masks_[static_cast<std::size_t>(i)], o, direction, lower, upper);
      continue;
    }
    double s_lo = lower;
    double s_hi = upper;
    out[i] = clip_to_chord_within(lambda(i, d), lambda(i, e), s_lo, s_hi) ? (s_hi - s_lo) * std::abs(f.inverse_det) : 0.0;
  }
  // 1/(n + 1) and n/(n + 1) of eq. 16 per degree (a division per node would be the critical path).
  std::array<double, kMaxSimplexSplineDegree + 1> inverse{}, ratio{};
  for (int n = 1; n <= kMaxSimplexSplineDegree; ++n) {
    inverse[static_cast<std::size_t>(n)] = 1.0 / (n + 1);
    ratio[static_cast<std::size_t>(n)] = static_cast<double>(n) / (n + 1);
  }
  for (int i = leaf_count_; i < count; ++i) {
    const PlanNode& n = interior(i);
    if (n.four == kFlatNode) {
      out[i] = flat_line_integral(knots_.data(), masks_[static_cast<std::size_t>(i)], o, direction, lower, upper);
      continue;
    }
    // Where the line misses every child's support it misses the subset's (eq. 1: M(V) vanishes
    // where all M(V \ w_j) do), and with both ends outside it too the integral is 0 (the sum below
    // would give exactly 0): no chord to compute.
    if (out[n.child[0]] == 0 && out[n.child[1]] == 0 && out[n.child[2]] == 0 && out[n.child[3]] == 0 &&
        at_upper[i] == 0 && at_lower[i] == 0) {
      out[i] = 0;
      continue;
    }
    // Eq. 16 about a point of the line where every λ_j >= 0, so that the sum does not cancel: the
    // middle of the chord of W's tetrahedron within [lower, upper], else recurrence_shift (the
    // middle of the whole chord, or the point nearest W's centroid where the line misses W).
    const auto l0 = lambda(n.four, d);
    const auto m = lambda(n.four, e);
    double lo = lower;
    double hi = upper;
    double shift;
    if (clip_to_chord_within(l0, m, lo, hi)) {
      shift = 0.5 * (lo + hi);
    } else {
      const PlanFour& f = fours_[n.four];
      const Eigen::Vector3d centroid = 0.25 * (knots_[f.w[0]] + knots_[f.w[1]] + knots_[f.w[2]] + knots_[f.w[3]]);
      shift = recurrence_shift(l0, m, centroid, o, direction, lower, upper);
    }
    double sum = 0;
    for (int j = 0; j < 4; ++j) sum += (l0[j] + shift * m[j]) * out[n.child[j]];
    const double boundary = (upper - shift) * at_upper[i] - (lower - shift) * at_lower[i];
    const auto degree = static_cast<std::size_t>(n.degree);
    out[i] = ratio[degree] * sum + inverse[degree] * boundary;
  }
}

}  // namespace volspline::simplex_detail
