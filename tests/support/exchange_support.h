#pragma once
// Models for the exchange-format tests: random curves, surfaces and volumes, polynomial and
// rational, with non-uniform and unclamped knots and attributes, and a comparison of two models
// by evaluation at random parameters.
#include <gtest/gtest.h>

#include <cmath>
#include <random>
#include <string>
#include <vector>

#include "support/test_splines.h"
#include "volspline/io/model_file.h"

namespace volspline::test_support {

/// Six objects: a curve, surface and volume, each polynomial and rational, with interior knots of
/// several multiplicities; the rational surface has unclamped knots. Every object carries an
/// attribute "temperature"; the volumes also "pressure".
inline Model random_exchange_model(std::mt19937& rng, int dimension = 3) {
  Model model;
  const auto add = [&](SplineObject spline, const std::string& name) {
    ModelObject object{name, false, std::move(spline), nullptr};
    const int n = visit_spline(object, "test", "", [](const auto& s) { return s.num_control_points_total(); });
    std::uniform_real_distribution<double> value(-5.0, 5.0);
    for (const char* attribute : {"temperature", "pressure"}) {
      if (std::string(attribute) == "pressure" && object.spline.index() != 2) continue;
      std::vector<double> values(static_cast<std::size_t>(n));
      for (double& v : values) v = value(rng);
      object.attributes[attribute] = values;
    }
    model.objects.push_back(std::move(object));
  };
  add(test_support::random_spline<1>(rng, {3}, 4, dimension, false), "curve");
  add(test_support::random_spline<1>(rng, {2}, 3, dimension, true), "rational_curve");
  add(test_support::random_spline<2>(rng, {2, 3}, 3, dimension, false), "surface");
  add(test_support::random_spline<2>(rng, {3, 2}, 2, dimension, true, false), "rational_surface");
  add(test_support::random_spline<3>(rng, {2, 1, 3}, 2, dimension, false), "volume");
  add(test_support::random_spline<3>(rng, {2, 2, 2}, 2, dimension, true), "rational_volume");
  return model;
}

/// Largest distance between a and b (and between their attributes, when `attributes`) at random
/// parameters and at the corners of the domain; the domains must agree to the last bit.
template <int D>
double max_difference(const TensorSpline<D>& a, const TensorSpline<D>& b, std::mt19937& rng, int samples = 50) {
  EXPECT_EQ(a.dimension(), b.dimension());
  for (int d = 0; d < D; ++d) {
    EXPECT_EQ(a.domain_min(d), b.domain_min(d));
    EXPECT_EQ(a.domain_max(d), b.domain_max(d));
  }
  double worst = 0.0;
  for (int s = 0; s < samples; ++s) {
    auto t = test_support::random_parameter(rng, a);
    if (s < (1 << D)) {
      for (int d = 0; d < D; ++d) t[static_cast<std::size_t>(d)] = (s >> d) & 1 ? a.domain_max(d) : a.domain_min(d);
    }
    worst = std::max(worst, (a.evaluate(t) - b.evaluate(t)).norm());
  }
  return worst;
}

/// The largest difference between the objects of two models of the same shape, geometry and
/// (where both have them) attributes, by evaluation.
inline double max_model_difference(const Model& a, const Model& b, std::mt19937& rng, bool attributes) {
  EXPECT_EQ(a.objects.size(), b.objects.size());
  double worst = 0.0;
  for (std::size_t i = 0; i < std::min(a.objects.size(), b.objects.size()); ++i) {
    EXPECT_EQ(a.objects[i].spline.index(), b.objects[i].spline.index()) << "object " << i;
    if (a.objects[i].spline.index() != b.objects[i].spline.index()) continue;
    visit_spline(a.objects[i], "comparison", "", [&](const auto& x) {
          using S = std::decay_t<decltype(x)>;
          const S& y = std::get<S>(b.objects[i].spline);
          worst = std::max(worst, max_difference(x, y, rng));
          if (!attributes) return;
          EXPECT_EQ(a.objects[i].attributes.size(), b.objects[i].attributes.size()) << "object " << i;
          for (const auto& [name, values] : a.objects[i].attributes) {
            for (int s = 0; s < 20; ++s) {
              const auto t = test_support::random_parameter(rng, x);
              const std::vector<double> tv(t.begin(), t.end());
              worst = std::max(worst, std::abs(evaluate_attribute(a.objects[i], name, tv) - evaluate_attribute(b.objects[i], name, tv)));
            }
          }
        });
  }
  return worst;
}

}  // namespace volspline::test_support
