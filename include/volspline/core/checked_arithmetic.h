#pragma once
// Overflow-safe products of counts. A file declares counts (knots per direction, NumberOfPoints,
// geoDim, XDIM ...) and the readers multiply them to size arrays and to compare with what the
// file holds; a product that wraps (2^48 control points x geoDim 2^16 = 2^64 = 0) would let a
// short or empty array pass that comparison and index far outside it later. Every product of
// counts taken from input goes through checked_product, which refuses instead of wrapping.
#include <concepts>
#include <cstdint>
#include <initializer_list>
#include <limits>
#include <optional>
#include <string>

#include "volspline/core/error.h"

namespace volspline {

/// a * b, or nullopt when the exact product does not fit in T (or a factor is negative).
template <std::integral T, std::integral A, std::integral B>
[[nodiscard]] constexpr std::optional<T> multiply_exactly(A a, B b) {
  if (a < 0 || b < 0) return std::nullopt;
  T out{};
  if (__builtin_mul_overflow(a, b, &out)) return std::nullopt;
  return out;
}

/// The product of nonnegative `factors` as a T, or nullopt when it does not fit (or a factor is
/// negative). A zero factor makes the product 0 whatever the others are.
template <std::integral T, std::integral F>
[[nodiscard]] constexpr std::optional<T> product_exactly(std::initializer_list<F> factors) {
  T product = 1;
  for (const F f : factors) {
    const std::optional<T> next = multiply_exactly<T>(product, f);
    if (!next) return std::nullopt;
    product = *next;
  }
  return product;
}

/// The same for any range of integers (a std::array of counts per direction, a vector).
template <std::integral T, class Range>
[[nodiscard]] constexpr std::optional<T> product_exactly(const Range& factors) {
  T product = 1;
  for (const auto f : factors) {
    const std::optional<T> next = multiply_exactly<T>(product, f);
    if (!next) return std::nullopt;
    product = *next;
  }
  return product;
}

namespace detail {
template <class Range>
std::string product_text(const Range& factors) {
  std::string text;
  for (const auto f : factors) text += (text.empty() ? "" : " x ") + std::to_string(f);
  return text;
}
}  // namespace detail

/// The product of `factors` (counts read from a file), at most `limit`. \throw InvalidInput
/// ("WHAT = A x B x C is more than LIMIT", where) when it overflows T or exceeds the limit, so
/// the message names the field of the input and the numbers that were declared.
template <std::integral T, class Range>
T checked_product(const Range& factors, const std::string& what, const std::string& where = {},
                  T limit = std::numeric_limits<T>::max()) {
  const std::optional<T> product = product_exactly<T>(factors);
  if (!product || *product > limit) {
    throw InvalidInput(what + " = " + detail::product_text(factors) + " is more than " + std::to_string(limit) +
                           " (the counts multiply beyond what can be represented or held)",
                       where);
  }
  return *product;
}

template <std::integral T, std::integral F>
T checked_product(std::initializer_list<F> factors, const std::string& what, const std::string& where = {},
                  T limit = std::numeric_limits<T>::max()) {
  return checked_product<T, std::initializer_list<F>>(factors, what, where, limit);
}

}  // namespace volspline
