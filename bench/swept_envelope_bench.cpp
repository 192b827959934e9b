// The whole trimmed envelope of a swept solid (superset, then contouring the certified
// membership, extract/swept_envelope.h) for the paper's examples (Conkey–Joy 2000, Figs. 4-8)
// and the two analytic sweeps, at tolerance 1e-3 of the bounding-box diagonal (the capsule at 1e-4
// too); and, in the same
// run, the Bernstein exclusion of the rank-deficient set against the paper's cone bounds on the
// examples that have one (the superset alone, Bézier vs cone).
#include <benchmark/benchmark.h>

#include "volspline/construct/swept_examples.h"
#include "volspline/extract/swept_envelope.h"

namespace {

using namespace volspline;

SweptSolid swept_bench_example(int which) {
  switch (which) {
    case 0: return torus_along_semicircle();
    case 1: return tumbling_cylinder();
    case 2: return folded_cube_along_cubic();
    case 3: return turning_folded_cylinder();
    case 4: return tumbling_folded_cube();
    case 5: return translated_ball(0.5, {1.2, 0.3, -0.2});
    case 7: return translated_ball(1.0, {3, 0, 0});
    default: return rotating_box();
  }
}

void BM_SweptEnvelope(benchmark::State& state, int which, bool trim, JacobianBoundMethod bounds, double coarse_cells = 0,
                      int adaptive_ratio = 0, bool halving_levels = true, double tolerance = 1e-3) {
  const auto patches = swept_patches(swept_bench_example(which));
  SweptEnvelopeOptions options;
  options.trim = trim;
  options.tolerance = tolerance;
  options.bounds = bounds;
  options.coarse_cell_factor = coarse_cells;
  options.adaptive_ratio = adaptive_ratio;
  options.contouring.halving_levels = halving_levels;
  SweptEnvelope e;
  for (auto _ : state) {
    e = swept_envelope(patches, options);
    benchmark::DoNotOptimize(e.mesh.triangles.data());
  }
  const SweptEnvelopeStats& s = e.stats;
  state.counters["triangles"] = static_cast<double>(e.mesh.num_triangles());
  state.counters["rank_cells"] = static_cast<double>(s.rank_cells_examined);
  state.counters["rank_parts"] = static_cast<double>(s.rank_part_cells_examined);
  state.counters["fold_cells"] = static_cast<double>(s.cells_examined);
  state.counters["s_superset"] = s.seconds_faces + s.seconds_folds + s.seconds_rank_deficient;
  state.counters["s_rank"] = s.seconds_rank_deficient;
  if (trim) {
    state.counters["closed"] = s.trimming.closed && s.trimming.oriented && s.trimming.self_intersection_free;
    state.counters["volume"] = s.trimming.volume;
    state.counters["grid_cells"] = static_cast<double>(s.trimming.grid_cells);
    state.counters["queries"] = static_cast<double>(s.trimming.membership_queries);
    state.counters["cells_refined"] = static_cast<double>(s.trimming.grid_cells_refined);
    state.counters["beyond_tol"] = static_cast<double>(s.trimming.refinement_edges_beyond_tolerance);
  }
}
constexpr auto kBezier = JacobianBoundMethod::Bezier;
constexpr auto kCone = JacobianBoundMethod::Cone;
BENCHMARK_CAPTURE(BM_SweptEnvelope, fig4_torus_trimmed, 0, true, kBezier)->Unit(benchmark::kMillisecond)->Iterations(1);
BENCHMARK_CAPTURE(BM_SweptEnvelope, fig5_tumbling_cylinder_trimmed, 1, true, kBezier)->Unit(benchmark::kMillisecond)->Iterations(1);
BENCHMARK_CAPTURE(BM_SweptEnvelope, fig6_folded_cube_trimmed, 2, true, kBezier)->Unit(benchmark::kMillisecond)->Iterations(1);
BENCHMARK_CAPTURE(BM_SweptEnvelope, fig7_turning_folded_cylinder_trimmed, 3, true, kBezier)->Unit(benchmark::kMillisecond)->Iterations(1);
BENCHMARK_CAPTURE(BM_SweptEnvelope, fig8_tumbling_folded_cube_trimmed, 4, true, kBezier)->Unit(benchmark::kMillisecond)->Iterations(1);
BENCHMARK_CAPTURE(BM_SweptEnvelope, capsule_trimmed, 5, true, kBezier)->Unit(benchmark::kMillisecond)->Iterations(1);
BENCHMARK_CAPTURE(BM_SweptEnvelope, annulus_trimmed, 6, true, kBezier)->Unit(benchmark::kMillisecond)->Iterations(1);
// Bernstein against cone bounds on the superset (the rank-deficient set and the 3-face folds).
// A coarse grid (16 x the tolerance) refined toward the sheets (`--coarse-cells 16`).
BENCHMARK_CAPTURE(BM_SweptEnvelope, fig4_torus_coarse16, 0, true, kBezier, 16.0)->Unit(benchmark::kMillisecond)->Iterations(1);
BENCHMARK_CAPTURE(BM_SweptEnvelope, fig7_turning_folded_cylinder_coarse16, 3, true, kBezier, 16.0)->Unit(benchmark::kMillisecond)->Iterations(1);
BENCHMARK_CAPTURE(BM_SweptEnvelope, capsule_coarse16, 5, true, kBezier, 16.0)->Unit(benchmark::kMillisecond)->Iterations(1);

// Adaptive cells (`--adaptive-cells 4`): 12 x the tolerance, 3 x at the creases; the same
// examples as the default grid above (the baseline of the ratio).
BENCHMARK_CAPTURE(BM_SweptEnvelope, fig4_torus_adaptive4, 0, true, kBezier, 0.0, 4)->Unit(benchmark::kMillisecond)->Iterations(1);
BENCHMARK_CAPTURE(BM_SweptEnvelope, fig5_tumbling_cylinder_adaptive4, 1, true, kBezier, 0.0, 4)->Unit(benchmark::kMillisecond)->Iterations(1);
BENCHMARK_CAPTURE(BM_SweptEnvelope, fig6_folded_cube_adaptive4, 2, true, kBezier, 0.0, 4)->Unit(benchmark::kMillisecond)->Iterations(1);
BENCHMARK_CAPTURE(BM_SweptEnvelope, fig7_turning_folded_cylinder_adaptive4, 3, true, kBezier, 0.0, 4)->Unit(benchmark::kMillisecond)->Iterations(1);
BENCHMARK_CAPTURE(BM_SweptEnvelope, fig8_tumbling_folded_cube_adaptive4, 4, true, kBezier, 0.0, 4)->Unit(benchmark::kMillisecond)->Iterations(1);
BENCHMARK_CAPTURE(BM_SweptEnvelope, capsule_adaptive4, 5, true, kBezier, 0.0, 4)->Unit(benchmark::kMillisecond)->Iterations(1);
BENCHMARK_CAPTURE(BM_SweptEnvelope, annulus_adaptive4, 6, true, kBezier, 0.0, 4)->Unit(benchmark::kMillisecond)->Iterations(1);
// The baseline of the octree: adaptive cells split straight into unit cells (halving_levels off,
// the complex before 2026-12-07).
BENCHMARK_CAPTURE(BM_SweptEnvelope, fig4_torus_adaptive4_unit_split, 0, true, kBezier, 0.0, 4, false)->Unit(benchmark::kMillisecond)->Iterations(1);
BENCHMARK_CAPTURE(BM_SweptEnvelope, fig5_tumbling_cylinder_adaptive4_unit_split, 1, true, kBezier, 0.0, 4, false)->Unit(benchmark::kMillisecond)->Iterations(1);
BENCHMARK_CAPTURE(BM_SweptEnvelope, fig6_folded_cube_adaptive4_unit_split, 2, true, kBezier, 0.0, 4, false)->Unit(benchmark::kMillisecond)->Iterations(1);
BENCHMARK_CAPTURE(BM_SweptEnvelope, fig7_turning_folded_cylinder_adaptive4_unit_split, 3, true, kBezier, 0.0, 4, false)->Unit(benchmark::kMillisecond)->Iterations(1);
BENCHMARK_CAPTURE(BM_SweptEnvelope, fig8_tumbling_folded_cube_adaptive4_unit_split, 4, true, kBezier, 0.0, 4, false)->Unit(benchmark::kMillisecond)->Iterations(1);
BENCHMARK_CAPTURE(BM_SweptEnvelope, capsule_adaptive4_unit_split, 5, true, kBezier, 0.0, 4, false)->Unit(benchmark::kMillisecond)->Iterations(1);
BENCHMARK_CAPTURE(BM_SweptEnvelope, annulus_adaptive4_unit_split, 6, true, kBezier, 0.0, 4, false)->Unit(benchmark::kMillisecond)->Iterations(1);

// Tolerance 1e-4 (the issue's ≤ 10 s): the automatic adaptive ratio (32) against the old
// default of 4 (docs/envelopes.md, "Fine tolerances"); the capsule (radius 1 along 3, as
// examples/swept-translated-ball.json, whose coarse cells matter most: it has no crease).
BENCHMARK_CAPTURE(BM_SweptEnvelope, capsule_tol1e4_automatic, 7, true, kBezier, 0.0, SweptEnvelopeOptions::kAutomaticRatio, true, 1e-4)
    ->Unit(benchmark::kMillisecond)->Iterations(1);
BENCHMARK_CAPTURE(BM_SweptEnvelope, capsule_tol1e4_adaptive4_baseline, 7, true, kBezier, 0.0, 4, true, 1e-4)
    ->Unit(benchmark::kMillisecond)->Iterations(1);
BENCHMARK_CAPTURE(BM_SweptEnvelope, fig6_superset_bezier, 2, false, kBezier)->Unit(benchmark::kMillisecond)->Iterations(1);
BENCHMARK_CAPTURE(BM_SweptEnvelope, fig6_superset_cone_baseline, 2, false, kCone)->Unit(benchmark::kMillisecond)->Iterations(1);

}  // namespace
