#include "volspline/core/resource_limits.h"

#include <atomic>
#include <charconv>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <limits>

#include "volspline/core/error.h"

namespace volspline {

namespace {
// 0: not set, read the environment.
std::atomic<std::uint64_t> resource_limits_memory{0};
std::atomic<std::uint64_t> resource_limits_work{0};
}  // namespace

std::uint64_t memory_limit() {
  if (const std::uint64_t set = resource_limits_memory.load()) return set;
  if (const char* text = std::getenv("VOLSPLINE_MEMORY_LIMIT"); text != nullptr && *text != '\0')
    return parse_byte_count(text, "VOLSPLINE_MEMORY_LIMIT");
  return kDefaultMemoryLimit;
}

void set_memory_limit(std::uint64_t bytes) { resource_limits_memory.store(bytes); }

std::uint64_t input_file_limit() { return memory_limit() / 4; }

std::uint64_t parse_byte_count(std::string_view text, const std::string& where) {
  const auto refuse = [&] {
    return InvalidInput("expected a byte count such as 8G, 512M or 1000000, got '" + std::string(text) + "'", where);
  };
  double value = 0;
  const auto [end, error] = std::from_chars(text.data(), text.data() + text.size(), value);
  if (error != std::errc() || !(value > 0) || !std::isfinite(value)) throw refuse();
  std::string_view suffix(end, static_cast<std::size_t>(text.data() + text.size() - end));
  if (suffix.ends_with("iB")) suffix.remove_suffix(2);
  else if (suffix.size() == 2 && (suffix[1] == 'B' || suffix[1] == 'b')) suffix.remove_suffix(1);
  double scale = 1;
  if (suffix.empty() || suffix == "B" || suffix == "b") scale = 1;
  else if (suffix == "k" || suffix == "K") scale = 0x1p10;
  else if (suffix == "M" || suffix == "m") scale = 0x1p20;
  else if (suffix == "G" || suffix == "g") scale = 0x1p30;
  else if (suffix == "T" || suffix == "t") scale = 0x1p40;
  else throw refuse();
  const double bytes = value * scale;
  if (!(bytes >= 1) || bytes >= 0x1p63) throw refuse();
  return static_cast<std::uint64_t>(bytes);
}

std::string format_byte_count(std::uint64_t bytes) {
  static const char* units[] = {"bytes", "KiB", "MiB", "GiB", "TiB", "PiB", "EiB"};
  double value = static_cast<double>(bytes);
  int unit = 0;
  while (value >= 1024 && unit < 6) {
    value /= 1024;
    ++unit;
  }
  char text[48];
  if (unit == 0) std::snprintf(text, sizeof text, "%llu bytes", static_cast<unsigned long long>(bytes));
  else std::snprintf(text, sizeof text, "%.3g %s", value, units[unit]);
  return text;
}

std::string memory_limit_hint() { return "raise it with --memory-limit or VOLSPLINE_MEMORY_LIMIT"; }

void require_memory(std::uint64_t bytes, std::string_view request, const std::string& where) {
  const std::uint64_t limit = memory_limit();
  if (bytes <= limit) return;
  const std::string needs = bytes == std::numeric_limits<std::uint64_t>::max() ? "more than 16 EiB" : "about " + format_byte_count(bytes);
  throw InvalidInput(std::string(request) + " needs " + needs + " of memory, more than the memory limit of " +
                         format_byte_count(limit) + " (" + memory_limit_hint() + ")",
                     where);
}

std::uint64_t work_limit() {
  if (const std::uint64_t set = resource_limits_work.load()) return set;
  if (const char* text = std::getenv("VOLSPLINE_WORK_LIMIT"); text != nullptr && *text != '\0')
    return parse_operation_count(text, "VOLSPLINE_WORK_LIMIT");
  return kDefaultWorkLimit;
}

void set_work_limit(std::uint64_t operations) { resource_limits_work.store(operations); }

std::uint64_t parse_operation_count(std::string_view text, const std::string& where) {
  double value = 0;
  const auto [end, error] = std::from_chars(text.data(), text.data() + text.size(), value);
  if (error != std::errc() || end != text.data() + text.size() || !(value >= 1) || !(value < 0x1p63))
    throw InvalidInput("expected a number of operations such as 1e12, got '" + std::string(text) + "'", where);
  return static_cast<std::uint64_t>(value);
}

void require_work(std::uint64_t operations, std::string_view request, const std::string& where) {
  const std::uint64_t limit = work_limit();
  if (operations <= limit) return;
  char needs[32], allowed[32];
  std::snprintf(needs, sizeof needs, "%.2g", static_cast<double>(operations));
  std::snprintf(allowed, sizeof allowed, "%.2g", static_cast<double>(limit));
  throw InvalidInput(std::string(request) + " needs about " + needs + " floating-point operations, more than the work limit of " +
                         allowed + " (raise it with --work-limit or VOLSPLINE_WORK_LIMIT)",
                     where);
}

std::uint64_t saturating_product(std::initializer_list<std::uint64_t> factors) {
  std::uint64_t product = 1;
  for (const std::uint64_t f : factors) {
    if (f == 0) return 0;
    if (product > std::numeric_limits<std::uint64_t>::max() / f) {
      product = std::numeric_limits<std::uint64_t>::max();
    } else {
      product *= f;
    }
  }
  return product;
}

std::uint64_t saturating_sum(std::initializer_list<std::uint64_t> terms) {
  std::uint64_t sum = 0;
  for (const std::uint64_t t : terms) sum = t > std::numeric_limits<std::uint64_t>::max() - sum ? std::numeric_limits<std::uint64_t>::max() : sum + t;
  return sum;
}

}  // namespace volspline
