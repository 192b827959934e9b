// The 7-direction box spline (issue 6): scattered evaluation of value + gradient, BB form against
// assembling each piece from the coefficients (the straightforward exact method, baseline); and
// the cylinder intersection of Peters & Wittman Fig. 1c (control method, two subdivisions).
#include <benchmark/benchmark.h>

#include <random>

#include "volspline/boxspline/bezier_form.h"
#include "volspline/boxspline/blend_examples.h"
#include "volspline/boxspline/lattice_field.h"
#include "volspline/boxspline/zero_set.h"

namespace {

using namespace volspline;

struct Setup {
  LatticeField field;
  std::vector<Eigen::Vector3d> points;
  explicit Setup(double h) {
    // h = 0.1: 25³ coefficients, BB form 62 MB (beyond the caches); h = 0.25: 13³, BB form 4.9 MB.
    field = lattice_covering(Eigen::Vector3d::Constant(-1.0), Eigen::Vector3d::Constant(1.0), h);
    std::mt19937 rng(1);
    std::uniform_real_distribution<double> u(-1.0, 1.0);
    for (double& c : field.coefficients) c = u(rng);
    for (int i = 0; i < 1 << 16; ++i) points.emplace_back(u(rng), u(rng), u(rng));
  }
};

const Setup& setup(int which = 0) {
  static const Setup large(0.1), small(0.25);
  return which == 0 ? large : small;
}

void BM_ScatteredValueGradient_BezierForm(benchmark::State& state) {
  const Setup& s = setup(static_cast<int>(state.range(0)));
  const BezierFormField form(s.field);
  std::size_t i = 0;
  Eigen::Vector3d g;
  for (auto _ : state) {
    benchmark::DoNotOptimize(form.evaluate(s.points[i], &g));
    benchmark::DoNotOptimize(g);
    i = (i + 1) & (s.points.size() - 1);
  }
  state.SetItemsProcessed(state.iterations());
}
BENCHMARK(BM_ScatteredValueGradient_BezierForm)->Arg(0)->Arg(1);

void BM_ScatteredValueGradient_AssembledBaseline(benchmark::State& state) {
  const Setup& s = setup(static_cast<int>(state.range(0)));
  std::size_t i = 0;
  Eigen::Vector3d g;
  for (auto _ : state) {
    benchmark::DoNotOptimize(s.field.evaluate(s.points[i], &g));
    benchmark::DoNotOptimize(g);
    i = (i + 1) & (s.points.size() - 1);
  }
  state.SetItemsProcessed(state.iterations());
}
BENCHMARK(BM_ScatteredValueGradient_AssembledBaseline)->Arg(0)->Arg(1);

void BM_BezierFormConstruction(benchmark::State& state) {
  const Setup& s = setup();
  for (auto _ : state) benchmark::DoNotOptimize(BezierFormField(s.field));
}
BENCHMARK(BM_BezierFormConstruction)->Unit(benchmark::kMillisecond);

// Fig. 1c: scene to mesh, control method, two subdivisions.
void BM_Fig1cCylinderIntersection_Control2(benchmark::State& state) {
  const Scene scene = cylinder_intersection_scene();
  std::size_t triangles = 0;
  for (auto _ : state) triangles = scene_zero_set(scene, {.levels = 2, .method = ZeroSetMethod::Control, .statistics = false}).mesh.num_triangles();
  state.counters["triangles"] = static_cast<double>(triangles);
}
BENCHMARK(BM_Fig1cCylinderIntersection_Control2)->Unit(benchmark::kMillisecond);

// Baseline: the same surface from exact spline values (exact method, same grid).
void BM_Fig1cCylinderIntersection_Exact2Baseline(benchmark::State& state) {
  const Scene scene = cylinder_intersection_scene();
  for (auto _ : state) benchmark::DoNotOptimize(scene_zero_set(scene, {.levels = 2, .method = ZeroSetMethod::Exact, .statistics = false}));
}
BENCHMARK(BM_Fig1cCylinderIntersection_Exact2Baseline)->Unit(benchmark::kMillisecond);

}  // namespace
