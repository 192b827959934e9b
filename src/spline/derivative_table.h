#pragma once
// Bookkeeping for partial derivatives of order <= n in D variables: their multi-indices in the
// order of derivative_multi_indices, a dense lookup from multi-index to position, and the terms
// of the Leibniz rule used to differentiate a quotient A / w (rational splines).
#include <array>
#include <vector>

namespace volspline::detail {

template <int D>
struct DerivativeTable {
  struct LeibnizTerm {
    int beta;          // position of beta (0 < beta <= alpha)
    int alpha_minus;   // position of alpha - beta
    double binomial;   // prod_d C(alpha_d, beta_d)
  };
  int order = 0;
  std::vector<std::array<int, D>> alphas;
  std::vector<int> position;  // dense, (order+1)^D entries, -1 where |alpha| > order
  std::vector<std::vector<LeibnizTerm>> leibniz;

  int dense_index(const std::array<int, D>& alpha) const {
    int index = 0;
    for (int d = D - 1; d >= 0; --d) index = index * (order + 1) + alpha[static_cast<std::size_t>(d)];
    return index;
  }
};

/// The table for `order`, built once per order and shared (thread-safe).
template <int D>
const DerivativeTable<D>& derivative_table(int order);

}  // namespace volspline::detail
