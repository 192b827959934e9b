#include "volspline/spline/degree_elevation.h"

#include <algorithm>
#include <string>

#include "directional.h"
#include "volspline/core/binomial.h"
#include "volspline/core/error.h"
#include "volspline/spline/knot_insertion.h"

namespace volspline {

namespace {


// Piegl & Tiller, The NURBS Book, A5.9 (DegreeElevateCurve), on lines whose points are blocks
// of B numbers: each Bézier segment is extracted by knot insertion, elevated with the Bézier
// elevation coefficients, and the surplus knots are removed again, segment by segment.
void elevate_line(const std::vector<double>& U, int p, int t, const double* Pw, double* Qw, std::size_t B) {
  const int m = static_cast<int>(U.size()) - 1;
  const int ph = p + t, ph2 = ph / 2;
  std::vector<double> bezalfs(static_cast<std::size_t>((ph + 1) * (p + 1)), 0.0);
  auto BA = [&](int i, int j) -> double& { return bezalfs[static_cast<std::size_t>(i * (p + 1) + j)]; };
  BA(0, 0) = BA(ph, p) = 1.0;
  for (int i = 1; i <= ph2; ++i) {
    const double inv = 1.0 / binomial_coefficient(ph, i);
    for (int j = std::max(0, i - t); j <= std::min(p, i); ++j) BA(i, j) = inv * binomial_coefficient(p, j) * binomial_coefficient(t, i - j);
  }
  for (int i = ph2 + 1; i <= ph - 1; ++i)
    for (int j = std::max(0, i - t); j <= std::min(p, i); ++j) BA(i, j) = BA(ph - i, p - j);

  std::vector<double> bpts(static_cast<std::size_t>(p + 1) * B), ebpts(static_cast<std::size_t>(ph + 1) * B),
      next(static_cast<std::size_t>(std::max(p - 1, 1)) * B), alfs(static_cast<std::size_t>(std::max(p - 1, 1)));
  std::vector<double> Uh;  // the new knots, rebuilt as in A5.9 to drive the knot removal
  auto bp = [&](int i) { return bpts.data() + static_cast<std::size_t>(i) * B; };
  auto ep = [&](int i) { return ebpts.data() + static_cast<std::size_t>(i) * B; };
  auto np = [&](int i) { return next.data() + static_cast<std::size_t>(i) * B; };
  auto qp = [&](int i) { return Qw + static_cast<std::size_t>(i) * B; };
  auto pp = [&](int i) { return Pw + static_cast<std::size_t>(i) * B; };
  auto copy = [&](const double* src, double* dst) { std::copy(src, src + B, dst); };

  int kind = ph + 1, r = -1, a = p, b = p + 1, cind = 1;
  double ua = U[0];
  copy(pp(0), qp(0));
  Uh.assign(static_cast<std::size_t>(ph + 1), ua);
  for (int i = 0; i <= p; ++i) copy(pp(i), bp(i));
  while (b < m) {
    const int i0 = b;
    while (b < m && U[static_cast<std::size_t>(b)] == U[static_cast<std::size_t>(b + 1)]) ++b;
    const int mul = b - i0 + 1;
    const double ub = U[static_cast<std::size_t>(b)];
    const int oldr = r;
    r = p - mul;
    const int lbz = oldr > 0 ? (oldr + 2) / 2 : 1;
    const int rbz = r > 0 ? ph - (r + 1) / 2 : ph;
    if (r > 0) {  // insert ub r times to isolate the Bézier segment [ua, ub]
      const double numer = ub - ua;
      for (int k = p; k > mul; --k) alfs[static_cast<std::size_t>(k - mul - 1)] = numer / (U[static_cast<std::size_t>(a + k)] - ua);
      for (int j = 1; j <= r; ++j) {
        const int save = r - j, s = mul + j;
        for (int k = p; k >= s; --k) {
          const double al = alfs[static_cast<std::size_t>(k - s)];
          detail::axpby(al, bp(k), 1.0 - al, bp(k - 1), bp(k), B);
        }
        copy(bp(p), np(save));
      }
    }
    for (int i = lbz; i <= ph; ++i) {  // elevate the Bézier segment
      double* e = ep(i);
      std::fill(e, e + B, 0.0);
      for (int j = std::max(0, i - t); j <= std::min(p, i); ++j) {
        const double c = BA(i, j);
        const double* src = bp(j);
        for (std::size_t x = 0; x < B; ++x) e[x] += c * src[x];
      }
    }
    if (oldr > 1) {  // remove the knot ua oldr - 1 times
      int first = kind - 2, last = kind;
      const double den = ub - ua;
      const double bet = (ub - Uh[static_cast<std::size_t>(kind - 1)]) / den;
      for (int tr = 1; tr < oldr; ++tr) {
        int i = first, j = last, kj = j - kind + 1;
        while (j - i > tr) {
          if (i < cind) {
            const double alf = (ub - Uh[static_cast<std::size_t>(i)]) / (ua - Uh[static_cast<std::size_t>(i)]);
            detail::axpby(alf, qp(i), 1.0 - alf, qp(i - 1), qp(i), B);
          }
          if (j >= lbz) {
            if (j - tr <= kind - ph + oldr) {
              const double gam = (ub - Uh[static_cast<std::size_t>(j - tr)]) / den;
              detail::axpby(gam, ep(kj), 1.0 - gam, ep(kj + 1), ep(kj), B);
            } else {
              detail::axpby(bet, ep(kj), 1.0 - bet, ep(kj + 1), ep(kj), B);
            }
          }
          ++i;
          --j;
          --kj;
        }
        --first;
        ++last;
      }
    }
    if (a != p)
      for (int i = 0; i < ph - oldr; ++i) {
        Uh.push_back(ua);
        ++kind;
      }
    for (int j = lbz; j <= rbz; ++j) copy(ep(j), qp(cind++));
    if (b < m) {
      for (int j = 0; j < r; ++j) copy(np(j), bp(j));
      for (int j = r; j <= p; ++j) copy(pp(b - p + j), bp(j));
      a = b;
      ++b;
      ua = ub;
    } else {
      for (int i = 0; i <= ph; ++i) Uh.push_back(ub);
    }
  }
}

}  // namespace

template <int D>
TensorSpline<D> elevate_degree(const TensorSpline<D>& spline, int direction, int times) {
  if (direction < 0 || direction >= D) throw InvalidInput("direction " + std::to_string(direction) + " does not exist");
  if (times < 0) throw InvalidInput("cannot elevate the degree by a negative amount");
  if (times == 0) return spline;
  TensorSpline<D> clamped = clamp(spline);
  const KnotVector& kv = clamped.knot_vector(direction);
  const int p = kv.degree();
  std::vector<double> knots;
  for (double b : kv.breakpoints()) {
    const int mult = kv.multiplicity(b) + times;
    knots.insert(knots.end(), static_cast<std::size_t>(mult), b);
  }
  KnotVector elevated(p + times, std::move(knots));
  // A5.9 assumes interior multiplicities <= p. At a knot of multiplicity p + 1 the spline
  // falls apart into independent pieces; elevate each and join them again.
  struct Segment {
    std::vector<double> knots;
    int first_row, first_new_row;
  };
  std::vector<Segment> segments;
  {
    const std::vector<double>& U = kv.knots();
    std::size_t start = 0;
    int row = 0, new_row = 0;
    for (std::size_t i = static_cast<std::size_t>(p + 1); i + static_cast<std::size_t>(p + 1) < U.size();) {
      const int mult = kv.multiplicity(U[i]);
      if (mult == p + 1) {
        std::vector<double> piece(U.begin() + static_cast<std::ptrdiff_t>(start), U.begin() + static_cast<std::ptrdiff_t>(i + static_cast<std::size_t>(p + 1)));
        const int count = static_cast<int>(piece.size()) - p - 1;
        const int new_count = KnotVector(p, piece).num_spans() * times + count;
        segments.push_back({std::move(piece), row, new_row});
        row += count;
        new_row += new_count;
        start = i;
      }
      i += static_cast<std::size_t>(mult);
    }
    segments.push_back({std::vector<double>(U.begin() + static_cast<std::ptrdiff_t>(start), U.end()), row, new_row});
  }
  return detail::transform_lines(clamped, direction, elevated, [&](const double* in, double* out, std::size_t B) {
    for (const Segment& seg : segments)
      elevate_line(seg.knots, p, times, in + static_cast<std::size_t>(seg.first_row) * B,
                   out + static_cast<std::size_t>(seg.first_new_row) * B, B);
  });
}

template TensorSpline<1> elevate_degree(const TensorSpline<1>&, int, int);
template TensorSpline<2> elevate_degree(const TensorSpline<2>&, int, int);
template TensorSpline<3> elevate_degree(const TensorSpline<3>&, int, int);
template TensorSpline<4> elevate_degree(const TensorSpline<4>&, int, int);

}  // namespace volspline
