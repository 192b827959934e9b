// The exact hash keys maps by values: equal arrays (-0 and +0 included) hash alike, and
// unordered maps keyed by it find exactly the arrays put in.
#include "volspline/core/exact_hash.h"

#include <unordered_map>

#include <gtest/gtest.h>

namespace volspline {
namespace {

TEST(ExactDoublesHash, EqualArraysHashAlikeAndMapsFindExactlyTheirKeys) {
  const ExactDoublesHash hash;
  EXPECT_EQ(hash(std::array<double, 3>{1.5, -0.0, 2}), hash(std::array<double, 3>{1.5, 0.0, 2}));
  std::unordered_map<std::array<double, 3>, int, ExactDoublesHash> map;
  for (int i = 0; i < 1000; ++i) map.emplace(std::array<double, 3>{0.001 * i, 1.0, -0.5 * i}, i);
  EXPECT_EQ(map.size(), 1000u);
  for (int i = 0; i < 1000; ++i) EXPECT_EQ(map.at(std::array<double, 3>{0.001 * i, 1.0, -0.5 * i}), i);
  EXPECT_EQ(map.count(std::array<double, 3>{0.001 * 3 + 1e-16, 1.0, -1.5}), 0u) << "no tolerance";
}

}  // namespace
}  // namespace volspline
