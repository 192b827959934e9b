#include "volspline/core/knot_vector.h"

#include <algorithm>
#include <cmath>
#include <string>

#include "volspline/core/error.h"
#include "volspline/core/format.h"

namespace volspline {

KnotVector::KnotVector(int degree, std::vector<double> knots) : degree_(degree), knots_(std::move(knots)) {
  if (degree_ < 1) {
    throw InvalidInput("degree must be at least 1, got " + std::to_string(degree_));
  }
  const std::size_t p = static_cast<std::size_t>(degree_);
  for (std::size_t i = 0; i < knots_.size(); ++i) {
    if (!std::isfinite(knots_[i])) {
      throw InvalidInput("expected a finite number, got " + format_double(knots_[i]),
                         "[" + std::to_string(i) + "]");
    }
    if (i > 0 && knots_[i] < knots_[i - 1]) {
      throw InvalidInput("knots must not decrease: " + format_double(knots_[i]) + " follows " +
                             format_double(knots_[i - 1]),
                         "[" + std::to_string(i) + "]");
    }
    if (i > p && knots_[i] == knots_[i - p - 1]) {
      throw InvalidInput("knot " + format_double(knots_[i]) + " has multiplicity above degree + 1 = " +
                             std::to_string(p + 1),
                         "[" + std::to_string(i) + "]");
    }
  }
  if (knots_.size() < 2 * (p + 1)) {
    throw InvalidInput("a knot vector of degree " + std::to_string(p) + " needs at least " +
                       std::to_string(2 * (p + 1)) + " knots, got " + std::to_string(knots_.size()));
  }
  if (!(domain_min() < domain_max())) {
    throw InvalidInput("the domain [t_p, t_{m-p}] = [" + format_double(domain_min()) + ", " +
                       format_double(domain_max()) + "] is empty");
  }
  const int per_span = degree_ * (degree_ + 1) / 2;
  inverse_differences_.assign(static_cast<std::size_t>((num_basis() - degree_) * per_span), 0.0);
  for (int span = degree_; span < num_basis(); ++span) {
    if (knots_[static_cast<std::size_t>(span)] == knots_[static_cast<std::size_t>(span) + 1]) continue;  // empty: never used
    double* inv = inverse_differences_.data() + static_cast<std::size_t>((span - degree_) * per_span);
    for (int j = 1; j <= degree_; ++j)
      for (int i = 0; i < j; ++i)
        inv[j * (j - 1) / 2 + i] =
            1.0 / (knots_[static_cast<std::size_t>(span + i + 1)] - knots_[static_cast<std::size_t>(span + 1 - j + i)]);
  }
}

KnotVector KnotVector::bezier(int degree, double a, double b) {
  // Checked before the copies are sized (the constructor checks it again).
  if (degree < 1) throw InvalidInput("degree must be at least 1, got " + std::to_string(degree));
  std::vector<double> k(static_cast<std::size_t>(degree + 1), a);
  k.insert(k.end(), static_cast<std::size_t>(degree + 1), b);
  return KnotVector(degree, std::move(k));
}

KnotVector KnotVector::uniform_clamped(int degree, int spans, double a, double b) {
  if (spans < 1) throw InvalidInput("a knot vector needs at least one span");
  if (degree < 1) throw InvalidInput("degree must be at least 1, got " + std::to_string(degree));
  std::vector<double> k(static_cast<std::size_t>(degree + 1), a);
  for (int i = 1; i < spans; ++i) k.push_back(a + (b - a) * i / spans);
  k.insert(k.end(), static_cast<std::size_t>(degree + 1), b);
  return KnotVector(degree, std::move(k));
}

bool KnotVector::is_clamped() const {
  const auto p = static_cast<std::size_t>(degree_);
  const std::size_t m = knots_.size() - 1;
  return knots_[0] == knots_[p] && knots_[m] == knots_[m - p];
}

bool KnotVector::is_bezier() const {
  return is_clamped() && num_basis() == degree_ + 1;
}

int KnotVector::find_span(double t) const {
  const int n = num_basis();
  const double* k = knots_.data();
  if (t >= k[n]) {
    // Upper end of the domain: the last nonempty span (closed at the top).
    int s = n - 1;
    while (k[s] == k[s + 1]) --s;
    return s;
  }
  // The largest s in [p, n-1] with t_s <= t; branch-free halving, since the comparison outcome
  // is unpredictable for scattered parameters.
  const double* base = k + degree_;
  std::size_t len = static_cast<std::size_t>(n - degree_);
  while (len > 1) {
    const std::size_t half = len / 2;
    base = (base[half] <= t) ? base + half : base;
    len -= half;
  }
  return static_cast<int>(base - k);
}

int KnotVector::find_span_left(double t) const {
  if (t <= domain_min()) return find_span(t);
  const auto first_not_below = std::lower_bound(knots_.begin(), knots_.end(), t);
  int s = static_cast<int>(first_not_below - knots_.begin()) - 1;  // last knot < t
  return std::clamp(s, degree_, num_basis() - 1);
}

namespace {

// The Cox-de Boor triangle (Piegl & Tiller A2.2) with the reciprocal knot differences
// precomputed. Its last step divides each degree p-1 function by its support length,
// N_{a,p-1} / (t_{a+p} - t_a); the derivative of a degree p function is p times the difference of
// two such quotients (Piegl & Tiller eq. 2.7), so values and first derivatives come from one
// pass. Instantiated with a compile-time degree (Fixed > 0) for the common degrees, so that the
// triangle stays in registers: the generic loop is bound by store-to-load latency.
template <int Fixed, bool WithDerivatives>
void cox_de_boor(const double* k, const double* inv, int span, double t, int runtime_degree, double* out) {
  const int p = Fixed > 0 ? Fixed : runtime_degree;
  constexpr int kStack = Fixed > 0 ? Fixed + 1 : 33;
  double stack[4 * kStack];
  std::vector<double> heap;
  double* N = stack;
  if (p + 1 > kStack) {
    heap.resize(4 * static_cast<std::size_t>(p + 1));
    N = heap.data();
  }
  double* l = N + (p + 1);
  double* r = l + (p + 1);
  double* quotients = r + (p + 1);
  N[0] = 1.0;
  for (int j = 1; j <= p; ++j) {
    l[j] = t - k[span + 1 - j];
    r[j] = k[span + j] - t;
    double saved = 0.0;
    const double* inv_j = inv + j * (j - 1) / 2;
    for (int i = 0; i < j; ++i) {
      const double q = N[i] * inv_j[i];  // N[i] / (r[i + 1] + l[j - i])
      N[i] = saved + r[i + 1] * q;
      saved = l[j - i] * q;
      if (j == p) quotients[i] = q;
    }
    N[j] = saved;
  }
  for (int i = 0; i <= p; ++i) out[i] = N[i];
  if constexpr (WithDerivatives) {
    for (int i = 0; i <= p; ++i) out[p + 1 + i] = p * ((i > 0 ? quotients[i - 1] : 0.0) - (i < p ? quotients[i] : 0.0));
  }
}

template <bool WithDerivatives>
void basis_any_degree(int p, const double* k, const double* inv, int span, double t, double* out) {
  switch (p) {
    case 1: return cox_de_boor<1, WithDerivatives>(k, inv, span, t, p, out);
    case 2: return cox_de_boor<2, WithDerivatives>(k, inv, span, t, p, out);
    case 3: return cox_de_boor<3, WithDerivatives>(k, inv, span, t, p, out);
    case 4: return cox_de_boor<4, WithDerivatives>(k, inv, span, t, p, out);
    case 5: return cox_de_boor<5, WithDerivatives>(k, inv, span, t, p, out);
    default: return cox_de_boor<0, WithDerivatives>(k, inv, span, t, p, out);
  }
}

}  // namespace

void KnotVector::basis(int span, double t, double* N) const {
  basis_any_degree<false>(degree_, knots_.data(), inverse_differences(span), span, t, N);
}

void KnotVector::basis_first_derivatives(int span, double t, double* values) const {
  basis_any_degree<true>(degree_, knots_.data(), inverse_differences(span), span, t, values);
}

void KnotVector::basis_derivatives(int span, double t, int order, double* values) const {
  // Piegl & Tiller A2.3: the triangle of basis functions of all degrees, then derivatives from
  // differences of lower-degree functions. Scratch lives on the stack for degrees below 16.
  const int p = degree_;
  const int P1 = p + 1;
  constexpr int kStack = 16;
  double stack[kStack * kStack + 4 * kStack];
  std::vector<double> heap;
  double* scratch = stack;
  if (P1 > kStack) {
    heap.resize(static_cast<std::size_t>(P1 * P1 + 4 * P1));
    scratch = heap.data();
  }
  double* ndu = scratch;
  double* left = ndu + P1 * P1;
  double* right = left + P1;
  double* a = right + P1;
  auto NDU = [&](int r, int c) -> double& { return ndu[r * P1 + c]; };
  const double* k = knots_.data();
  NDU(0, 0) = 1.0;
  for (int j = 1; j <= p; ++j) {
    left[j] = t - k[span + 1 - j];
    right[j] = k[span + j] - t;
    double saved = 0.0;
    for (int r = 0; r < j; ++r) {
      NDU(j, r) = right[r + 1] + left[j - r];  // lower triangle: knot differences
      const double temp = NDU(r, j - 1) / NDU(j, r);
      NDU(r, j) = saved + right[r + 1] * temp;
      saved = left[j - r] * temp;
    }
    NDU(j, j) = saved;
  }
  for (int j = 0; j <= p; ++j) values[j] = NDU(j, p);
  const int n = std::min(order, p);
  for (int kk = p + 1; kk <= order; ++kk)
    for (int j = 0; j <= p; ++j) values[kk * P1 + j] = 0.0;
  double* a0 = a;
  double* a1 = a + P1;
  for (int r = 0; r <= p; ++r) {
    int s1 = 0, s2 = 1;
    double* as[2] = {a0, a1};
    as[0][0] = 1.0;
    for (int kk = 1; kk <= n; ++kk) {
      double d = 0.0;
      const int rk = r - kk, pk = p - kk;
      if (r >= kk) {
        as[s2][0] = as[s1][0] / NDU(pk + 1, rk);
        d = as[s2][0] * NDU(rk, pk);
      }
      const int j1 = rk >= -1 ? 1 : -rk;
      const int j2 = (r - 1 <= pk) ? kk - 1 : p - r;
      for (int j = j1; j <= j2; ++j) {
        as[s2][j] = (as[s1][j] - as[s1][j - 1]) / NDU(pk + 1, rk + j);
        d += as[s2][j] * NDU(rk + j, pk);
      }
      if (r <= pk) {
        as[s2][kk] = -as[s1][kk - 1] / NDU(pk + 1, r);
        d += as[s2][kk] * NDU(r, pk);
      }
      values[kk * P1 + r] = d;
      std::swap(s1, s2);
    }
  }
  double factor = p;
  for (int kk = 1; kk <= n; ++kk) {
    for (int j = 0; j <= p; ++j) values[kk * P1 + j] *= factor;
    factor *= (p - kk);
  }
}

std::vector<double> KnotVector::breakpoints() const {
  std::vector<double> b;
  const auto lo = static_cast<std::size_t>(degree_);
  const auto hi = knots_.size() - lo - 1;
  for (std::size_t i = lo; i <= hi; ++i)
    if (b.empty() || knots_[i] != b.back()) b.push_back(knots_[i]);
  return b;
}

std::vector<double> KnotVector::greville_abscissae() const {
  std::vector<double> g(static_cast<std::size_t>(num_basis()));
  for (int i = 0; i < num_basis(); ++i) {
    double sum = 0;
    for (int j = 1; j <= degree_; ++j) sum += knots_[static_cast<std::size_t>(i + j)];
    g[static_cast<std::size_t>(i)] = sum / degree_;
  }
  return g;
}

int KnotVector::multiplicity(double t) const {
  return static_cast<int>(std::count(knots_.begin(), knots_.end(), t));
}

}  // namespace volspline
