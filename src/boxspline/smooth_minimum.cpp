// The n-ary smooth minimum E[min_i(a_i + u_i)], u_i independent and uniform on [−k/2, k/2]
// (implicit_scene.h; derivation and the choice of method in docs/blend.md, "Blends of many
// children").
//
// With τ = (t − least + k/2)/k and the breakpoints τ_i = (a_i − least)/k sorted, τ_0 = 0,
//   E = least − k/2 + k I,   I = ∫_0^1 S(τ) dτ,   S(τ) = Π_{τ_i < τ} φ_i(τ),   φ_i = 1 + τ_i − τ,
// S being the probability that every a_i + u_i exceeds t; values with τ_i ≥ 1 never take part.
// The partial derivatives are the probabilities that each value is the least:
//   ∂E/∂a_j = ∫_{τ_j}^1 S(τ) / φ_j(τ) dτ.
// Every factor φ_i lies in (0, 1] where it is used, so S and every integrand are sums and
// products of positive numbers; the methods below keep them so (no differences of large
// numbers), which is what the monomial form in τ did not (its coefficients alternate in sign and
// grow like binomials: at 60 tied values nothing of I was left).
#include <algorithm>
#include <array>
#include <cmath>
#include <optional>
#include <span>
#include <vector>

#include "volspline/analysis/mass_properties.h"  // gauss_legendre
#include "volspline/boxspline/implicit_scene.h"

namespace volspline {
namespace {

// Up to these many values the integrals are computed exactly, panel by panel (O(m²) for the
// value, O(m³) with the derivatives), which is faster there; beyond, by the quadrature below
// (O(m log m); bench/boxspline_bench.cpp, docs/performance.md).
constexpr std::size_t kExactValueLimit = 128;
constexpr std::size_t kExactDerivativeLimit = 16;

// ∫_{τ_first}^1 Π_{i ≤ r, i ≠ skip} φ_i over the panels r ≥ first, exactly: in y = 1 − τ each
// factor is y + τ_i, whose coefficients are positive, so the product's coefficients c_d are
// positive; a panel [Y_{r+1}, Y_r] contributes Σ_d c_d (Y_r^{d+1} − Y_{r+1}^{d+1})/(d + 1), and
// Y_r^{d+1} − Y_{r+1}^{d+1} = (τ_{r+1} − τ_r) Σ_{j ≤ d} Y_r^j Y_{r+1}^{d−j} is a sum of positive
// terms too.
double exact_survival_integral(std::span<const double> tau, std::size_t skip, std::size_t first) {
  std::vector<double> c{1.0};
  double sum = 0.0;
  for (std::size_t r = 0; r < tau.size(); ++r) {
    if (r != skip) {
      c.push_back(0.0);
      for (std::size_t d = c.size() - 1; d > 0; --d) c[d] = c[d - 1] + tau[r] * c[d];
      c[0] *= tau[r];
    }
    if (r < first) continue;
    const double next = r + 1 < tau.size() ? tau[r + 1] : 1.0;
    const double width = next - tau[r];
    if (!(width > 0.0)) continue;
    const double high = 1.0 - tau[r], low = 1.0 - next;
    double power = 1.0, h = 0.0, panel = 0.0;  // power = high^d, h = Σ_{j ≤ d} high^j low^{d−j}
    for (std::size_t d = 0; d < c.size(); ++d) {
      h = power + low * h;
      power *= high;
      panel += c[d] * h / static_cast<double>(d + 1);
    }
    sum += width * panel;
  }
  return sum;
}

// Gauss–Legendre rules on [−1, 1] with 1..kMaxRule points, computed once.
constexpr int kMaxRule = 10;
struct GaussRules {
  std::array<std::array<double, kMaxRule>, kMaxRule + 1> nodes{}, weights{};
  // c_q = (q!)^4 / ((2q + 1) ((2q)!)^3): the q-point rule's error on [0, w] is c_q w^{2q+1} f^{(2q)}.
  std::array<double, kMaxRule + 1> error_constant{};
  GaussRules() {
    for (int q = 1; q <= kMaxRule; ++q) {
      gauss_legendre(q, nodes[static_cast<std::size_t>(q)].data(), weights[static_cast<std::size_t>(q)].data());
      const double fq = std::tgamma(q + 1.0), f2q = std::tgamma(2.0 * q + 1.0);
      error_constant[static_cast<std::size_t>(q)] = fq * fq * fq * fq / ((2.0 * q + 1.0) * f2q * f2q * f2q);
    }
  }
};
const GaussRules& gauss_rules() {
  static const GaussRules rules;
  return rules;
}

// The fewest points that integrate S over a piece of width w with λ w ≤ x to 1e-17 of S's
// largest value times w. S is a product of linear factors φ_i = β_i − s with roots β_i ≥ w
// (s measured from the piece's start), so |S^{(2q)}| ≤ (2q)! e_{2q}(1/β) S(0) ≤ (λ w)^{2q} S(0) / w^{2q}
// with λ = Σ 1/β_i = −(log S)' at the start: the error is at most c_q (λ w)^{2q} S(0) w.
int points_for(double x) {
  const GaussRules& rules = gauss_rules();
  for (int q = 1; q < kMaxRule; ++q)
    if (rules.error_constant[static_cast<std::size_t>(q)] * std::pow(x, 2 * q) <= 1e-17) return q;
  return kMaxRule;
}

// Sums Σ_i f(c − x_i) over groups of points x_i, all lying on one side of the arguments, by
// power sums about the group's anchor (Barnes–Hut in one dimension): with d_i = |anchor − x_i|
// ≤ spread, Σ_i g(b − d_i) is expanded in d_i/b, whose terms all have one sign. A group whose
// spread exceeds kRatio b is split; groups of at most kLeaf points are summed directly.
constexpr double kRatio = 0.125;
constexpr int kMoments = 24;  // kRatio^24 = 2e-22: truncation below rounding even for 1e5 points
constexpr std::size_t kLeaf = 4;

struct PowerSumTree {
  struct Group {
    std::size_t begin = 0, end = 0;
    int left = -1, right = -1;
    double anchor = 0.0, spread = 0.0;
    std::array<double, kMoments + 1> moments{};  // Σ weight_i d_i^k
  };
  std::vector<Group> groups;
  std::span<const double> x, weight;  // weight empty: 1 for every point

  // anchor_last: the anchor is the largest x of the group (d_i = anchor − x_i), else the least.
  PowerSumTree(std::span<const double> points, std::span<const double> weights, bool anchor_last)
      : x(points), weight(weights) {
    if (!points.empty()) build(0, points.size(), anchor_last);
  }

  int build(std::size_t begin, std::size_t end, bool anchor_last) {
    const int id = static_cast<int>(groups.size());
    groups.emplace_back();
    Group g;
    g.begin = begin;
    g.end = end;
    g.anchor = anchor_last ? x[end - 1] : x[begin];
    g.spread = x[end - 1] - x[begin];
    for (std::size_t i = begin; i < end; ++i) {
      const double d = anchor_last ? g.anchor - x[i] : x[i] - g.anchor;
      double term = weight.empty() ? 1.0 : weight[i];
      for (int k = 0; k <= kMoments; ++k) {
        g.moments[static_cast<std::size_t>(k)] += term;
        term *= d;
      }
    }
    if (end - begin > kLeaf) {
      const std::size_t middle = begin + (end - begin) / 2;
      g.left = build(begin, middle, anchor_last);
      g.right = build(middle, end, anchor_last);
    }
    groups[static_cast<std::size_t>(id)] = g;
    return id;
  }
};

// log S(τ) and λ(τ) = Σ 1/φ_i(τ) over the values [0, born) (those with τ_i ≤ τ).
struct SurvivalAt {
  double log_survival = 0.0;
  double rate = 0.0;
};

void add_survival(const PowerSumTree& tree, int id, std::size_t born, double tau, SurvivalAt& out) {
  const PowerSumTree::Group& g = tree.groups[static_cast<std::size_t>(id)];
  if (g.begin >= born) return;
  if (g.end <= born) {
    // φ_i = b − d_i with b = 1 − (τ − anchor), the youngest factor of the group.
    const double age = tau - g.anchor, b = 1.0 - age;
    if (g.spread <= kRatio * b) {
      const double n = g.moments[0], t = g.spread > 0.0 ? 1.0 / b : 0.0;
      double log_part = 0.0, rate = n / b, power = 1.0;
      for (int k = 1; k <= kMoments && t > 0.0; ++k) {
        power *= t;
        const double term = g.moments[static_cast<std::size_t>(k)] * power;
        log_part += term / k;
        rate += term / b;
        if (term <= 1e-19) break;  // terms fall by 8 or more each: the rest is below rounding
      }
      out.log_survival += n * std::log1p(-age) - log_part;
      out.rate += rate;
      return;
    }
    if (g.left < 0) {
      for (std::size_t i = g.begin; i < g.end; ++i) {
        const double a = tau - tree.x[i];
        out.log_survival += std::log1p(-a);
        out.rate += 1.0 / (1.0 - a);
      }
      return;
    }
  } else if (g.left < 0) {
    for (std::size_t i = g.begin; i < std::min(g.end, born); ++i) {
      const double a = tau - tree.x[i];
      out.log_survival += std::log1p(-a);
      out.rate += 1.0 / (1.0 - a);
    }
    return;
  }
  add_survival(tree, g.left, born, tau, out);
  add_survival(tree, g.right, born, tau, out);
}

// Σ_{nodes n ≥ first} ω_n S_n / (1 − (t_n − τ_j)): the derivative of value j.
double add_probability(const PowerSumTree& nodes, int id, std::size_t first, double tau_j) {
  const PowerSumTree::Group& g = nodes.groups[static_cast<std::size_t>(id)];
  if (g.end <= first) return 0.0;
  const auto direct = [&](std::size_t from) {
    double sum = 0.0;
    for (std::size_t n = from; n < g.end; ++n) sum += nodes.weight[n] / (1.0 - (nodes.x[n] - tau_j));
    return sum;
  };
  if (g.begin >= first) {
    // 1/(B − e_n) = Σ_k e_n^k / B^{k+1}, B = φ_j at the group's first node.
    const double B = 1.0 - (g.anchor - tau_j);
    if (g.spread <= kRatio * B) {
      const double t = 1.0 / B;
      double sum = 0.0, power = t;
      for (int k = 0; k <= kMoments; ++k) {
        const double term = g.moments[static_cast<std::size_t>(k)] * power;
        sum += term;
        if (g.spread == 0.0 || term <= 1e-18 * sum) break;
        power *= t;
      }
      return sum;
    }
    if (g.left < 0) return direct(g.begin);
  } else if (g.left < 0) {
    return direct(first);
  }
  return add_probability(nodes, g.left, first, tau_j) + add_probability(nodes, g.right, first, tau_j);
}

// Binomial coefficients C(k, j), k, j ≤ kMoments, for moving power sums to another anchor.
const std::array<std::array<double, kMoments + 1>, kMoments + 1>& moment_binomials() {
  static const auto table = [] {
    std::array<std::array<double, kMoments + 1>, kMoments + 1> c{};
    for (int k = 0; k <= kMoments; ++k) {
      c[static_cast<std::size_t>(k)][0] = 1.0;
      for (int j = 1; j <= k; ++j)
        c[static_cast<std::size_t>(k)][static_cast<std::size_t>(j)] =
            c[static_cast<std::size_t>(k - 1)][static_cast<std::size_t>(j - 1)] + (j < k ? c[static_cast<std::size_t>(k - 1)][static_cast<std::size_t>(j)] : 0.0);
    }
    return c;
  }();
  return table;
}

// Power sums M_k = Σ weight_i d_i^k of distances d_i ≥ 0 from an anchor, moved to an anchor s
// farther from every point: (d + s)^k = Σ_j C(k, j) d^j s^{k−j}, all terms positive.
void move_power_sums(std::array<double, kMoments + 1>& sums, double s) {
  if (!(s > 0.0)) return;
  const auto& c = moment_binomials();
  for (int k = kMoments; k >= 1; --k) {
    double sum = sums[static_cast<std::size_t>(k)], power = 1.0;
    for (int j = k - 1; j >= 0; --j) {
      power *= s;
      sum += c[static_cast<std::size_t>(k)][static_cast<std::size_t>(j)] * power * sums[static_cast<std::size_t>(j)];
    }
    sums[static_cast<std::size_t>(k)] = sum;
  }
}

// I by Gauss–Legendre quadrature on pieces of every panel [τ_r, τ_{r+1}] (S is a polynomial
// there; its kinks are the breakpoints), each piece short enough that λ w ≤ 2, with as many
// points as points_for asks. log S at the points: from the power sums of the born values' ages
// about the youngest (kept as values are born, O(K²) each) when the born values lie within 1/8
// of the youngest factor (nearly tied values: always), else from the tree of power sums. Stops
// where S (1 − τ), which bounds the rest because S decreases, falls below 1e-17 of the integral
// so far. If `derivatives` is not empty, the rule's weighted values ω_n S_n are summed against
// 1/φ_j = Σ_k (t_n − τ_j)^k by suffix power sums when every point lies within 1/8 of τ = 0, else
// by the same kind of tree over the points.
double quadrature_survival_integral(std::span<const double> tau, std::span<double> derivatives) {
  const GaussRules& rules = gauss_rules();
  const std::size_t m = tau.size();
  std::optional<PowerSumTree> tree;  // built only when the born values are spread out
  std::array<double, kMoments + 1> ages{};  // Σ (anchor − τ_i)^k over the born values
  double anchor = 0.0;
  std::size_t born = 0;
  const auto survival_at = [&](double t) {
    SurvivalAt out;
    const double b = 1.0 - (t - anchor);  // the youngest born factor; the oldest is b − anchor
    if (anchor <= kRatio * b) {
      const double n = ages[0], inverse = 1.0 / b;
      double log_part = 0.0, rate = n * inverse, power = 1.0;
      for (int k = 1; k <= kMoments && anchor > 0.0; ++k) {
        power *= inverse;
        const double term = ages[static_cast<std::size_t>(k)] * power;
        log_part += term / k;
        rate += term * inverse;
        if (term <= 1e-19) break;
      }
      out.log_survival = n * std::log1p(-(t - anchor)) - log_part;
      out.rate = rate;
    } else {
      if (!tree) tree.emplace(tau, std::span<const double>{}, true);
      add_survival(*tree, 0, born, t, out);
    }
    return out;
  };
  std::vector<double> node_tau, node_weight;
  double integral = 0.0, start = 0.0;
  while (start < 1.0) {
    while (born < m && tau[born] <= start) {
      move_power_sums(ages, tau[born] - anchor);
      anchor = std::max(anchor, tau[born]);
      ages[0] += 1.0;
      ++born;
    }
    const double panel_end = born < m ? tau[born] : 1.0;
    const SurvivalAt here = survival_at(start);
    const double survival = std::exp(here.log_survival);
    if (survival * (1.0 - start) <= 1e-17 * integral) break;
    const double width = std::min(panel_end - start, 2.0 / here.rate);
    const double end = width == panel_end - start ? panel_end : start + width;
    if (!(end > start)) break;
    const int q = points_for(here.rate * (end - start));
    const double mid = 0.5 * (start + end), half = 0.5 * (end - start);
    for (int i = 0; i < q; ++i) {
      const double t = mid + half * rules.nodes[static_cast<std::size_t>(q)][static_cast<std::size_t>(i)];
      const double w = half * rules.weights[static_cast<std::size_t>(q)][static_cast<std::size_t>(i)] * std::exp(survival_at(t).log_survival);
      integral += w;
      if (!derivatives.empty()) {
        node_tau.push_back(t);
        node_weight.push_back(w);
      }
    }
    start = end;
  }
  if (!derivatives.empty()) {
    std::fill(derivatives.begin(), derivatives.end(), 0.0);
    if (!node_tau.empty() && node_tau.back() <= kRatio) {
      // Values from the youngest to the oldest; the sums hold the points after τ_j.
      std::array<double, kMoments + 1> after{};
      double at = tau[m - 1];
      std::size_t next = node_tau.size();  // points from here on are in the sums
      for (std::size_t j = m; j-- > 0;) {
        move_power_sums(after, at - tau[j]);
        at = tau[j];
        while (next > 0 && node_tau[next - 1] > at) {
          --next;
          const double e = node_tau[next] - at;
          double term = node_weight[next];
          for (int k = 0; k <= kMoments; ++k, term *= e) after[static_cast<std::size_t>(k)] += term;
        }
        double p = 0.0;
        for (int k = 0; k <= kMoments; ++k) {
          p += after[static_cast<std::size_t>(k)];
          if (after[static_cast<std::size_t>(k)] <= 1e-19 * p) break;
        }
        derivatives[j] = p;
      }
    } else {
      const PowerSumTree nodes(node_tau, node_weight, false);
      for (std::size_t j = 0; j < m; ++j) {
        const std::size_t first = static_cast<std::size_t>(std::upper_bound(node_tau.begin(), node_tau.end(), tau[j]) - node_tau.begin());
        if (first < node_tau.size()) derivatives[j] = add_probability(nodes, 0, first, tau[j]);
      }
    }
  }
  return integral;
}

}  // namespace

double smooth_minimum(double a, double b, double k) {
  const double h = std::max(k - std::abs(a - b), 0.0) / k;
  return std::min(a, b) - h * h * h * k / 6.0;
}

double smooth_minimum(std::span<const double> values, double k, std::span<double> derivatives) {
  const std::size_t n = values.size();
  const double least = *std::min_element(values.begin(), values.end());
  std::vector<std::pair<double, std::size_t>> active;  // (τ_i, i), sorted
  for (std::size_t i = 0; i < n; ++i) {
    const double tau = (values[i] - least) / k;
    if (tau < 1.0) active.emplace_back(tau, i);
  }
  std::sort(active.begin(), active.end());
  const std::size_t m = active.size();
  if (!derivatives.empty()) std::fill(derivatives.begin(), derivatives.end(), 0.0);
  if (m == 1) {
    if (!derivatives.empty()) derivatives[active[0].second] = 1.0;
    return least;
  }
  std::vector<double> tau(m);
  for (std::size_t r = 0; r < m; ++r) tau[r] = active[r].first;
  double integral = 0.0;
  if (m <= (derivatives.empty() ? kExactValueLimit : kExactDerivativeLimit)) {
    integral = exact_survival_integral(tau, m, 0);
    if (!derivatives.empty())
      for (std::size_t r = 0; r < m; ++r) derivatives[active[r].second] = exact_survival_integral(tau, r, r);
  } else {
    std::vector<double> sorted_derivatives(derivatives.empty() ? 0 : m);
    integral = quadrature_survival_integral(tau, sorted_derivatives);
    for (std::size_t r = 0; r < sorted_derivatives.size(); ++r) derivatives[active[r].second] = sorted_derivatives[r];
  }
  // least − k/2 + k I, written so that the correction k (1/2 − I) ≥ 0 is formed first.
  return least - k * (0.5 - integral);
}

}  // namespace volspline
