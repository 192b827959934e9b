#pragma once
// The mean square error of a fitted attribute against the field it was sampled from, at points
// of Ω (points outside the domain are skipped): what knot placement and the local knot step are
// meant to lower, as opposed to the error at the samples they see.
#include <algorithm>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "volspline/simplex/dms_spline_evaluator.h"
#include "volspline/simplex/dms_spline_volume.h"

namespace volspline::test_support {

template <class Field>
double truth_mean_square(const DmsSplineVolume& volume, const std::string& attribute, const Field& field,
                         const std::vector<Eigen::Vector3d>& points) {
  DmsSplineEvaluator evaluator(volume);
  const int column = volume.attribute_column(attribute);
  double sum = 0;
  int inside = 0;
  for (const auto& x : points) {
    const DmsSplinePoint p = evaluator.evaluate(x);
    if (!p.inside) continue;
    const double e = p.value[column] - field(x);
    sum += e * e;
    ++inside;
  }
  return sum / std::max(inside, 1);
}

}  // namespace volspline::test_support
