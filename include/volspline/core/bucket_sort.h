#pragma once
// Sorting the keys of mesh edges: 64-bit keys whose high bits are a vertex number below the
// vertex count. A counting sort by that vertex, then a sort of each vertex's few keys, is linear
// in the number of keys where a comparison sort of all of them is not; the contouring of swept
// envelopes sorts the 600,000 edge uses of its mesh several times per repair round.
#include <cstddef>
#include <cstdint>
#include <vector>

namespace volspline {

/// Sorts `keys` ascending, given that key >> shift is below `buckets` for every key (otherwise
/// \throw InvalidInput). The result equals std::sort's.
void sort_keys_by_high_bits(std::vector<std::uint64_t>& keys, int shift, std::size_t buckets);

}  // namespace volspline
