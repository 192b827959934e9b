#include "volspline/core/bucket_sort.h"

#include <algorithm>
#include <string>

#include "volspline/core/error.h"

namespace volspline {

void sort_keys_by_high_bits(std::vector<std::uint64_t>& keys, int shift, std::size_t buckets) {
  if (shift < 0 || shift > 63) throw InvalidInput("expected a shift in [0, 63], got " + std::to_string(shift), "shift");
  for (const std::uint64_t k : keys)
    if ((k >> shift) >= buckets)
      throw InvalidInput("key " + std::to_string(k) + " >> " + std::to_string(shift) + " is not below " + std::to_string(buckets), "keys");
  // Few keys: the counting pass over the buckets would cost more than the sort.
  if (keys.size() < buckets / 8) {
    std::sort(keys.begin(), keys.end());
    return;
  }
  std::vector<std::size_t> start(buckets + 1, 0);
  for (const std::uint64_t k : keys) ++start[static_cast<std::size_t>(k >> shift) + 1];
  for (std::size_t b = 0; b < buckets; ++b) start[b + 1] += start[b];
  std::vector<std::uint64_t> sorted(keys.size());
  {
    std::vector<std::size_t> next(start.begin(), start.end() - 1);
    for (const std::uint64_t k : keys) sorted[next[static_cast<std::size_t>(k >> shift)]++] = k;
  }
  for (std::size_t b = 0; b < buckets; ++b)
    if (start[b + 1] - start[b] > 1)
      std::sort(sorted.begin() + static_cast<std::ptrdiff_t>(start[b]), sorted.begin() + static_cast<std::ptrdiff_t>(start[b + 1]));
  keys.swap(sorted);
}

}  // namespace volspline
