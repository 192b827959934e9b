// Fitting volume data (Hua–He–Qin §5, eq. 10; docs/fitting.md, "Speed"): the least squares of a
// degree-2 fit of Marschner–Lobb samples with about 12,000 and 20,000 control vectors, by the
// conjugate-gradient path (loose inner solves refined by the Tikhonov steps) against the baseline
// of the same run, SimplicialLDLT on the normal equations; and the whole fit of 35,937 points.
#include <map>

#include <benchmark/benchmark.h>

#include "volspline/construct/volume_data_examples.h"
#include "volspline/simplex/knot_clouds.h"
#include "volspline/simplex/volume_fitting.h"

namespace {

struct FittingBenchProblem {
  volspline::VolumeData data;
  volspline::DmsSplineVolume volume;
};

const FittingBenchProblem& fitting_bench_problem(int knots) {
  static std::map<int, FittingBenchProblem> problems;
  auto found = problems.find(knots);
  if (found == problems.end()) {
    volspline::VolumeData data = volspline::marschner_lobb_data(31);
    volspline::PointCloudDomainOptions options;
    options.primary_knots = knots;
    volspline::PointCloudDomain domain = volspline::point_cloud_domain(data.points, options);
    volspline::KnotClouds clouds = volspline::generate_knot_clouds(domain.mesh, 2);
    found = problems.emplace(knots, FittingBenchProblem{std::move(data), volspline::DmsSplineVolume(std::move(domain.mesh), std::move(clouds),
                                                                                                      volspline::DmsControlSharing::Shared)})
                .first;
  }
  return found->second;
}

void fitting_bench_solve(benchmark::State& state, bool direct, double inner) {
  const FittingBenchProblem& problem = fitting_bench_problem(static_cast<int>(state.range(0)));
  volspline::ControlVectorFitOptions options;
  options.direct_limit = direct ? 1L << 40 : 0;
  options.inner_tolerance = inner;
  volspline::VolumeFitErrors errors;
  for (auto _ : state) {
    volspline::DmsSplineVolume volume = problem.volume;
    errors = volspline::fit_control_vectors(volume, problem.data, options);
  }
  state.counters["control_vectors"] = problem.volume.control_vector_count();
  state.counters["cg_iterations"] = errors.solver.iterations;
  state.counters["tikhonov_steps"] = errors.solver.tikhonov_steps;
  state.counters["field_mse"] = errors.attributes[0].normalised_mean_square;
}

void BM_FitControlVectorsConjugateGradients(benchmark::State& state) { fitting_bench_solve(state, false, 1e-6); }
BENCHMARK(BM_FitControlVectorsConjugateGradients)->Arg(1300)->Arg(2500)->Unit(benchmark::kSecond)->Iterations(1);

void BM_FitControlVectorsConjugateGradientsLooser(benchmark::State& state) { fitting_bench_solve(state, false, 1e-3); }
BENCHMARK(BM_FitControlVectorsConjugateGradientsLooser)->Arg(1300)->Arg(2500)->Unit(benchmark::kSecond)->Iterations(1);

void BM_FitControlVectorsSimplicialLdlt(benchmark::State& state) { fitting_bench_solve(state, true, 1e-6); }
BENCHMARK(BM_FitControlVectorsSimplicialLdlt)->Arg(1300)->Unit(benchmark::kSecond)->Iterations(1);

void BM_FitVolumeData35937Points(benchmark::State& state) {
  const volspline::VolumeData data = volspline::marschner_lobb_data(33);
  for (auto _ : state) benchmark::DoNotOptimize(volspline::fit_volume_data(data));
}
BENCHMARK(BM_FitVolumeData35937Points)->Unit(benchmark::kSecond)->Iterations(1);

}  // namespace
