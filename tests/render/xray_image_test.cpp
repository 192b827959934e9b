// X-ray pictures of simplex spline volumes (Hua–He–Qin §6.1): the line integral of a constant 1
// is the chord length through Ω, of a linear attribute the chord length times its value at the
// chord's midpoint; the incremental update of eq. 12 equals rendering again.
#include <cmath>
#include <limits>

#include <gtest/gtest.h>

#include "support/simplex_domains.h"
#include "volspline/core/error.h"
#include "volspline/render/xray_image.h"

namespace volspline {
namespace {

// The chord of a ray through the unit cube, by slab clipping.
bool cube_chord(const Eigen::Vector3d& o, const Eigen::Vector3d& d, double& t0, double& t1) {
  t0 = -1e300, t1 = 1e300;
  for (int a = 0; a < 3; ++a) {
    if (d[a] == 0) {
      if (o[a] < 0 || o[a] > 1) return false;
      continue;
    }
    double u = -o[a] / d[a], v = (1 - o[a]) / d[a];
    if (u > v) std::swap(u, v);
    t0 = std::max(t0, u), t1 = std::min(t1, v);
  }
  return t0 < t1;
}

XrayOptions small_options() {
  XrayOptions options;
  options.width = 24;
  options.height = 20;
  return options;
}

TEST(XrayImage, ConstantAttributeGivesTheChordLengthsOfTheDomain) {
  for (const double fov : {0.0, 30.0}) {
    DmsSplineVolume v = test_support::cube_simplex_volume(2);
    v.control_vectors().col(3).setOnes();
    XrayOptions options = small_options();
    options.field_of_view_deg = fov;
    const XrayRenderer renderer(v, options);
    int hits = 0;
    for (int y = 0; y < options.height; ++y)
      for (int x = 0; x < options.width; ++x) {
        Eigen::Vector3d o, d;
        renderer.pixel_ray(x, y, o, d);
        double t0, t1;
        const double expected = cube_chord(o, d, t0, t1) ? t1 - t0 : 0.0;
        hits += expected > 0;
        EXPECT_NEAR(renderer.picture().line_integrals[static_cast<std::size_t>(y * options.width + x)], expected, 1e-10)
            << "pixel " << x << ", " << y << " fov " << fov;
      }
    EXPECT_GT(hits, options.width * options.height / 4);
  }
}

TEST(XrayImage, LinearAttributeIntegratesToLengthTimesMidpointValue) {
  for (const int degree : {1, 3}) {
    DmsSplineVolume v = test_support::cube_simplex_volume(degree);
    const Eigen::Vector3d a(0.7, -0.4, 1.3);
    const double b = 0.5;
    set_column_from_blossom(v, 3, [&](std::span<const Eigen::Vector3d> args) {
      Eigen::Vector3d mean = Eigen::Vector3d::Zero();
      for (const auto& x : args) mean += x;
      return a.dot(mean / static_cast<double>(args.size())) + b;  // the blossom of an affine function
    });
    const XrayOptions options = small_options();
    const XrayRenderer renderer(v, options);
    for (int y = 0; y < options.height; ++y)
      for (int x = 0; x < options.width; ++x) {
        Eigen::Vector3d o, d;
        renderer.pixel_ray(x, y, o, d);
        double t0, t1;
        const double expected = cube_chord(o, d, t0, t1) ? (t1 - t0) * (a.dot(o + (t0 + t1) / 2 * d) + b) : 0.0;
        // Whole chords through Ω go to the kernel (ends outside a support need no boundary
        // terms, which is faster); over chords that long the recurrence keeps about 1e-10.
        EXPECT_NEAR(renderer.picture().line_integrals[static_cast<std::size_t>(y * options.width + x)], expected, 1e-9);
      }
  }
}

// A baseline b: the line integral of f - b, i.e. the integral of f less b times the chord.
TEST(XrayImage, ABaselineIsSubtractedAlongTheChord) {
  DmsSplineVolume v = test_support::cube_simplex_volume(2);
  const Eigen::Vector3d a(0.7, -0.4, 1.3);
  set_column_from_blossom(v, 3, [&](std::span<const Eigen::Vector3d> args) {
    Eigen::Vector3d mean = Eigen::Vector3d::Zero();
    for (const auto& x : args) mean += x;
    return a.dot(mean / static_cast<double>(args.size())) + 300;  // an affine field around 300
  });
  XrayOptions options = small_options();
  const XrayRenderer plain(v, options);
  options.baseline = 298;
  const XrayRenderer above(v, options);
  for (int y = 0; y < options.height; ++y)
    for (int x = 0; x < options.width; ++x) {
      Eigen::Vector3d o, d;
      above.pixel_ray(x, y, o, d);
      double t0, t1;
      const double chord = cube_chord(o, d, t0, t1) ? t1 - t0 : 0.0;
      const auto p = static_cast<std::size_t>(y * options.width + x);
      EXPECT_NEAR(above.picture().line_integrals[p], plain.picture().line_integrals[p] - 298 * chord, 1e-8);
      EXPECT_NEAR(above.picture().line_integrals[p], chord * (a.dot(o + (t0 + t1) / 2 * d) + 2), 1e-8);
    }
  options.baseline = std::numeric_limits<double>::infinity();
  EXPECT_THROW(XrayRenderer(v, options), InvalidInput);
}

TEST(XrayImage, IncrementalUpdateEqualsRenderingAgain) {
  DmsSplineVolume v = test_support::cube_simplex_volume(2);
  for (Eigen::Index r = 0; r < v.control_vectors().rows(); ++r) v.control_vectors()(r, 3) = std::sin(3.0 * static_cast<double>(r));
  XrayOptions options = small_options();
  XrayRenderer renderer(v, options);
  const std::vector<double> before = renderer.picture().line_integrals;
  const int row = v.control_vector_count() / 2;
  v.control_vectors()(row, 3) += 0.75;
  const int touched = renderer.update_coefficient(row, 0.75);
  const std::vector<double> updated = renderer.picture().line_integrals;
  renderer.render();
  int changed = 0;
  for (std::size_t p = 0; p < updated.size(); ++p) {
    EXPECT_NEAR(updated[p], renderer.picture().line_integrals[p], 1e-12);
    changed += std::abs(updated[p] - before[p]) > 1e-14;
  }
  EXPECT_GT(changed, 0);
  EXPECT_LE(changed, touched);
  EXPECT_LT(touched, options.width * options.height);  // local: not every pixel
  EXPECT_THROW(renderer.update_coefficient(-1, 1.0), InvalidInput);
}

TEST(XrayImage, RefusesBadRequests) {
  const DmsSplineVolume v = test_support::cube_simplex_volume(1);
  XrayOptions options = small_options();
  options.attribute = "temperature";
  EXPECT_THROW(XrayRenderer(v, options), InvalidInput);
  options = small_options();
  options.view_direction = Eigen::Vector3d(0, 0, 1);
  EXPECT_THROW(XrayRenderer(v, options), InvalidInput);  // up parallel to the view
  options = small_options();
  options.width = 0;
  EXPECT_THROW(XrayRenderer(v, options), InvalidInput);
}

}  // namespace
}  // namespace volspline
