// Knot-cloud generation and validation (Hua–He–Qin §3.2) on a Delaunay cube of about 2,000
// tetrahedra; the target is validation of the whole domain in at most 1 s.
#include <benchmark/benchmark.h>

#include "support/tetrahedral_domains.h"
#include "volspline/simplex/knot_clouds.h"

namespace {

const volspline::TetrahedralMesh& domain() {
  // 8^3 jittered grid points: about 2,000 tetrahedra.
  static const volspline::TetrahedralMesh mesh = volspline::test_support::delaunay_cube(8);
  return mesh;
}

void BM_ValidateKnotClouds(benchmark::State& state) {
  const int degree = static_cast<int>(state.range(0));
  const volspline::KnotClouds clouds = volspline::generate_knot_clouds(domain(), degree);
  for (auto _ : state) volspline::validate_knot_clouds(domain(), clouds);
  state.counters["tetrahedra"] = static_cast<double>(domain().tetrahedra.size());
}
BENCHMARK(BM_ValidateKnotClouds)->DenseRange(1, 4)->Unit(benchmark::kMillisecond);

void BM_GenerateKnotClouds(benchmark::State& state) {
  const int degree = static_cast<int>(state.range(0));
  for (auto _ : state) benchmark::DoNotOptimize(volspline::generate_knot_clouds(domain(), degree));
  state.counters["tetrahedra"] = static_cast<double>(domain().tetrahedra.size());
}
BENCHMARK(BM_GenerateKnotClouds)->DenseRange(1, 4)->Unit(benchmark::kMillisecond);

}  // namespace
