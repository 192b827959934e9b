#pragma once
// Reading numbers from the text formats (G+Smo XML, IRIT): locale-independent, exact (correct
// rounding), and strict about what counts as a number.
#include <charconv>
#include <cmath>
#include <cstdlib>
#include <optional>
#include <string>
#include <string_view>

namespace volspline::detail {

/// The double a decimal token denotes, or nothing if the token is not a finite number (NaN,
/// infinity, overflow, trailing characters). Literals that underflow read as 0 or subnormals,
/// as in model files.
inline std::optional<double> parse_double(std::string_view token) {
  std::string_view digits = token;
  if (!digits.empty() && digits.front() == '+') digits.remove_prefix(1);
  if (digits.empty() || digits.front() == '+') return std::nullopt;
  double value = 0.0;
  const auto [end, error] = std::from_chars(digits.data(), digits.data() + digits.size(), value,
                                            std::chars_format::general);
  if (end != digits.data() + digits.size()) return std::nullopt;
  if (error == std::errc::result_out_of_range) {
    // from_chars reports underflow and overflow alike; strtod tells them apart.
    value = std::strtod(std::string(digits).c_str(), nullptr);
  } else if (error != std::errc()) {
    return std::nullopt;
  }
  if (!std::isfinite(value)) return std::nullopt;
  return value;
}

/// The integer a decimal token denotes if it lies in [lo, hi], else nothing.
inline std::optional<long long> parse_integer(std::string_view token, long long lo, long long hi) {
  if (!token.empty() && token.front() == '+') token.remove_prefix(1);
  long long value = 0;
  const auto [end, error] = std::from_chars(token.data(), token.data() + token.size(), value);
  if (token.empty() || error != std::errc() || end != token.data() + token.size() || value < lo || value > hi) {
    return std::nullopt;
  }
  return value;
}

/// A token shortened for a message: "'abc'" or "'abcdefgh...'".
inline std::string quoted_token(std::string_view token, std::size_t limit = 40) {
  std::string shown(token.substr(0, limit));
  for (char& c : shown) {
    if (static_cast<unsigned char>(c) < 0x20) c = ' ';
  }
  return "'" + shown + (token.size() > limit ? "...'" : "'");
}

}  // namespace volspline::detail
