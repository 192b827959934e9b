// Evaluation of tensor-product splines: scattered points and tensor grids, with partial
// derivatives of any order, polynomial and rational.
#include <algorithm>
#include <cmath>
#include <cstring>
#include <map>
#include <memory>
#include <mutex>
#include <string>
#include <utility>

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include "derivative_table.h"
#include "volspline/core/binomial.h"
#include "volspline/core/error.h"
#include "volspline/spline/tensor_spline.h"

namespace volspline {

namespace detail {

namespace {

template <int D>
std::unique_ptr<DerivativeTable<D>> build_derivative_table(int order) {
  auto table = std::make_unique<DerivativeTable<D>>();
  table->order = order;
  table->alphas = derivative_multi_indices<D>(order);
  int dense = 1;
  for (int d = 0; d < D; ++d) dense *= order + 1;
  table->position.assign(static_cast<std::size_t>(dense), -1);
  for (std::size_t i = 0; i < table->alphas.size(); ++i)
    table->position[static_cast<std::size_t>(table->dense_index(table->alphas[i]))] = static_cast<int>(i);
  table->leibniz.resize(table->alphas.size());
  for (std::size_t a = 0; a < table->alphas.size(); ++a) {
    const auto& alpha = table->alphas[a];
    for (std::size_t b = 1; b < table->alphas.size(); ++b) {
      const auto& beta = table->alphas[b];
      bool below = true;
      double binomial = 1.0;
      std::array<int, D> rest{};
      for (int d = 0; d < D; ++d) {
        const auto dd = static_cast<std::size_t>(d);
        if (beta[dd] > alpha[dd]) below = false;
        rest[dd] = alpha[dd] - beta[dd];
        if (beta[dd] <= alpha[dd]) binomial *= binomial_coefficient(alpha[dd], beta[dd]);
      }
      if (!below) continue;
      table->leibniz[a].push_back({static_cast<int>(b),
                                   table->position[static_cast<std::size_t>(table->dense_index(rest))], binomial});
    }
  }
  return table;
}

}  // namespace

template <int D>
const DerivativeTable<D>& derivative_table(int order) {
  // Orders used on hot paths are built once at first use; higher ones on demand.
  static constexpr int kPrebuilt = 4;
  static const auto prebuilt = [] {
    std::array<std::unique_ptr<DerivativeTable<D>>, kPrebuilt + 1> t;
    for (int n = 0; n <= kPrebuilt; ++n) t[static_cast<std::size_t>(n)] = build_derivative_table<D>(n);
    return t;
  }();
  if (order <= kPrebuilt) return *prebuilt[static_cast<std::size_t>(order)];
  static std::mutex mutex;
  static std::map<int, std::unique_ptr<DerivativeTable<D>>> tables;
  std::lock_guard lock(mutex);
  auto& slot = tables[order];
  if (!slot) slot = build_derivative_table<D>(order);
  return *slot;
}

template const DerivativeTable<1>& derivative_table<1>(int);
template const DerivativeTable<2>& derivative_table<2>(int);
template const DerivativeTable<3>& derivative_table<3>(int);
template const DerivativeTable<4>& derivative_table<4>(int);

}  // namespace detail

namespace {


// One contraction step of a local block along one direction (sum factorisation):
//   out[r][row * len + x] = sum_k basis[r][k] * in[k * kstride + row_offset[row] + x]
// for the derivative orders r = 0..orders-1, reading the input once for all orders.
inline void contract_stage(const double* in, std::ptrdiff_t kstride, const std::ptrdiff_t* row_offset, int rows,
                           int len, const double* basis, int n, int orders, double* out) {
  const int block = rows * len;
  std::fill(out, out + static_cast<std::ptrdiff_t>(orders) * block, 0.0);
  for (int k = 0; k < n; ++k) {
    for (int row = 0; row < rows; ++row) {
      const double* src = in + k * kstride + row_offset[row];
      for (int r = 0; r < orders; ++r) {
        const double b = basis[r * n + k];
        double* dst = out + r * block + row * len;
        for (int x = 0; x < len; ++x) dst[x] += b * src[x];
      }
    }
  }
}

template <int D>
struct LocalEvaluation {
  const double* coefficients;
  int C;
  std::array<int, D> n;          // p_d + 1
  std::array<std::ptrdiff_t, D> stride;  // global stride of direction d
  std::array<const double*, D> basis;    // (order+1) x n_d derivative rows per direction
  int order;
  const detail::DerivativeTable<D>* table;
  double* results;  // table size x C
  double* scratch;

  // Contracts direction d of `in` (global block when d == D-1, else contiguous) and recurses.
  void descend(int d, const double* in, std::ptrdiff_t kstride, const std::ptrdiff_t* row_offset, int rows, int len,
               int used, std::array<int, D>& alpha, double* buffer) {
    const auto dd = static_cast<std::size_t>(d);
    const int orders = std::min(order - used, n[dd] - 1) + 1;
    const int block = rows * len;
    contract_stage(in, kstride, row_offset, rows, len, basis[dd], n[dd], orders, buffer);
    for (int r = 0; r < orders; ++r) {
      alpha[dd] = r;
      const double* part = buffer + r * block;
      if (d == 0) {
        const int pos = table->position[static_cast<std::size_t>(table->dense_index(alpha))];
        std::memcpy(results + pos * C, part, sizeof(double) * static_cast<std::size_t>(C));
      } else {
        // The contracted block has shape n_0 x ... x n_{d-1} x C, contiguous.
        const int next_len = block / n[dd - 1];
        const std::ptrdiff_t zero = 0;
        descend(d - 1, part, next_len, &zero, 1, next_len, used + r, alpha, buffer + orders * block);
      }
    }
    alpha[dd] = 0;
  }
};

// The partial derivatives of a rational spline R = A / w from those of its homogeneous form
// (A, w), by the quotient rule in Leibniz form: A_alpha = sum_{beta <= alpha} C(alpha, beta)
// w_beta R_{alpha-beta}, solved for R_alpha in the order of the table (lower multi-indices first;
// Lasser 1994 eq. 4-5 give the homogeneous form). homogeneous(a) points to the k + 1
// numbers (A, w) of multi-index a, rational(a) to the k numbers R_a it fills.
template <int D, class Homogeneous, class Rational>
void divide_by_weight(const detail::DerivativeTable<D>& table, int k, Homogeneous homogeneous, Rational rational) {
  const double w0 = homogeneous(0)[k];
  if (!(w0 > 0.0)) throw Error("internal: rational denominator vanished inside the domain");
  for (std::size_t a = 0; a < table.alphas.size(); ++a) {
    double* r = rational(a);
    const double* h = homogeneous(a);
    for (int c = 0; c < k; ++c) r[c] = h[c];
    for (const auto& term : table.leibniz[a]) {
      const double wb = term.binomial * homogeneous(static_cast<std::size_t>(term.beta))[k];
      const double* lower = rational(static_cast<std::size_t>(term.alpha_minus));
      for (int c = 0; c < k; ++c) r[c] -= wb * lower[c];
    }
    for (int c = 0; c < k; ++c) r[c] /= w0;
  }
}

thread_local std::vector<double> tl_scratch;
thread_local std::vector<double> tl_grid_scratch[3];

// Sum factorisation of one 3-variate block with compile-time sizes: N0, N1, N2 = p + 1 along
// u, v, w, C numbers per coefficient. Contracting w first leaves rows of N0*C contiguous
// numbers, which the compiler unrolls and vectorises. Computes the value and, for order 1, the
// three first partials in derivative_multi_indices order.
// One contraction stage of the fixed kernels: L contiguous numbers at `row`, n of them `stride`
// apart along the contracted direction, summed with the basis values B[0..n) into `value` and,
// for order 1, with the derivatives B[n..2n) into `derivative`.
template <int L, int Order>
inline void contract_fixed_row(const double* row, std::ptrdiff_t stride, int n, const double* B, double* value, double* derivative) {
  for (int x = 0; x < L; ++x) {
    double a = 0.0, b = 0.0;
    for (int k = 0; k < n; ++k) {
      const double g = row[k * stride + x];
      a += B[k] * g;
      if constexpr (Order) b += B[n + k] * g;
    }
    value[x] = a;
    if constexpr (Order) derivative[x] = b;
  }
}

template <int N0, int N1, int N2, int C, int Order>
void contract_volume_fixed(const double* G, std::ptrdiff_t sv, std::ptrdiff_t sw, const double* Bu, const double* Bv,
                           const double* Bw, double* results) {
  constexpr int L = N0 * C;
  double w0[N1][L], w1[N1][L];
  for (int j = 0; j < N1; ++j) contract_fixed_row<L, Order>(G + j * sv, sw, N2, Bw, w0[j], w1[j]);
  double v00[L], v10[L], v01[L];
  for (int x = 0; x < L; ++x) {
    double a = 0.0, b = 0.0, c = 0.0;
    for (int j = 0; j < N1; ++j) {
      a += Bv[j] * w0[j][x];
      if constexpr (Order) {
        b += Bv[N1 + j] * w0[j][x];
        c += Bv[j] * w1[j][x];
      }
    }
    v00[x] = a;
    v10[x] = b;  // d/dv
    v01[x] = c;  // d/dw
  }
  for (int c = 0; c < C; ++c) {
    double value = 0.0, du = 0.0, dv = 0.0, dw = 0.0;
    for (int i = 0; i < N0; ++i) {
      value += Bu[i] * v00[i * C + c];
      if constexpr (Order) {
        du += Bu[N0 + i] * v00[i * C + c];
        dv += Bu[i] * v10[i * C + c];
        dw += Bu[i] * v01[i * C + c];
      }
    }
    results[c] = value;
    if constexpr (Order) {
      results[C + c] = du;
      results[2 * C + c] = dv;
      results[3 * C + c] = dw;
    }
  }
}

// A 4-variate block (a swept solid s(u, v, w, t), Conkey–Joy 2000 eq. 1, whose Newton solves
// evaluate it millions of times while trimming): the t direction (the largest stride) is
// contracted first into contiguous 3-variate blocks, the value's and, for order 1, d/dt's,
// which the fixed volume kernel then finishes. Results in derivative_multi_indices order:
// value, d/du, d/dv, d/dw, d/dt.
template <int N0, int N1, int N2, int C, int Order>
void contract_hypervolume_fixed(const double* G, std::ptrdiff_t sv, std::ptrdiff_t sw, std::ptrdiff_t st, int nt, const double* Bu,
                                const double* Bv, const double* Bw, const double* Bt, double* results) {
  constexpr int L = N0 * C;
  double t0[N2][N1][L], t1[N2][N1][L];
  for (int k = 0; k < N2; ++k)
    for (int j = 0; j < N1; ++j) contract_fixed_row<L, Order>(G + k * sw + j * sv, st, nt, Bt, t0[k][j], t1[k][j]);
  contract_volume_fixed<N0, N1, N2, C, Order>(&t0[0][0][0], L, N1 * L, Bu, Bv, Bw, results);
  if constexpr (Order) contract_volume_fixed<N0, N1, N2, C, 0>(&t1[0][0][0], L, N1 * L, Bu, Bv, Bw, results + 4 * C);
}

// Second order, for the trimming of swept envelopes: Newton on a fold or the rank-deficient set
// (Conkey–Joy 2000 §5) needs the second partials of s(u, v, w, t) at every step. The same sum
// factorisation with the basis functions' second derivatives (B[2n..3n)): t is contracted with
// B_t, B_t' and B_t'', each block then finishes as a volume to the order left. Results go to
// `table.position` of their multi-index.
template <int N0, int N1, int N2, int C>
void contract_volume_to_order(const double* G, std::ptrdiff_t sv, std::ptrdiff_t sw, const double* Bu, const double* Bv,
                              const double* Bw, int order, double (&out)[3][3][3][C]) {
  constexpr int L = N0 * C;
  double w[3][N1][L];
  for (int j = 0; j < N1; ++j)
    for (int x = 0; x < L; ++x) {
      double a[3] = {0.0, 0.0, 0.0};
      for (int k = 0; k < N2; ++k) {
        const double g = G[j * sv + k * sw + x];
        for (int e = 0; e <= order; ++e) a[e] += Bw[e * N2 + k] * g;
      }
      for (int e = 0; e <= order; ++e) w[e][j][x] = a[e];
    }
  double v[3][3][L];
  for (int dv = 0; dv <= order; ++dv)
    for (int dw = 0; dv + dw <= order; ++dw)
      for (int x = 0; x < L; ++x) {
        double a = 0.0;
        for (int j = 0; j < N1; ++j) a += Bv[dv * N1 + j] * w[dw][j][x];
        v[dv][dw][x] = a;
      }
  for (int du = 0; du <= order; ++du)
    for (int dv = 0; du + dv <= order; ++dv)
      for (int dw = 0; du + dv + dw <= order; ++dw)
        for (int c = 0; c < C; ++c) {
          double a = 0.0;
          for (int i = 0; i < N0; ++i) a += Bu[du * N0 + i] * v[dv][dw][i * C + c];
          out[du][dv][dw][c] = a;
        }
}

template <int N0, int N1, int N2, int C>
void contract_hypervolume_second(const double* G, std::ptrdiff_t sv, std::ptrdiff_t sw, std::ptrdiff_t st, int nt, const double* Bu,
                                 const double* Bv, const double* Bw, const double* Bt, const detail::DerivativeTable<4>& table,
                                 double* results) {
  constexpr int L = N0 * C;
  double t[3][N2][N1][L];
  for (int k = 0; k < N2; ++k)
    for (int j = 0; j < N1; ++j)
      for (int x = 0; x < L; ++x) {
        const double* row = G + k * sw + j * sv + x;
        double a0 = 0.0, a1 = 0.0, a2 = 0.0;
        for (int q = 0; q < nt; ++q) {
          const double g = row[q * st];
          a0 += Bt[q] * g;
          a1 += Bt[nt + q] * g;
          a2 += Bt[2 * nt + q] * g;
        }
        t[0][k][j][x] = a0;
        t[1][k][j][x] = a1;
        t[2][k][j][x] = a2;
      }
  double out[3][3][3][C];
  for (int dt = 0; dt <= 2; ++dt) {
    contract_volume_to_order<N0, N1, N2, C>(&t[dt][0][0][0], L, N1 * L, Bu, Bv, Bw, 2 - dt, out);
    for (int du = 0; du + dt <= 2; ++du)
      for (int dv = 0; du + dv + dt <= 2; ++dv)
        for (int dw = 0; du + dv + dw + dt <= 2; ++dw) {
          const int a = table.position[static_cast<std::size_t>(table.dense_index({du, dv, dw, dt}))];
          for (int c = 0; c < C; ++c) results[a * C + c] = out[du][dv][dw][c];
        }
  }
}

// The (p_v, p_w) with fixed kernels: p_v = p_w (any p_u: a ball's or torus's (1, 2, 2), tricubic
// and triquadratic solids), and linear against quadratic either way (a cylinder's (1, 1, 2),
// Conkey–Joy Fig. 5's tumbled generator, whose swept solid the trimming evaluates millions of
// times). All nine pairs would triple the instances, and the build time with them, for models
// we do not have.
bool has_fixed_vw_orders(const std::array<int, 3>& n) {
  return n[1] == n[2] || (n[1] + n[2] == 5 && std::min(n[1], n[2]) == 2);
}

using SecondOrderHyperKernel = void (*)(const double*, std::ptrdiff_t, std::ptrdiff_t, std::ptrdiff_t, int, const double*, const double*,
                                        const double*, const double*, const detail::DerivativeTable<4>&, double*);

template <int C, int N0>
SecondOrderHyperKernel second_order_kernel_n1(int n1, int n2) {
  if (n1 != n2) return n1 == 2 ? contract_hypervolume_second<N0, 2, 3, C> : contract_hypervolume_second<N0, 3, 2, C>;
  if (n1 == 2) return contract_hypervolume_second<N0, 2, 2, C>;
  if (n1 == 3) return contract_hypervolume_second<N0, 3, 3, C>;
  return contract_hypervolume_second<N0, 4, 4, C>;
}

template <int C>
SecondOrderHyperKernel second_order_kernel_of(const std::array<int, 3>& n) {
  if (n[0] == 2) return second_order_kernel_n1<C, 2>(n[1], n[2]);
  if (n[0] == 3) return second_order_kernel_n1<C, 3>(n[1], n[2]);
  return second_order_kernel_n1<C, 4>(n[1], n[2]);
}

// The 4-variate second-order kernel for the sizes the fixed kernels below take; nullptr otherwise.
SecondOrderHyperKernel second_order_hyper_kernel(const std::array<int, 3>& n, int c) {
  if (c != 3 && c != 4) return nullptr;
  for (int x : n)
    if (x < 2 || x > 4) return nullptr;
  if (!has_fixed_vw_orders(n)) return nullptr;
  return c == 3 ? second_order_kernel_of<3>(n) : second_order_kernel_of<4>(n);
}

// The fixed-size kernels for n_u in {2, 3, 4} and the (n_v, n_w) above, and 3 or 4 numbers per
// coefficient; nullptr otherwise (the general recurrence then runs).
using FixedKernel = void (*)(const double*, std::ptrdiff_t, std::ptrdiff_t, const double*, const double*, const double*,
                             double*);
using FixedHyperKernel = void (*)(const double*, std::ptrdiff_t, std::ptrdiff_t, std::ptrdiff_t, int, const double*, const double*,
                                  const double*, const double*, double*);

template <int N0, int N1, int N2, int C, int Order>
constexpr std::pair<FixedKernel, FixedHyperKernel> fixed_pair() {
  return {contract_volume_fixed<N0, N1, N2, C, Order>, contract_hypervolume_fixed<N0, N1, N2, C, Order>};
}

template <int C, int Order, int N0>
std::pair<FixedKernel, FixedHyperKernel> fixed_kernels_n1(int n1, int n2) {
  if (n1 != n2) return n1 == 2 ? fixed_pair<N0, 2, 3, C, Order>() : fixed_pair<N0, 3, 2, C, Order>();
  if (n1 == 2) return fixed_pair<N0, 2, 2, C, Order>();
  if (n1 == 3) return fixed_pair<N0, 3, 3, C, Order>();
  return fixed_pair<N0, 4, 4, C, Order>();
}

template <int C, int Order>
std::pair<FixedKernel, FixedHyperKernel> fixed_kernels_of(const std::array<int, 3>& n) {
  if (n[0] == 2) return fixed_kernels_n1<C, Order, 2>(n[1], n[2]);
  if (n[0] == 3) return fixed_kernels_n1<C, Order, 3>(n[1], n[2]);
  return fixed_kernels_n1<C, Order, 4>(n[1], n[2]);
}

std::pair<FixedKernel, FixedHyperKernel> fixed_kernels(const std::array<int, 3>& n, int c, int order) {
  if (order > 1 || (c != 3 && c != 4)) return {nullptr, nullptr};
  for (int x : n)
    if (x < 2 || x > 4) return {nullptr, nullptr};
  if (!has_fixed_vw_orders(n)) return {nullptr, nullptr};
  if (c == 3) return order == 0 ? fixed_kernels_of<3, 0>(n) : fixed_kernels_of<3, 1>(n);
  return order == 0 ? fixed_kernels_of<4, 0>(n) : fixed_kernels_of<4, 1>(n);
}

}  // namespace

template <int D>
void TensorSpline<D>::evaluate(const Parameter& t, double* out) const {
  evaluate_derivatives(t, 0, out);
}

template <int D>
Eigen::VectorXd TensorSpline<D>::evaluate(const Parameter& t) const {
  Eigen::VectorXd x(dimension_);
  evaluate(t, x.data());
  return x;
}

template <int D>
std::vector<double> TensorSpline<D>::evaluate_derivatives(const Parameter& t, int order) const {
  const auto& table = detail::derivative_table<D>(order);
  std::vector<double> out(table.alphas.size() * static_cast<std::size_t>(dimension_));
  evaluate_derivatives(t, order, out.data());
  return out;
}

template <int D>
void TensorSpline<D>::evaluate_derivatives(const Parameter& t, int order, double* out) const {
  if (order < 0) throw InvalidInput("derivative order must be >= 0");
  check_in_domain(t);
  const auto& table = detail::derivative_table<D>(order);
  const int C = coefficient_size();
  const bool rational = is_rational();

  // Basis functions (and derivatives) per direction; all on the stack for ordinary degrees.
  std::array<int, D> n{}, first{};
  std::array<std::ptrdiff_t, D> stride{};
  std::size_t basis_size = 0, block = 1;
  for (int d = 0; d < D; ++d) {
    const auto dd = static_cast<std::size_t>(d);
    n[dd] = knots_[dd].degree() + 1;
    basis_size += static_cast<std::size_t>((order + 1) * n[dd]);
    block *= static_cast<std::size_t>(n[dd]);
    stride[dd] = d == 0 ? C : stride[dd - 1] * counts_[dd - 1];
  }
  const std::size_t n_alpha = table.alphas.size();
  // scratch: basis | results (homogeneous) | contraction buffers (bounded by 2 * (order+1) * block * C)
  const std::size_t need = basis_size + n_alpha * static_cast<std::size_t>(C) +
                           2 * static_cast<std::size_t>(order + 1) * block * static_cast<std::size_t>(C) * D;
  std::vector<double>& scratch = tl_scratch;
  if (scratch.size() < need) scratch.resize(need);
  double* basis_ptr = scratch.data();
  std::array<const double*, D> basis{};
  std::ptrdiff_t base = 0;
  for (int d = 0; d < D; ++d) {
    const auto dd = static_cast<std::size_t>(d);
    const KnotVector& kv = knots_[dd];
    const double x = t[dd];
    const int span = kv.find_span(x);
    first[dd] = span - kv.degree();
    if (order == 0)
      kv.basis(span, x, basis_ptr);
    else if (order == 1)
      kv.basis_first_derivatives(span, x, basis_ptr);
    else
      kv.basis_derivatives(span, x, order, basis_ptr);
    basis[dd] = basis_ptr;
    basis_ptr += (order + 1) * n[dd];
    base += first[dd] * stride[dd];
  }
  double* results = basis_ptr;
  double* buffers = results + n_alpha * static_cast<std::size_t>(C);
  std::fill(results, results + n_alpha * static_cast<std::size_t>(C), 0.0);

  FixedKernel fixed = nullptr;
  FixedHyperKernel fixed_hyper = nullptr;
  SecondOrderHyperKernel second_hyper = nullptr;
  if constexpr (D == 3) fixed = fixed_kernels({n[0], n[1], n[2]}, C, order).first;
  if constexpr (D == 4) {
    fixed_hyper = fixed_kernels({n[0], n[1], n[2]}, C, order).second;
    if (order == 2) second_hyper = second_order_hyper_kernel({n[0], n[1], n[2]}, C);
  }
  if (second_hyper) {
    if constexpr (D == 4)
      second_hyper(evaluation_coefficients().data() + base, stride[1], stride[2], stride[3], n[3], basis[0], basis[1], basis[2], basis[3],
                   table, results);
  } else if (fixed) {
    fixed(evaluation_coefficients().data() + base, stride[1], stride[2], basis[0], basis[1], basis[2], results);
  } else if (fixed_hyper) {
    if constexpr (D == 4) {
      fixed_hyper(evaluation_coefficients().data() + base, stride[1], stride[2], stride[3], n[3], basis[0], basis[1], basis[2],
                  basis[3], results);
    }
  } else {
    // Row offsets of the block in global memory for the first stage (direction D-1): the rows
    // run along direction 0 and are contiguous (n_0 * C numbers).
    std::array<std::ptrdiff_t, 64> row_offset_stack{};
    std::vector<std::ptrdiff_t> row_offset_heap;
    int rows = 1;
    for (int d = 1; d < D - 1; ++d) rows *= n[static_cast<std::size_t>(d)];
    std::ptrdiff_t* row_offset = row_offset_stack.data();
    if (rows > static_cast<int>(row_offset_stack.size())) {
      row_offset_heap.resize(static_cast<std::size_t>(rows));
      row_offset = row_offset_heap.data();
    }
    for (int row = 0; row < rows; ++row) {
      std::ptrdiff_t off = 0;
      int rest = row;
      for (int d = 1; d < D - 1; ++d) {
        const auto dd = static_cast<std::size_t>(d);
        off += (rest % n[dd]) * stride[dd];
        rest /= n[dd];
      }
      row_offset[row] = off;
    }
    const int len = D == 1 ? C : n[0] * C;

    LocalEvaluation<D> local{evaluation_coefficients().data(), C, n, stride, basis, order, &table, results, buffers};
    std::array<int, D> alpha{};
    local.descend(D - 1, evaluation_coefficients().data() + base, stride[D - 1], row_offset, rows, len, 0, alpha, buffers);
  }

  const int k = dimension_;
  if (!rational) {
    std::memcpy(out, results, sizeof(double) * n_alpha * static_cast<std::size_t>(k));
  } else {
    divide_by_weight(
        table, k, [&](std::size_t a) { return results + a * static_cast<std::size_t>(C); },
        [&](std::size_t a) { return out + a * static_cast<std::size_t>(k); });
  }
  add_local_origin(out, 1, static_cast<std::size_t>(k));  // the position (multi-index 0) only
}

template <int D>
std::vector<double> TensorSpline<D>::evaluate_points(const std::vector<Parameter>& t, int order) const {
  if (order < 0) throw InvalidInput("derivative order must be >= 0");
  for (std::size_t i = 0; i < t.size(); ++i) {
    try {
      check_in_domain(t[i]);
    } catch (const InvalidInput& e) {
      throw e.located("points[" + std::to_string(i) + "]");
    }
  }
  const std::size_t row = detail::derivative_table<D>(order).alphas.size() * static_cast<std::size_t>(dimension_);
  std::vector<double> out(t.size() * row);
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, t.size(), 1024), [&](const tbb::blocked_range<std::size_t>& r) {
    for (std::size_t i = r.begin(); i != r.end(); ++i) evaluate_derivatives(t[i], order, out.data() + i * row);
  });
  return out;
}

template <int D>
std::vector<double> TensorSpline<D>::evaluate_grid(const std::array<std::vector<double>, D>& samples, int order) const {
  std::size_t num_points = 1;
  for (const auto& s : samples) num_points *= s.size();
  std::vector<double> out(detail::derivative_table<D>(std::max(order, 0)).alphas.size() * num_points *
                          static_cast<std::size_t>(dimension_));
  evaluate_grid(samples, order, out.data());
  return out;
}

template <int D>
void TensorSpline<D>::evaluate_grid(const std::array<std::vector<double>, D>& samples, int order, double* out) const {
  if (order < 0) throw InvalidInput("derivative order must be >= 0");
  const auto& table = detail::derivative_table<D>(order);
  const int C = coefficient_size();
  const int k = dimension_;
  std::size_t num_points = 1;
  for (const auto& s : samples) num_points *= s.size();
  const std::size_t n_alpha = table.alphas.size();
  if (num_points == 0) return;

  // Basis functions of every sample, per direction: first index and (order+1) x (p+1) values.
  std::array<std::vector<int>, D> first;
  std::array<std::vector<double>, D> basis;
  for (int d = 0; d < D; ++d) {
    const auto dd = static_cast<std::size_t>(d);
    const KnotVector& kv = knots_[dd];
    const int n = kv.degree() + 1;
    first[dd].resize(samples[dd].size());
    basis[dd].resize(samples[dd].size() * static_cast<std::size_t>((order + 1) * n));
    for (std::size_t s = 0; s < samples[dd].size(); ++s) {
      Parameter probe{};
      for (int e = 0; e < D; ++e) probe[static_cast<std::size_t>(e)] = knots_[static_cast<std::size_t>(e)].domain_min();
      probe[dd] = samples[dd][s];
      check_in_domain(probe);
      const int span = kv.find_span(samples[dd][s]);
      first[dd][s] = span - kv.degree();
      kv.basis_derivatives(span, samples[dd][s], order, &basis[dd][s * static_cast<std::size_t>((order + 1) * n)]);
    }
  }

  // Sum factorisation, one multi-index at a time: contract direction 0, then 1, ...; after
  // direction d the tensor is [c][s_0]..[s_d][i_{d+1}]..[i_{D-1}], so every step is a long
  // contiguous multiply-add over the already contracted block. Scratch is reused between calls
  // (fresh pages cost more than the arithmetic).
  const bool rational = is_rational();
  std::vector<double>& homog = tl_grid_scratch[2];
  if (rational) homog.resize(n_alpha * num_points * static_cast<std::size_t>(C));
  for (std::size_t a = 0; a < n_alpha; ++a) {
    const auto& alpha = table.alphas[a];
    const double* in = evaluation_coefficients().data();
    std::size_t inner = static_cast<std::size_t>(C);
    for (int d = 0; d < D; ++d) {
      const auto dd = static_cast<std::size_t>(d);
      const int p1 = knots_[dd].degree() + 1;
      const int r = alpha[dd];
      const std::size_t ns = samples[dd].size();
      const std::size_t nd = static_cast<std::size_t>(counts_[dd]);
      std::size_t outer = 1;
      for (int e = d + 1; e < D; ++e) outer *= static_cast<std::size_t>(counts_[static_cast<std::size_t>(e)]);
      double* dst_base;
      if (d == D - 1) {
        dst_base = (rational ? homog.data() : out) + a * num_points * static_cast<std::size_t>(C);
      } else {
        std::vector<double>& target = tl_grid_scratch[d % 2];
        if (target.size() < inner * ns * outer) target.resize(inner * ns * outer);
        dst_base = target.data();
      }
      for (std::size_t o = 0; o < outer; ++o) {
        for (std::size_t s = 0; s < ns; ++s) {
          double* dst = dst_base + inner * (s + ns * o);
          if (r >= p1) {  // derivative above the degree: zero
            std::fill(dst, dst + inner, 0.0);
            continue;
          }
          const double* b = &basis[dd][s * static_cast<std::size_t>((order + 1) * p1) + static_cast<std::size_t>(r * p1)];
          const double* src0 = in + inner * (static_cast<std::size_t>(first[dd][s]) + nd * o);
          for (std::size_t x = 0; x < inner; ++x) dst[x] = b[0] * src0[x];
          for (int kk = 1; kk < p1; ++kk) {
            const double coef = b[kk];
            const double* src = src0 + inner * static_cast<std::size_t>(kk);
            for (std::size_t x = 0; x < inner; ++x) dst[x] += coef * src[x];
          }
        }
      }
      in = dst_base;
      inner *= ns;
    }
  }
  if (rational) {
    for (std::size_t pt = 0; pt < num_points; ++pt) {
      divide_by_weight(
          table, k, [&](std::size_t a) { return &homog[(a * num_points + pt) * static_cast<std::size_t>(C)]; },
          [&](std::size_t a) { return &out[(a * num_points + pt) * static_cast<std::size_t>(k)]; });
    }
  }
  add_local_origin(out, num_points, static_cast<std::size_t>(k));  // the block of positions (multi-index 0)
}

#define VOLSPLINE_INSTANTIATE_EVALUATION(D)                                                           \
  template void TensorSpline<D>::evaluate(const Parameter&, double*) const;                          \
  template Eigen::VectorXd TensorSpline<D>::evaluate(const Parameter&) const;                        \
  template void TensorSpline<D>::evaluate_derivatives(const Parameter&, int, double*) const;         \
  template std::vector<double> TensorSpline<D>::evaluate_derivatives(const Parameter&, int) const;   \
  template std::vector<double> TensorSpline<D>::evaluate_grid(const std::array<std::vector<double>, D>&, int) const; \
  template void TensorSpline<D>::evaluate_grid(const std::array<std::vector<double>, D>&, int, double*) const; \
  template std::vector<double> TensorSpline<D>::evaluate_points(const std::vector<Parameter>&, int) const;
VOLSPLINE_INSTANTIATE_EVALUATION(1)
VOLSPLINE_INSTANTIATE_EVALUATION(2)
VOLSPLINE_INSTANTIATE_EVALUATION(3)
VOLSPLINE_INSTANTIATE_EVALUATION(4)
#undef VOLSPLINE_INSTANTIATE_EVALUATION

}  // namespace volspline
