// Knot-cloud generation and validation (Hua–He–Qin §3.2) on a Delaunay cube of about 2,000
// tetrahedra; the target is validation of the whole domain in at most 1 s.
#include <benchmark/benchmark.h>

#include "support/tetrahedral_domains.h"
#include "volspline/core/error.h"
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

namespace {

// One tetrahedron (p, q, r, s) whose knot tetrahedra need more than the centroid certificate:
// p_1 just above the face qrs makes [p_1, q, r, s] a thin wedge. With q_1 outside, the common
// interior is that wedge (the relaxation method finds a witness); with q_1 just beside the face
// prs too, the two wedges meet only on the edge rs and the exact linear programme decides that
// the interior is empty. Either way validation then throws (p_1 lies inside Ω, or eq. 3): the
// time is that of the decision.
void validate_one_tetrahedron(benchmark::State& state, const Eigen::Vector3d& q_1) {
  const volspline::TetrahedralMesh domain{{{0, 0, 1}, {0, 1, 0}, {1, 0, 0}, {0, 0, 0}}, {{0, 1, 2, 3}}};
  const volspline::KnotClouds clouds{1, {domain.points[0], {0.25, 0.25, 1e-3}, domain.points[1], q_1,
                                         domain.points[2], {1.1, -0.1, -0.1}, domain.points[3], {-0.1, -0.1, -0.1}}};
  for (auto _ : state) {
    try {
      volspline::validate_knot_clouds(domain, clouds);
    } catch (const volspline::InvalidInput&) {
    }
  }
}
void BM_RelaxationWitnessOfOneTetrahedron(benchmark::State& state) { validate_one_tetrahedron(state, {-0.1, 1.1, -0.1}); }
void BM_ExactEmptyInteriorOfOneTetrahedron(benchmark::State& state) { validate_one_tetrahedron(state, {0.25, 1e-3, 0.25}); }
BENCHMARK(BM_RelaxationWitnessOfOneTetrahedron)->Unit(benchmark::kMicrosecond);
BENCHMARK(BM_ExactEmptyInteriorOfOneTetrahedron)->Unit(benchmark::kMicrosecond);

}  // namespace
