#include "volspline/core/bernstein_tensor.h"

#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

#include "volspline/core/error.h"

namespace volspline {

namespace {

void check_direction(int direction, int dimension) {
  if (direction < 0 || direction >= dimension) {
    throw InvalidInput("direction must be in [0, " + std::to_string(dimension) + "), got " + std::to_string(direction));
  }
}

void check_component(int component, int components) {
  if (component < 0 || component >= components) {
    throw InvalidInput("component " + std::to_string(component) + " does not exist (the polynomial has " +
                       std::to_string(components) + ")");
  }
}

// Calls visit(a) for every multi-index 0 <= a < sizes in storage order (first index fastest).
template <int D, class Visit>
void for_each_index(const std::array<int, D>& sizes, Visit&& visit) {
  for (int s : sizes) {
    if (s <= 0) return;
  }
  std::array<int, D> a{};
  while (true) {
    visit(a);
    int d = 0;
    while (d < D && ++a[static_cast<std::size_t>(d)] == sizes[static_cast<std::size_t>(d)]) a[static_cast<std::size_t>(d++)] = 0;
    if (d == D) return;
  }
}

template <int D>
std::array<int, D> sizes_of(const std::array<int, D>& degrees) {
  std::array<int, D> n{};
  for (std::size_t d = 0; d < static_cast<std::size_t>(D); ++d) n[d] = degrees[d] + 1;
  return n;
}

// The product of the binomials of multi-index a: C(n_0, a_0) C(n_1, a_1) ..., multiplied into
// `value` one direction at a time (scale) or formed first and divided by (unscale). Both orders
// are those the certified Jacobian bound was derived for (docs/jacobian.md).
template <int D>
void scale_coefficients(TensorCoefficients<D>& f, bool divide) {
  const std::size_t c = static_cast<std::size_t>(f.components);
  // One table row per direction, looked up once (this runs for every product of the Jacobian).
  // Degrees beyond the table (never reached by models: kMaxModelDegree) take the product formula.
  std::array<std::vector<double>, D> beyond;
  std::array<const double*, D> rows{};
  for (std::size_t d = 0; d < static_cast<std::size_t>(D); ++d) {
    if (f.degrees[d] <= kBinomialTableOrder) {
      rows[d] = binomial_row(f.degrees[d]);
    } else {
      for (int k = 0; k <= f.degrees[d]; ++k) beyond[d].push_back(binomial_coefficient(f.degrees[d], k));
      rows[d] = beyond[d].data();
    }
  }
  std::size_t linear = 0;
  for_each_index<D>(sizes_of<D>(f.degrees), [&](const std::array<int, D>& a) {
    double* x = f.coefficients.data() + linear * c;
    if (divide) {
      double b = 1;
      for (std::size_t d = 0; d < static_cast<std::size_t>(D); ++d) b *= rows[d][a[d]];
      for (std::size_t k = 0; k < c; ++k) x[k] /= b;
    } else {
      for (std::size_t k = 0; k < c; ++k) {
        for (std::size_t d = 0; d < static_cast<std::size_t>(D); ++d) x[k] *= rows[d][a[d]];
      }
    }
    ++linear;
  });
}

// The same coefficients in the other basis (scaled or not).
template <class To, int D>
To rescaled(TensorCoefficients<D> f, bool divide) {
  To t;
  t.degrees = f.degrees;
  t.components = f.components;
  t.coefficients = std::move(f.coefficients);
  scale_coefficients<D>(t, divide);
  return t;
}

// The components of a product: equal counts, or a scalar factor.
int product_components(int a, int b) {
  if (a == b || b == 1) return a;
  if (a == 1) return b;
  throw InvalidInput("cannot multiply polynomials with " + std::to_string(a) + " and " + std::to_string(b) +
                     " components (equal counts or a scalar factor)");
}

// Scalar convolution: the D nested loops of o[a + b] += av * b_b over the coefficients of b,
// innermost along direction 0 where both are contiguous.
template <int D, int d>
inline void convolve_rows(const double* __restrict b, const std::array<std::size_t, D>& b_stride, const std::array<int, D>& b_size,
                          double* __restrict o, const std::array<std::size_t, D>& o_stride, double av) {
  if constexpr (d == 0) {
    for (int i = 0; i < b_size[0]; ++i) o[i] += av * b[i];
  } else {
    for (int i = 0; i < b_size[static_cast<std::size_t>(d)]; ++i) {
      convolve_rows<D, d - 1>(b + static_cast<std::size_t>(i) * b_stride[static_cast<std::size_t>(d)], b_stride, b_size,
                              o + static_cast<std::size_t>(i) * o_stride[static_cast<std::size_t>(d)], o_stride, av);
    }
  }
}

template <int D, int d>
inline void convolve_scalar(const double* a, const std::array<std::size_t, D>& a_stride, const std::array<int, D>& a_size,
                            const double* b, const std::array<std::size_t, D>& b_stride, const std::array<int, D>& b_size,
                            double* o, const std::array<std::size_t, D>& o_stride, double sign) {
  const std::size_t dd = static_cast<std::size_t>(d);
  for (int i = 0; i < a_size[dd]; ++i) {
    const double* ai = a + static_cast<std::size_t>(i) * a_stride[dd];
    double* oi = o + static_cast<std::size_t>(i) * o_stride[dd];
    if constexpr (d == 0) {
      const double av = sign * *ai;
      if (av == 0) continue;
      convolve_rows<D, D - 1>(b, b_stride, b_size, oi, o_stride, av);
    } else {
      convolve_scalar<D, d - 1>(ai, a_stride, a_size, b, b_stride, b_size, oi, o_stride, sign);
    }
  }
}

template <int D>
std::array<std::size_t, D> strides_of(const TensorCoefficients<D>& f) {
  std::array<std::size_t, D> s{};
  for (int d = 0; d < D; ++d) s[static_cast<std::size_t>(d)] = f.stride(d);
  return s;
}

}  // namespace

template <int D>
TensorCoefficients<D>::TensorCoefficients(const std::array<int, D>& d, int c) : degrees(d), components(c) {
  std::size_t n = 1;
  for (int x : d) {
    if (x < 0) throw InvalidInput("Bernstein degrees must be >= 0, got " + std::to_string(x));
    n *= static_cast<std::size_t>(x + 1);
  }
  if (c < 1) throw InvalidInput("a Bernstein polynomial needs at least one component, got " + std::to_string(c));
  coefficients.assign(n * static_cast<std::size_t>(c), 0.0);
}

template <int D>
void bernstein_evaluate(const BernsteinTensor<D>& f, const BernsteinPoint<D>& s, double* values) {
  const std::size_t c = static_cast<std::size_t>(f.components);
  std::vector<double> work = f.coefficients;
  // Collapse direction 0, then 1, ...; after each step the data is contiguous again.
  for (int d = 0; d < D; ++d) {
    const int len = f.size(d);
    const double t = s[static_cast<std::size_t>(d)], t1 = 1 - t;
    std::size_t outer = 1;
    for (int e = d + 1; e < D; ++e) outer *= static_cast<std::size_t>(f.size(e));
    for (std::size_t o = 0; o < outer; ++o) {
      double* line = work.data() + o * static_cast<std::size_t>(len) * c;
      for (int r = 1; r < len; ++r) {
        for (std::size_t i = 0; i + static_cast<std::size_t>(r) < static_cast<std::size_t>(len); ++i) {
          for (std::size_t k = 0; k < c; ++k) line[i * c + k] = t1 * line[i * c + k] + t * line[(i + 1) * c + k];
        }
      }
      for (std::size_t k = 0; k < c; ++k) work[o * c + k] = line[k];
    }
  }
  std::copy(work.begin(), work.begin() + static_cast<std::ptrdiff_t>(c), values);
}

template <int D>
double bernstein_evaluate(const BernsteinTensor<D>& f, const BernsteinPoint<D>& s) {
  if (f.components != 1) {
    throw InvalidInput("a polynomial with " + std::to_string(f.components) + " components has no single value");
  }
  double value = 0;
  bernstein_evaluate(f, s, &value);
  return value;
}

template <int D>
void bernstein_split(const BernsteinTensor<D>& f, int direction, double t, BernsteinTensor<D>& left, BernsteinTensor<D>& right) {
  check_direction(direction, D);
  if (&left == &f || &right == &f || &left == &right) throw InvalidInput("bernstein_split needs two outputs distinct from its input");
  for (BernsteinTensor<D>* half : {&left, &right}) {
    half->degrees = f.degrees;
    half->components = f.components;
  }
  // De Casteljau runs in place in the right half, a copy of f: after step s, row len - 1 - s is
  // final (later steps only touch rows before it) and row 0 is the left half's row s. Every
  // coefficient of the left half is written below, so only its size is set here.
  right.coefficients.assign(f.coefficients.begin(), f.coefficients.end());
  left.coefficients.resize(f.coefficients.size());
  // The coefficients are blocks [outer][i][inner]: i the index along `direction`, `inner` the
  // contiguous numbers of the faster directions and the components. The steps run on whole
  // rows of `inner` numbers at once (the same operations per number as one line at a time, so
  // the same results to the bit), which the compiler vectorises; this was the hot spot of the
  // rank-deficient subdivision (Conkey–Joy §5), whose tensors have (3p+1)^4 4-vectors.
  const auto len = static_cast<std::size_t>(f.size(direction));
  const std::size_t inner = f.stride(direction) * static_cast<std::size_t>(f.components);
  const std::size_t block = len * inner;
  const std::size_t outer = f.coefficients.size() / block;
  const double t1 = 1 - t;
  for (std::size_t o = 0; o < outer; ++o) {
    double* w = right.coefficients.data() + o * block;
    double* l = left.coefficients.data() + o * block;
    std::copy_n(w, inner, l);
    for (std::size_t step = 1; step < len; ++step) {
      for (std::size_t i = 0; i + step < len; ++i) {
        double* a = w + i * inner;
        const double* b = a + inner;
        for (std::size_t x = 0; x < inner; ++x) a[x] = t1 * a[x] + t * b[x];
      }
      std::copy_n(w, inner, l + step * inner);
    }
  }
}

template <int D>
std::pair<BernsteinTensor<D>, BernsteinTensor<D>> bernstein_split(const BernsteinTensor<D>& f, int direction, double t) {
  std::pair<BernsteinTensor<D>, BernsteinTensor<D>> halves;
  bernstein_split(f, direction, t, halves.first, halves.second);
  return halves;
}

template <int D>
  requires(D >= 2)
BernsteinTensor<D - 1> bernstein_face(const BernsteinTensor<D>& f, int direction, int side) {
  check_direction(direction, D);
  if (side != 0 && side != 1) throw InvalidInput("a face is at side 0 or 1, got " + std::to_string(side));
  std::array<int, D - 1> degrees{};
  for (int d = 0, e = 0; d < D; ++d) {
    if (d != direction) degrees[static_cast<std::size_t>(e++)] = f.degrees[static_cast<std::size_t>(d)];
  }
  BernsteinTensor<D - 1> face(degrees, f.components);
  const std::size_t c = static_cast<std::size_t>(f.components);
  std::size_t linear = 0;
  for_each_index<D - 1>(sizes_of<D - 1>(degrees), [&](const std::array<int, D - 1>& b) {
    std::array<int, D> a{};
    for (int d = 0, e = 0; d < D; ++d) {
      a[static_cast<std::size_t>(d)] = d == direction ? side * f.degrees[static_cast<std::size_t>(d)] : b[static_cast<std::size_t>(e++)];
    }
    std::copy_n(f.coefficients.data() + f.index(a) * c, c, face.coefficients.data() + linear * c);
    ++linear;
  });
  return face;
}

template <int D>
BernsteinTensor<D> bernstein_divide_by_face(const BernsteinTensor<D>& f, int direction, int side) {
  check_direction(direction, D);
  if (side != 0 && side != 1) throw InvalidInput("a face is at side 0 or 1, got " + std::to_string(side));
  const int n = f.degrees[static_cast<std::size_t>(direction)];
  if (n < 1) throw InvalidInput("a polynomial of degree 0 along the direction has no factor to divide out");
  std::array<int, D> degrees = f.degrees;
  --degrees[static_cast<std::size_t>(direction)];
  BernsteinTensor<D> q(degrees, f.components);
  const std::size_t c = static_cast<std::size_t>(f.components);
  std::size_t linear = 0;
  for_each_index<D>(sizes_of<D>(degrees), [&](const std::array<int, D>& b) {
    const int j = b[static_cast<std::size_t>(direction)];
    std::array<int, D> a = b;
    double factor = 0;
    if (side == 0) {
      a[static_cast<std::size_t>(direction)] = j + 1;
      factor = static_cast<double>(n) / (j + 1);
    } else {
      factor = static_cast<double>(n) / (n - j);
    }
    const double* from = f.coefficients.data() + f.index(a) * c;
    double* to = q.coefficients.data() + linear * c;
    for (std::size_t k = 0; k < c; ++k) to[k] = from[k] * factor;
    ++linear;
  });
  return q;
}

template <int D>
std::pair<double, double> bernstein_coefficient_range(const BernsteinTensor<D>& f, int component) {
  check_component(component, f.components);
  if (f.coefficients.empty()) throw InvalidInput("the polynomial has no coefficients");
  const std::size_t c = static_cast<std::size_t>(f.components);
  double lo = f.coefficients[static_cast<std::size_t>(component)], hi = lo;
  for (std::size_t i = static_cast<std::size_t>(component); i < f.coefficients.size(); i += c) {
    lo = std::min(lo, f.coefficients[i]);
    hi = std::max(hi, f.coefficients[i]);
  }
  return {lo, hi};
}

template <int D>
double bernstein_max_abs(const BernsteinTensor<D>& f) {
  double m = 0;
  for (double x : f.coefficients) m = std::max(m, std::abs(x));
  return m;
}

template <int D>
BernsteinTensor<D> bernstein_derivative(const BernsteinTensor<D>& f, int direction, double interval_length) {
  check_direction(direction, D);
  const int n = f.degrees[static_cast<std::size_t>(direction)];
  if (n == 0) {
    std::array<int, D> zero = f.degrees;
    zero[static_cast<std::size_t>(direction)] = 0;
    return BernsteinTensor<D>(zero, f.components);
  }
  std::array<int, D> d = f.degrees;
  d[static_cast<std::size_t>(direction)] = n - 1;
  BernsteinTensor<D> g(d, f.components);
  const double factor = n / interval_length;
  const std::size_t c = static_cast<std::size_t>(f.components), step = f.stride(direction) * c;
  std::size_t out = 0;
  for_each_index<D>(sizes_of<D>(d), [&](const std::array<int, D>& a) {
    const double* x = f.coefficients.data() + f.index(a) * c;
    for (std::size_t k = 0; k < c; ++k) g.coefficients[out + k] = factor * (x[step + k] - x[k]);
    out += c;
  });
  return g;
}

template <int D>
std::pair<double, double> bernstein_derivative_range(const BernsteinTensor<D>& f, int direction, int component) {
  check_direction(direction, D);
  check_component(component, f.components);
  const int n = f.degrees[static_cast<std::size_t>(direction)];
  if (n == 0) return {0, 0};
  double lo = INFINITY, hi = -INFINITY;
  const std::size_t c = static_cast<std::size_t>(f.components), step = f.stride(direction) * c;
  std::array<int, D> sizes = sizes_of<D>(f.degrees);
  sizes[static_cast<std::size_t>(direction)] -= 1;
  for_each_index<D>(sizes, [&](const std::array<int, D>& a) {
    const double* x = f.coefficients.data() + f.index(a) * c + static_cast<std::size_t>(component);
    const double v = n * (x[step] - x[0]);
    lo = std::min(lo, v);
    hi = std::max(hi, v);
  });
  return {lo, hi};
}

template <int D>
ScaledBernsteinTensor<D> bernstein_scaled(const BernsteinTensor<D>& f) {
  return rescaled<ScaledBernsteinTensor<D>>(f, false);
}

template <int D>
ScaledBernsteinTensor<D> bernstein_scaled(BernsteinTensor<D>&& f) {
  return rescaled<ScaledBernsteinTensor<D>>(std::move(static_cast<TensorCoefficients<D>&>(f)), false);
}

template <int D>
BernsteinTensor<D> bernstein_unscaled(const ScaledBernsteinTensor<D>& f) {
  return rescaled<BernsteinTensor<D>>(f, true);
}

template <int D>
BernsteinTensor<D> bernstein_unscaled(ScaledBernsteinTensor<D>&& f) {
  return rescaled<BernsteinTensor<D>>(std::move(static_cast<TensorCoefficients<D>&>(f)), true);
}

template <int D>
void scaled_product_add(const ScaledBernsteinTensor<D>& a, const ScaledBernsteinTensor<D>& b, double sign,
                        ScaledBernsteinTensor<D>& out) {
  if (out.degrees != product_degrees(a.degrees, b.degrees) || out.components != product_components(a.components, b.components) ||
      out.coefficients.size() != out.count() * static_cast<std::size_t>(out.components)) {
    throw InvalidInput("scaled_product_add: the output does not have the product's degrees and components");
  }
  if (a.coefficients.empty() || b.coefficients.empty()) return;
  if (out.components == 1) {
    convolve_scalar<D, D - 1>(a.coefficients.data(), strides_of(a), sizes_of<D>(a.degrees), b.coefficients.data(), strides_of(b),
                              sizes_of<D>(b.degrees), out.coefficients.data(), strides_of(out), sign);
    return;
  }
  // Vector-valued: the same sums per component, component k of a scalar factor being its only one.
  const std::size_t c = static_cast<std::size_t>(out.components);
  const std::size_t ca = a.components == 1 ? 0 : 1, cb = b.components == 1 ? 0 : 1;
  std::vector<std::size_t> b_offsets;
  b_offsets.reserve(b.count());
  for_each_index<D>(sizes_of<D>(b.degrees), [&](const std::array<int, D>& j) { b_offsets.push_back(out.index(j)); });
  std::size_t ia = 0;
  for_each_index<D>(sizes_of<D>(a.degrees), [&](const std::array<int, D>& i) {
    const std::size_t oa = out.index(i);
    const double* av = a.coefficients.data() + ia * static_cast<std::size_t>(a.components);
    for (std::size_t ib = 0; ib < b_offsets.size(); ++ib) {
      const double* bv = b.coefficients.data() + ib * static_cast<std::size_t>(b.components);
      double* o = out.coefficients.data() + (oa + b_offsets[ib]) * c;
      for (std::size_t k = 0; k < c; ++k) o[k] += sign * av[k * ca] * bv[k * cb];
    }
    ++ia;
  });
}

template <int D>
BernsteinTensor<D> bernstein_product(const BernsteinTensor<D>& f, const BernsteinTensor<D>& g) {
  ScaledBernsteinTensor<D> h(product_degrees(f.degrees, g.degrees), product_components(f.components, g.components));
  scaled_product_add(bernstein_scaled(f), bernstein_scaled(g), 1.0, h);
  return bernstein_unscaled(std::move(h));
}

template <int D>
BernsteinTensor<D> bernstein_power(const BernsteinTensor<D>& f, int n) {
  if (n < 0) throw InvalidInput("a power must be >= 0, got " + std::to_string(n));
  if (n >= 2 && f.components != 1) throw InvalidInput("only a scalar polynomial has powers");
  BernsteinTensor<D> out(std::array<int, D>{}, 1);
  out.coefficients[0] = 1.0;
  for (int i = 0; i < n; ++i) out = bernstein_product(out, f);
  return out;
}

template <int D>
BernsteinTensor<D> bernstein_elevate(const BernsteinTensor<D>& f, const BernsteinDegrees<D>& degrees) {
  std::array<int, D> raise{};
  for (std::size_t d = 0; d < static_cast<std::size_t>(D); ++d) {
    if (degrees[d] < f.degrees[d]) throw InvalidInput("degree elevation cannot lower a degree");
    raise[d] = degrees[d] - f.degrees[d];
  }
  if (raise == std::array<int, D>{}) return f;
  // Multiplying by the constant 1 written in degree (r - n) raises the degree exactly.
  BernsteinTensor<D> one(raise, 1);
  std::fill(one.coefficients.begin(), one.coefficients.end(), 1.0);
  return bernstein_product(f, one);
}

template <int D>
void bernstein_add(BernsteinTensor<D>& sum, const BernsteinTensor<D>& f) {
  if (sum.degrees != f.degrees || sum.components != f.components || sum.coefficients.size() != f.coefficients.size()) {
    throw InvalidInput("bernstein_add needs polynomials of equal degrees and components");
  }
  for (std::size_t i = 0; i < sum.coefficients.size(); ++i) sum.coefficients[i] += f.coefficients[i];
}

template <int D>
BernsteinTensor<D> bernstein_components(const BernsteinTensor<D>& f, int first, int count) {
  if (first < 0 || count < 1 || first + count > f.components) {
    throw InvalidInput("components [" + std::to_string(first) + ", " + std::to_string(first + count) +
                       ") are not inside the polynomial's " + std::to_string(f.components));
  }
  BernsteinTensor<D> g(f.degrees, count);
  const std::size_t n = f.count(), c = static_cast<std::size_t>(f.components), k = static_cast<std::size_t>(count);
  for (std::size_t i = 0; i < n; ++i) {
    std::copy_n(f.coefficients.data() + i * c + static_cast<std::size_t>(first), k, g.coefficients.data() + i * k);
  }
  return g;
}

void bernstein_blossom(const BernsteinTensor<1>& f, const double* arguments, double* values) {
  const std::size_t c = static_cast<std::size_t>(f.components);
  std::vector<double> work = f.coefficients;
  const int q = f.degrees[0];
  for (int r = 1; r <= q; ++r) {
    const double lambda = arguments[r - 1];
    for (int j = 0; j <= q - r; ++j) {
      for (std::size_t k = 0; k < c; ++k) {
        const std::size_t i = static_cast<std::size_t>(j) * c + k;
        work[i] = (1.0 - lambda) * work[i] + lambda * work[i + c];
      }
    }
  }
  std::copy_n(work.begin(), c, values);
}

#define VOLSPLINE_BERNSTEIN_INSTANTIATE(D)                                                                          \
  template struct TensorCoefficients<D>;                                                                            \
  template double bernstein_evaluate(const BernsteinTensor<D>&, const BernsteinPoint<D>&);                      \
  template void bernstein_evaluate(const BernsteinTensor<D>&, const BernsteinPoint<D>&, double*);              \
  template std::pair<BernsteinTensor<D>, BernsteinTensor<D>> bernstein_split(const BernsteinTensor<D>&, int, double); \
  template void bernstein_split(const BernsteinTensor<D>&, int, double, BernsteinTensor<D>&, BernsteinTensor<D>&); \
  template std::pair<double, double> bernstein_coefficient_range(const BernsteinTensor<D>&, int);                   \
  template double bernstein_max_abs(const BernsteinTensor<D>&);                                                     \
  template BernsteinTensor<D> bernstein_derivative(const BernsteinTensor<D>&, int, double);                         \
  template std::pair<double, double> bernstein_derivative_range(const BernsteinTensor<D>&, int, int);               \
  template BernsteinTensor<D> bernstein_product(const BernsteinTensor<D>&, const BernsteinTensor<D>&);              \
  template BernsteinTensor<D> bernstein_power(const BernsteinTensor<D>&, int);                                      \
  template BernsteinTensor<D> bernstein_elevate(const BernsteinTensor<D>&, const BernsteinDegrees<D>&);              \
  template BernsteinTensor<D> bernstein_divide_by_face(const BernsteinTensor<D>&, int, int);                        \
  template void bernstein_add(BernsteinTensor<D>&, const BernsteinTensor<D>&);                                      \
  template BernsteinTensor<D> bernstein_components(const BernsteinTensor<D>&, int, int);                            \
  template ScaledBernsteinTensor<D> bernstein_scaled(const BernsteinTensor<D>&);                                    \
  template ScaledBernsteinTensor<D> bernstein_scaled(BernsteinTensor<D>&&);                                         \
  template BernsteinTensor<D> bernstein_unscaled(const ScaledBernsteinTensor<D>&);                                  \
  template BernsteinTensor<D> bernstein_unscaled(ScaledBernsteinTensor<D>&&);                                       \
  template void scaled_product_add(const ScaledBernsteinTensor<D>&, const ScaledBernsteinTensor<D>&, double,        \
                                   ScaledBernsteinTensor<D>&);

VOLSPLINE_BERNSTEIN_INSTANTIATE(1)
VOLSPLINE_BERNSTEIN_INSTANTIATE(2)
VOLSPLINE_BERNSTEIN_INSTANTIATE(3)
VOLSPLINE_BERNSTEIN_INSTANTIATE(4)
#undef VOLSPLINE_BERNSTEIN_INSTANTIATE

template BernsteinTensor<1> bernstein_face(const BernsteinTensor<2>&, int, int);
template BernsteinTensor<2> bernstein_face(const BernsteinTensor<3>&, int, int);
template BernsteinTensor<3> bernstein_face(const BernsteinTensor<4>&, int, int);

}  // namespace volspline
