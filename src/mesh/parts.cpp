#include "volspline/mesh/parts.h"

#include <string>

namespace volspline {

namespace {

// The table is indexed by number; a misordered row would colour a part with another's colour.
constexpr bool numbered_in_order() {
  for (std::size_t n = 0; n < kParts.size(); ++n) {
    if (part_number(kParts[n].part) != static_cast<int>(n)) return false;
  }
  return true;
}
static_assert(numbered_in_order(), "kParts must list the parts in the order of their numbers");

}  // namespace

Eigen::Vector3d part_color(int number) {
  const PartInfo* info = part_info(number);
  const std::array<double, 3>& c = info != nullptr ? info->srgb : kUnknownPartSrgb;
  return {c[0], c[1], c[2]};
}

std::string part_name(int number) {
  const PartInfo* info = part_info(number);
  return info != nullptr ? std::string(info->name) : "part_" + std::to_string(number);
}

}  // namespace volspline
