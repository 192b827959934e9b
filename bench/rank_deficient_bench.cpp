// The rank-deficient set of a swept solid (Conkey–Joy 2000 §5, §6): the Bernstein certificates
// of the four sub-Jacobians (strict sign, separating direction of the coefficient 4-vectors)
// against the paper's cone bounds, on one folded generator that is sheared and turned as it
// moves, both refined to the same finest level: cells examined and kept, triangles and time, in
// the same run.
#include <benchmark/benchmark.h>

#include "../tests/support/translated_generators.h"
#include "volspline/extract/rank_deficient_surface.h"

namespace {

using namespace volspline;

BSplineHypervolume turning_fold() {
  // h = (w - 0.37)^2 + u v^2, x = u + w / 2, swept along (1, 0.3, 0.45) while turning.
  const double c = 0.37;
  return test_support::translated_generator({{1.0, 0, 0, 2}, {-2 * c, 0, 0, 1}, {c * c, 0, 0, 0}, {1.0, 1, 2, 0}}, {1, 2, 2},
                                            {1.0, 0.3, 0.45}, {0, -0.6, 0.2, 0.6, 0, -0.3, -0.2, 0.3, 0}, 1.0, 0.5);
}

void BM_TurningFoldRankDeficient(benchmark::State& state, JacobianBoundMethod bounds) {
  const auto map = turning_fold();
  RankDeficientOptions options;
  options.bounds = bounds;
  options.tolerance = 1.0 / 16;
  RankDeficientSurface r;
  for (auto _ : state) {
    r = rank_deficient_surface(map, options);
    benchmark::DoNotOptimize(r.mesh.triangles.data());
  }
  state.counters["cells"] = static_cast<double>(r.stats.cells_examined);
  state.counters["kept"] = static_cast<double>(r.stats.cells_kept);
  state.counters["by_hull"] = static_cast<double>(r.stats.cells_excluded_by_hull);
  state.counters["triangles"] = static_cast<double>(r.stats.triangles);
  state.counters["s_subdivision"] = r.stats.seconds_subdivision;
  state.counters["s_marching"] = r.stats.seconds_marching;
}
BENCHMARK_CAPTURE(BM_TurningFoldRankDeficient, bezier, JacobianBoundMethod::Bezier)->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(BM_TurningFoldRankDeficient, cone_baseline, JacobianBoundMethod::Cone)->Unit(benchmark::kMillisecond);

}  // namespace
