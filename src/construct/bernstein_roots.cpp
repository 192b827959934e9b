#include "bernstein_roots.h"

#include <cmath>
#include <cstddef>
#include <limits>
#include <utility>

namespace volspline {

namespace {

constexpr int kMaxDepth = 40;
// Spans examined at most; beyond this every remaining span with a sign change reports its
// midpoint (a safeguard: a polynomial of degree m has at most m roots, so real inputs stay far below).
constexpr std::size_t kMaxSpans = 4096;

// Sign changes of the coefficients, those within noise of 0 skipped; -1 if all are within it.
int sign_changes(const std::vector<double>& c, double noise) {
  int changes = 0, last = 0;
  bool any = false;
  for (const double v : c) {
    if (std::abs(v) <= noise) continue;
    const int sign = v > 0 ? 1 : -1;
    if (any && sign != last) ++changes;
    last = sign;
    any = true;
  }
  return any ? changes : -1;
}

// Brent's method (Brent 1973, ch. 4 "zero") on [a, b] with f(a) f(b) < 0.
double brent_root(const BernsteinTensor<1>& f, double a, double b, double fa, double fb) {
  const double eps = std::numeric_limits<double>::epsilon();
  double c = a, fc = fa, d = b - a, e = d;
  for (int iteration = 0; iteration < 200; ++iteration) {
    if ((fb > 0) == (fc > 0)) {
      c = a;
      fc = fa;
      d = e = b - a;
    }
    if (std::abs(fc) < std::abs(fb)) {
      a = b;
      b = c;
      c = a;
      fa = fb;
      fb = fc;
      fc = fa;
    }
    const double tolerance = 2 * eps * std::abs(b);
    const double m = 0.5 * (c - b);
    if (std::abs(m) <= tolerance || fb == 0) return b;
    if (std::abs(e) < tolerance || std::abs(fa) <= std::abs(fb)) {
      d = e = m;
    } else {
      double p, q, r;
      const double s = fb / fa;
      if (a == c) {
        p = 2 * m * s;
        q = 1 - s;
      } else {
        q = fa / fc;
        r = fb / fc;
        p = s * (2 * m * q * (q - r) - (b - a) * (r - 1));
        q = (q - 1) * (r - 1) * (s - 1);
      }
      if (p > 0) q = -q;
      else p = -p;
      if (2 * p < std::min(3 * m * q - std::abs(tolerance * q), std::abs(e * q))) {
        e = d;
        d = p / q;
      } else {
        d = e = m;
      }
    }
    a = b;
    fa = fb;
    b += std::abs(d) > tolerance ? d : (m > 0 ? tolerance : -tolerance);
    fb = bernstein_evaluate(f, {b});
  }
  return b;
}

}  // namespace

std::vector<double> bernstein_roots(const BernsteinTensor<1>& f, double noise) {
  struct Span {
    BernsteinTensor<1> piece;
    double lo, hi;
    int depth;
  };
  std::vector<double> roots;
  std::vector<Span> stack{{f, 0.0, 1.0, 0}};
  std::size_t examined = 0;
  while (!stack.empty()) {
    Span span = std::move(stack.back());
    stack.pop_back();
    const std::vector<double>& c = span.piece.coefficients;
    const int changes = sign_changes(c, noise);
    if (changes == 0) continue;
    const double mid = 0.5 * (span.lo + span.hi);
    if (changes < 0) {
      roots.push_back(mid);
      continue;
    }
    const double first = c.front(), last = c.back();
    if (changes == 1 && std::abs(first) > noise && std::abs(last) > noise && (first > 0) != (last > 0)) {
      roots.push_back(brent_root(f, span.lo, span.hi, first, last));
      continue;
    }
    if (span.depth >= kMaxDepth || ++examined > kMaxSpans) {
      roots.push_back(mid);
      continue;
    }
    Span left{{}, span.lo, mid, span.depth + 1}, right{{}, mid, span.hi, span.depth + 1};
    bernstein_split(span.piece, 0, 0.5, left.piece, right.piece);
    stack.push_back(std::move(right));
    stack.push_back(std::move(left));
  }
  return roots;
}

}  // namespace volspline
