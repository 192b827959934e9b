// The long operations report their phases through core/progress.h: in order, with monotone
// fractions, counts that agree with their statistics, and without changing their results.
#include <gtest/gtest.h>

#include <mutex>
#include <string>
#include <vector>

#include "volspline/analysis/jacobian_validity.h"
#include "volspline/extract/solid_boundary.h"
#include "volspline/boxspline/blend_examples.h"
#include "volspline/boxspline/zero_set.h"
#include "volspline/construct/example_solids.h"
#include "volspline/construct/paper_examples.h"
#include "volspline/construct/primitives.h"
#include "volspline/core/progress.h"

namespace volspline {
namespace {

struct PhaseRecord {
  std::string name;
  double done = 0;
  double last_fraction = 0;
  bool monotone = true;
};

// Collects the phases of one operation: names in order, the count at the end, and whether the
// fraction ever decreased.
struct PhaseLog {
  std::mutex mutex;
  std::vector<PhaseRecord> phases;
  Progress progress{[this](const ProgressEvent& e) {
    std::lock_guard lock(mutex);
    if (e.kind == ProgressEvent::Kind::PhaseBegin) {
      phases.push_back({std::string(e.phase)});
      return;
    }
    PhaseRecord& p = phases.back();
    EXPECT_EQ(p.name, e.phase);
    p.monotone = p.monotone && e.fraction >= p.last_fraction && e.fraction <= 1.0;
    p.last_fraction = e.fraction;
    if (e.kind == ProgressEvent::Kind::PhaseEnd) p.done = e.done;
  }};
  std::vector<std::string> names() const {
    std::vector<std::string> n;
    for (const auto& p : phases) n.push_back(p.name);
    return n;
  }
};

TEST(ProgressReporting, SolidBoundaryPhasesAndCellCount) {
  const BSplineVolume v = twisted_loft();
  BoundaryOptions options;
  options.snap = true;
  const SolidBoundary plain = solid_boundary(v, options);
  PhaseLog log;
  options.progress = &log.progress;
  const SolidBoundary reported = solid_boundary(v, options);
  EXPECT_EQ(log.names(), (std::vector<std::string>{"subdivision", "tetrahedra", "marching", "snap", "mapping", "faces"}));
  for (const auto& p : log.phases) EXPECT_TRUE(p.monotone) << p.name;
  EXPECT_EQ(log.phases[0].done, static_cast<double>(reported.stats.cells_examined));
  EXPECT_DOUBLE_EQ(log.phases[2].last_fraction, 1.0);  // every tetrahedron marched
  EXPECT_DOUBLE_EQ(log.phases[3].last_fraction, 1.0);  // every vertex snapped
  EXPECT_EQ(reported.mesh.positions, plain.mesh.positions);
  EXPECT_EQ(reported.mesh.triangles, plain.mesh.triangles);

  PhaseLog uniform;
  options.method = ZeroSurfaceMethod::Uniform;
  options.resolution = 8;
  options.snap = false;
  options.progress = &uniform.progress;
  solid_boundary(v, options);
  EXPECT_EQ(uniform.names(), (std::vector<std::string>{"sampling", "marching", "mapping", "faces"}));
  EXPECT_EQ(uniform.phases[1].done, 8.0);  // one unit per layer of cubes
}

TEST(ProgressReporting, JacobianCertificationCountsItsCells) {
  for (const BSplineVolume& v : {bent_tricubic_volume(), half_cylinder_sweep()}) {
    PhaseLog log;
    JacobianValidityOptions options;
    options.progress = &log.progress;
    const JacobianValidity r = check_jacobian(v, options);
    ASSERT_EQ(log.names(), std::vector<std::string>{"certification"});
    EXPECT_EQ(log.phases[0].done, static_cast<double>(r.cells));
    options.progress = nullptr;
    EXPECT_EQ(check_jacobian(v, options).verdict, r.verdict);
  }
}

TEST(ProgressReporting, ZeroSetPhases) {
  PhaseLog log;
  ZeroSetOptions options{.levels = 1, .method = ZeroSetMethod::Exact, .project = true};
  options.progress = &log.progress;
  const ZeroSet z = scene_zero_set(cylinder_intersection_scene(), options);
  EXPECT_EQ(log.names(), (std::vector<std::string>{"refinement", "values", "marching", "projection", "statistics"}));
  for (const auto& p : log.phases) EXPECT_TRUE(p.monotone) << p.name;
  EXPECT_DOUBLE_EQ(log.phases[1].last_fraction, 1.0);  // every layer of grid nodes
  EXPECT_EQ(log.phases[3].done, static_cast<double>(z.mesh.num_vertices()));
  options.progress = nullptr;
  EXPECT_EQ(scene_zero_set(cylinder_intersection_scene(), options).mesh.positions, z.mesh.positions);
}

}  // namespace
}  // namespace volspline
