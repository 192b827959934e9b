// The bucket sort of edge keys gives std::sort's order, for many keys and for few, and refuses
// keys outside its buckets.
#include "volspline/core/bucket_sort.h"

#include <algorithm>
#include <random>

#include <gtest/gtest.h>

#include "volspline/core/error.h"

namespace volspline {
namespace {

std::vector<std::uint64_t> random_edge_keys(std::size_t count, std::uint32_t vertices, std::uint32_t seed) {
  std::mt19937 random(seed);
  std::uniform_int_distribution<std::uint32_t> vertex(0, vertices - 1);
  std::vector<std::uint64_t> keys(count);
  for (auto& k : keys) {
    const std::uint32_t a = vertex(random), b = vertex(random);
    k = (static_cast<std::uint64_t>(std::min(a, b)) << 32) | std::max(a, b);
  }
  return keys;
}

TEST(SortKeysByHighBits, GivesTheOrderOfAComparisonSort) {
  for (const std::size_t count : {std::size_t{0}, std::size_t{1}, std::size_t{10}, std::size_t{5000}, std::size_t{60000}}) {
    std::vector<std::uint64_t> keys = random_edge_keys(count, 1000, static_cast<std::uint32_t>(count));
    std::vector<std::uint64_t> expected = keys;
    std::sort(expected.begin(), expected.end());
    sort_keys_by_high_bits(keys, 32, 1000);
    EXPECT_EQ(keys, expected) << count << " keys";
  }
  // Keys with a flag bit below the vertex numbers (mesh_checks' edge uses): the same order.
  std::vector<std::uint64_t> uses;
  for (std::uint64_t a = 0; a < 300; ++a)
    for (std::uint64_t b : {a + 1, a + 7, a + 2})
      for (std::uint64_t forward : {1u, 0u}) uses.push_back((a << 33) | (b << 1) | forward);
  std::reverse(uses.begin(), uses.end());
  std::vector<std::uint64_t> expected = uses;
  std::sort(expected.begin(), expected.end());
  sort_keys_by_high_bits(uses, 33, 300);
  EXPECT_EQ(uses, expected);
}

TEST(SortKeysByHighBits, RefusesAKeyBeyondTheBucketsAndABadShift) {
  std::vector<std::uint64_t> keys{std::uint64_t{5} << 32, std::uint64_t{1000} << 32};
  EXPECT_THROW(sort_keys_by_high_bits(keys, 32, 1000), InvalidInput);
  EXPECT_THROW(sort_keys_by_high_bits(keys, 64, 1000), InvalidInput);
  EXPECT_NO_THROW(sort_keys_by_high_bits(keys, 32, 1001));
  EXPECT_EQ(keys[1], std::uint64_t{1000} << 32);
}

}  // namespace
}  // namespace volspline
