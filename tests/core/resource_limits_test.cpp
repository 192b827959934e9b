// Limits known before the work: byte counts read and written back, saturating estimates, and
// refusals that say what was asked and what the limit is.
#include <gtest/gtest.h>

#include <cstdlib>
#include <limits>
#include <string>

#include "volspline/core/error.h"
#include "volspline/core/resource_limits.h"

namespace volspline {
namespace {

// Restores the default limits whatever a test set.
struct ResourceLimitsReset {
  ~ResourceLimitsReset() {
    set_memory_limit(0);
    set_work_limit(0);
    ::unsetenv("VOLSPLINE_MEMORY_LIMIT");
    ::unsetenv("VOLSPLINE_WORK_LIMIT");
  }
};

TEST(ResourceLimits, ByteCountsInPowersOf1024) {
  EXPECT_EQ(parse_byte_count("100000", "x"), 100000u);
  EXPECT_EQ(parse_byte_count("2k", "x"), 2048u);
  EXPECT_EQ(parse_byte_count("512M", "x"), 512u << 20);
  EXPECT_EQ(parse_byte_count("8G", "x"), std::uint64_t{8} << 30);
  EXPECT_EQ(parse_byte_count("8GB", "x"), std::uint64_t{8} << 30);
  EXPECT_EQ(parse_byte_count("1.5GiB", "x"), std::uint64_t{3} << 29);
  EXPECT_EQ(parse_byte_count("1T", "x"), std::uint64_t{1} << 40);
  for (const char* bad : {"", "0", "-1G", "lots", "1Q", "1e30", "nan", "G"}) EXPECT_THROW((void)parse_byte_count(bad, "--memory-limit"), InvalidInput) << bad;
  for (const std::uint64_t bytes : {std::uint64_t{1} << 20, std::uint64_t{3} << 29, std::uint64_t{4} << 30})
    EXPECT_EQ(parse_byte_count(format_byte_count(bytes).replace(format_byte_count(bytes).find(' '), 1, ""), "x"), bytes)
        << format_byte_count(bytes);
  EXPECT_EQ(format_byte_count(100), "100 bytes");
}

TEST(ResourceLimits, EstimatesSaturateInsteadOfWrapping) {
  const std::uint64_t max = std::numeric_limits<std::uint64_t>::max();
  EXPECT_EQ(saturating_product({std::uint64_t{1} << 32, std::uint64_t{1} << 32, 3}), max);  // 2^64 * 3 wraps to 0 in plain arithmetic
  EXPECT_EQ(saturating_product({1u << 20, 1u << 20}), std::uint64_t{1} << 40);
  EXPECT_EQ(saturating_product({max, 0}), 0u);
  EXPECT_EQ(saturating_sum({max - 1, 5}), max);
  EXPECT_EQ(saturating_sum({2, 3}), 5u);
}

TEST(ResourceLimits, TheOptionOverridesTheEnvironmentWhichOverridesTheDefault) {
  const ResourceLimitsReset reset;
  EXPECT_EQ(memory_limit(), kDefaultMemoryLimit);
  EXPECT_EQ(input_file_limit(), kDefaultMemoryLimit / 4);
  ::setenv("VOLSPLINE_MEMORY_LIMIT", "1G", 1);
  EXPECT_EQ(memory_limit(), std::uint64_t{1} << 30);
  set_memory_limit(std::uint64_t{2} << 30);
  EXPECT_EQ(memory_limit(), std::uint64_t{2} << 30);
  set_memory_limit(0);
  ::setenv("VOLSPLINE_MEMORY_LIMIT", "plenty", 1);
  EXPECT_THROW((void)memory_limit(), InvalidInput);
  EXPECT_EQ(work_limit(), kDefaultWorkLimit);
  ::setenv("VOLSPLINE_WORK_LIMIT", "1e12", 1);
  EXPECT_EQ(work_limit(), 1000000000000u);
}

TEST(ResourceLimits, ARefusalSaysWhatWasAskedWhatItNeedsAndTheLimit) {
  const ResourceLimitsReset reset;
  set_memory_limit(std::uint64_t{1} << 30);
  EXPECT_NO_THROW(require_memory(std::uint64_t{1} << 30, "a grid"));
  try {
    require_memory(std::uint64_t{5} << 30, "sampling a 1000 x 1000 x 700 grid", "--resolution");
    FAIL() << "not refused";
  } catch (const InvalidInput& e) {
    EXPECT_EQ(e.where(), "--resolution");
    EXPECT_NE(e.message().find("sampling a 1000 x 1000 x 700 grid"), std::string::npos) << e.message();
    EXPECT_NE(e.message().find("5 GiB"), std::string::npos) << e.message();
    EXPECT_NE(e.message().find("1 GiB"), std::string::npos) << e.message();
    EXPECT_NE(e.message().find("--memory-limit"), std::string::npos) << e.message();
  }
  EXPECT_THROW(require_memory(std::numeric_limits<std::uint64_t>::max(), "everything"), InvalidInput);
  set_work_limit(1000);
  EXPECT_NO_THROW(require_work(1000, "a little"));
  try {
    require_work(5000, "checking a degree 64 Jacobian");
    FAIL() << "not refused";
  } catch (const InvalidInput& e) {
    EXPECT_NE(e.message().find("checking a degree 64 Jacobian"), std::string::npos) << e.message();
    EXPECT_NE(e.message().find("--work-limit"), std::string::npos) << e.message();
  }
}

}  // namespace
}  // namespace volspline
