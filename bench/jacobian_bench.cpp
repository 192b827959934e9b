// Certified Jacobian analysis and boundary determination (issue 4). Each figure has its
// comparison in the same run:
// - certifying a tricubic Bézier volume valid, against sampling J at the 4 x 4 x 4 Gauss points
//   the way a mesher's (uncertified) element check does;
// - Bernstein bounds against the paper's cone bounds on twisted-loft, both stopping when the
//   bound of J is narrower than the same tolerance (the paper's criterion): cells and time;
// - adaptive subdivision against the uniform marching-tetrahedra baseline at equal accuracy
//   (largest first-order domain distance |J| / |grad J| of an implicit vertex), the uniform
//   resolution being the coarsest power-of-two grid that is at least as accurate.
#include <benchmark/benchmark.h>

#include <random>

#include "volspline/analysis/jacobian_validity.h"
#include "volspline/extract/solid_boundary.h"
#include "volspline/construct/example_solids.h"
#include "volspline/construct/paper_examples.h"
#include "volspline/spline/bezier_extraction.h"

namespace {

using namespace volspline;

BSplineVolume tricubic_bezier() {
  // A bent, jittered tricubic Bézier brick: valid, but not affine.
  std::mt19937 rng(3);
  std::uniform_real_distribution<double> jitter(-0.05, 0.05);
  std::vector<double> p;
  for (int k = 0; k < 4; ++k)
    for (int j = 0; j < 4; ++j)
      for (int i = 0; i < 4; ++i) {
        p.push_back(i / 3.0 + jitter(rng));
        p.push_back(j / 3.0 + 0.3 * (i / 3.0) * (i / 3.0) + jitter(rng));
        p.push_back(k / 3.0 + jitter(rng));
      }
  return BSplineVolume({KnotVector::bezier(3), KnotVector::bezier(3), KnotVector::bezier(3)}, 3, p);
}

void BM_CertifyTricubicBezier(benchmark::State& state) {
  const auto v = tricubic_bezier();
  for (auto _ : state) {
    const auto r = check_jacobian(v);
    if (r.verdict != JacobianVerdict::Valid) state.SkipWithError("not certified valid");
    benchmark::DoNotOptimize(r);
  }
}
BENCHMARK(BM_CertifyTricubicBezier)->Unit(benchmark::kMicrosecond);

void BM_SampledCheckTricubicBezier_Baseline(benchmark::State& state) {
  const auto v = tricubic_bezier();
  const double g[4] = {0.0694318442029737, 0.330009478207572, 0.669990521792428, 0.930568155797026};
  for (auto _ : state) {
    double lo = 1e300;
    double d[12];
    for (double a : g)
      for (double b : g)
        for (double c : g) {
          v.evaluate_derivatives({a, b, c}, 1, d);
          const double j = d[3] * (d[7] * d[11] - d[8] * d[10]) - d[4] * (d[6] * d[11] - d[8] * d[9]) + d[5] * (d[6] * d[10] - d[7] * d[9]);
          lo = std::min(lo, j);
        }
    benchmark::DoNotOptimize(lo);
  }
}
BENCHMARK(BM_SampledCheckTricubicBezier_Baseline)->Unit(benchmark::kMicrosecond);

void BM_TwistedLoftBoundary(benchmark::State& state, JacobianBoundMethod bounds) {
  const auto v = twisted_loft();
  BoundaryOptions o;
  o.bounds = bounds;
  o.stop = StopCriterion::Width;
  o.tolerance = 0.05;
  o.min_level = 0;  // the paper's algorithm: cells are split on their bounds alone
  SolidBoundary r;
  for (auto _ : state) r = jacobian_zero_surface(v, o);
  state.counters["cells"] = static_cast<double>(r.stats.cells_examined);
  state.counters["kept"] = static_cast<double>(r.stats.cells_kept);
  state.counters["triangles"] = static_cast<double>(r.stats.triangles[6]);
}
BENCHMARK_CAPTURE(BM_TwistedLoftBoundary, bezier_width, JacobianBoundMethod::Bezier)->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(BM_TwistedLoftBoundary, cone_width_baseline, JacobianBoundMethod::Cone)->Unit(benchmark::kMillisecond);

// Accuracy reached by the adaptive method at tolerance 1e-4, and the uniform resolution that
// matches it.
struct EqualAccuracy {
  double distance;
  int resolution;
};
const EqualAccuracy& equal_accuracy() {
  static const EqualAccuracy e = [] {
    BoundaryOptions a;
    a.tolerance = 1e-4;
    const double d = jacobian_zero_surface(twisted_loft(), a).stats.max_domain_distance;
    int n = 8;
    BoundaryOptions u;
    u.method = ZeroSurfaceMethod::Uniform;
    while (n < 1024) {
      u.resolution = n;
      if (jacobian_zero_surface(twisted_loft(), u).stats.max_domain_distance <= d) break;
      n *= 2;
    }
    return EqualAccuracy{d, n};
  }();
  return e;
}

void BM_TwistedLoftAdaptive(benchmark::State& state) {
  const auto v = twisted_loft();
  BoundaryOptions o;
  o.tolerance = 1e-4;
  SolidBoundary r;
  for (auto _ : state) r = jacobian_zero_surface(v, o);
  state.counters["cells"] = static_cast<double>(r.stats.cells_examined);
  state.counters["triangles"] = static_cast<double>(r.stats.triangles[6]);
  state.counters["distance"] = r.stats.max_domain_distance;
}
BENCHMARK(BM_TwistedLoftAdaptive)->Unit(benchmark::kMillisecond);

void BM_TwistedLoftUniform_Baseline(benchmark::State& state) {
  const auto v = twisted_loft();
  BoundaryOptions o;
  o.method = ZeroSurfaceMethod::Uniform;
  o.resolution = equal_accuracy().resolution;
  SolidBoundary r;
  for (auto _ : state) r = jacobian_zero_surface(v, o);
  state.counters["resolution"] = o.resolution;
  state.counters["triangles"] = static_cast<double>(r.stats.triangles[6]);
  state.counters["distance"] = r.stats.max_domain_distance;
}
BENCHMARK(BM_TwistedLoftUniform_Baseline)->Unit(benchmark::kMillisecond);

}  // namespace
