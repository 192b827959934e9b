#include "volspline/mesh/part_colors.h"

namespace volspline {

Eigen::Vector3d part_color(int part) {
  switch (part) {
    case 0:
      return {0.26, 0.47, 0.82};  // u = min: blue
    case 1:
      return {0.55, 0.72, 0.95};  // u = max: light blue
    case 2:
      return {0.30, 0.66, 0.38};  // v = min: green
    case 3:
      return {0.64, 0.85, 0.52};  // v = max: light green
    case 4:
      return {0.55, 0.40, 0.78};  // w = min: purple
    case 5:
      return {0.80, 0.70, 0.95};  // w = max: lavender
    case 6:
      return {0.95, 0.33, 0.12};  // det J = 0: orange-red, the thing one looks for
    case 7:
      return {0.36, 0.58, 0.90};  // u = const surfaces: the u faces' blue
    case 8:
      return {0.45, 0.76, 0.45};  // v = const: green
    case 9:
      return {0.68, 0.55, 0.88};  // w = const: purple
    case 10:
      return {0.93, 0.76, 0.45};  // planar slices: sand, like a cut through material
    default:
      return {0.70, 0.70, 0.70};
  }
}

}  // namespace volspline
