// The DMS basis of one tetrahedron (issue 13, simplex/): memoised evaluation of all N_β^I with
// gradients (DmsTetrahedronBasis::evaluate) against the plain unmemoised recurrence of eq. 1 per β
// (simplex_spline_value, values only, so the baseline is if anything flattered), degrees 2 and 3,
// one thread, points uniform in the domain tetrahedron (inside every support: the worst case).
// The Ratio benchmark times both on the same points in the same run and reports the speedup.
// And the line integrals of all N_β^I along random rays through the tetrahedron.
#include <benchmark/benchmark.h>

#include <Eigen/Geometry>

#include <array>
#include <chrono>
#include <limits>
#include <memory>
#include <random>
#include <vector>

#include "volspline/simplex/dms_tetrahedron_basis.h"
#include "volspline/simplex/simplex_spline.h"

namespace {

using namespace volspline;
using Eigen::Vector3d;

struct Setup {
  int degree;
  std::array<std::vector<Vector3d>, 4> clouds;
  std::vector<Vector3d> points;
  std::vector<Vector3d> directions;
  std::vector<std::vector<Vector3d>> knot_sets;  // V_β per β
  std::vector<double> scales;                    // |d(p_i, q_j, r_k, s_l)|

  explicit Setup(int n) : degree(n) {
    std::mt19937 rng(7);
    std::normal_distribution<double> normal(0.0, 0.08);
    std::exponential_distribution<double> e(1.0);
    const std::array<Vector3d, 4> vertices = {Vector3d::Zero(), Vector3d::UnitX(), Vector3d::UnitY(),
                                              Vector3d::UnitZ()};
    for (int c = 0; c < 4; ++c) {
      clouds[c].push_back(vertices[c]);
      for (int i = 1; i <= n; ++i) clouds[c].push_back(vertices[c] + Vector3d(normal(rng), normal(rng), normal(rng)));
    }
    for (int i = 0; i < 4096; ++i) {
      std::array<double, 4> w;
      double total = 0;
      for (double& x : w) total += (x = e(rng));
      Vector3d x = Vector3d::Zero();
      for (int c = 0; c < 4; ++c) x += w[c] / total * vertices[c];
      points.push_back(x);
      directions.push_back(Vector3d(normal(rng), normal(rng), normal(rng)).normalized());
    }
    for (const auto& beta : dms_multi_indices(n)) {
      std::vector<Vector3d> v;
      for (int c = 0; c < 4; ++c) {
        for (int i = 0; i <= beta[c]; ++i) v.push_back(clouds[c][i]);
      }
      knot_sets.push_back(v);
      const Vector3d& a = clouds[0][beta[0]];
      scales.push_back(std::abs((clouds[1][beta[1]] - a).dot((clouds[2][beta[2]] - a).cross(clouds[3][beta[3]] - a))));
    }
  }
  std::array<const Vector3d*, 4> pointers() const {
    return {clouds[0].data(), clouds[1].data(), clouds[2].data(), clouds[3].data()};
  }
};

const Setup& setup(int degree) {
  static std::array<std::unique_ptr<Setup>, kMaxSimplexSplineDegree + 1> setups;
  if (!setups[degree]) setups[degree] = std::make_unique<Setup>(degree);
  return *setups[degree];
}

// 16 tetrahedra: the setup's knot clouds with their sub-knots moved a little more.
std::vector<std::array<std::vector<Vector3d>, 4>> cloud_variants(const Setup& s) {
  std::vector<std::array<std::vector<Vector3d>, 4>> variants;
  std::mt19937 rng(9);
  std::normal_distribution<double> normal(0.0, 0.008);
  for (int v = 0; v < 16; ++v) {
    auto clouds = s.clouds;
    for (auto& cloud : clouds) {
      for (std::size_t i = 1; i < cloud.size(); ++i) cloud[i] += Vector3d(normal(rng), normal(rng), normal(rng));
    }
    variants.push_back(clouds);
  }
  return variants;
}

void BM_DmsEvaluateWithGradient(benchmark::State& state) {
  const Setup& s = setup(static_cast<int>(state.range(0)));
  DmsTetrahedronBasis basis(s.degree);
  DmsBasisValues out;
  std::size_t i = 0;
  for (auto _ : state) {
    basis.evaluate(s.points[i++ & 4095], s.pointers(), 1, out);
    benchmark::DoNotOptimize(out.values.data());
  }
  state.SetItemsProcessed(state.iterations());
}
BENCHMARK(BM_DmsEvaluateWithGradient)->Arg(2)->Arg(3);

// Each point in another of 16 tetrahedra (more than the basis caches plans for): every call
// compiles its recurrence plan, as scattered points over a large domain do.
void BM_DmsEvaluateWithGradientNewTetrahedronEachPoint(benchmark::State& state) {
  const int degree = static_cast<int>(state.range(0));
  const Setup& s = setup(degree);
  const auto variants = cloud_variants(s);
  DmsTetrahedronBasis basis(degree);
  DmsBasisValues out;
  std::size_t i = 0;
  for (auto _ : state) {
    const auto& clouds = variants[i % 16];
    basis.evaluate(s.points[i & 4095], {clouds[0].data(), clouds[1].data(), clouds[2].data(), clouds[3].data()}, 1,
                   out);
    ++i;
    benchmark::DoNotOptimize(out.values.data());
  }
  state.SetItemsProcessed(state.iterations());
}
BENCHMARK(BM_DmsEvaluateWithGradientNewTetrahedronEachPoint)->Arg(2)->Arg(3);

// The same scattered points with one DmsTetrahedronPlan compiled beforehand per tetrahedron (as a
// spline volume keeps them): no recompilation.
void BM_DmsEvaluateWithGradientFromPlans(benchmark::State& state) {
  const int degree = static_cast<int>(state.range(0));
  const Setup& s = setup(degree);
  std::vector<DmsTetrahedronPlan> plans;
  for (const auto& clouds : cloud_variants(s)) {
    plans.emplace_back(degree, std::array<const Vector3d*, 4>{clouds[0].data(), clouds[1].data(), clouds[2].data(),
                                                               clouds[3].data()});
  }
  DmsTetrahedronBasis basis(degree);
  DmsBasisValues out;
  std::size_t i = 0;
  for (auto _ : state) {
    basis.evaluate(s.points[i & 4095], plans[i % 16], 1, out);
    ++i;
    benchmark::DoNotOptimize(out.values.data());
  }
  state.SetItemsProcessed(state.iterations());
  state.SetLabel(std::to_string(plans[0].memory_bytes() / 1024) + " KiB per plan");
}
BENCHMARK(BM_DmsEvaluateWithGradientFromPlans)->Arg(2)->Arg(3);

void BM_UnmemoisedValuesPerBeta(benchmark::State& state) {
  const Setup& s = setup(static_cast<int>(state.range(0)));
  std::size_t i = 0;
  for (auto _ : state) {
    const Vector3d& x = s.points[i++ & 4095];
    double sum = 0;
    for (std::size_t b = 0; b < s.knot_sets.size(); ++b) sum += s.scales[b] * simplex_spline_value(x, s.knot_sets[b]);
    benchmark::DoNotOptimize(sum);
  }
  state.SetItemsProcessed(state.iterations());
}
BENCHMARK(BM_UnmemoisedValuesPerBeta)->Arg(2)->Arg(3);

// Both on the same 256 points per iteration; counters: points per second of each and the ratio.
void BM_MemoisedOverUnmemoisedRatio(benchmark::State& state) {
  const Setup& s = setup(static_cast<int>(state.range(0)));
  DmsTetrahedronBasis basis(s.degree);
  DmsBasisValues out;
  double memoised_seconds = 0;
  double plain_seconds = 0;
  std::size_t points = 0;
  for (auto _ : state) {
    const auto t0 = std::chrono::steady_clock::now();
    for (int i = 0; i < 256; ++i) {
      basis.evaluate(s.points[i], s.pointers(), 1, out);
      benchmark::DoNotOptimize(out.values.data());
    }
    const auto t1 = std::chrono::steady_clock::now();
    for (int i = 0; i < 256; ++i) {
      double sum = 0;
      for (std::size_t b = 0; b < s.knot_sets.size(); ++b) {
        sum += s.scales[b] * simplex_spline_value(s.points[i], s.knot_sets[b]);
      }
      benchmark::DoNotOptimize(sum);
    }
    const auto t2 = std::chrono::steady_clock::now();
    memoised_seconds += std::chrono::duration<double>(t1 - t0).count();
    plain_seconds += std::chrono::duration<double>(t2 - t1).count();
    points += 256;
  }
  state.counters["memoised_pts_per_s"] = static_cast<double>(points) / memoised_seconds;
  state.counters["unmemoised_pts_per_s"] = static_cast<double>(points) / plain_seconds;
  state.counters["speedup"] = plain_seconds / memoised_seconds;
}
BENCHMARK(BM_MemoisedOverUnmemoisedRatio)->Arg(2)->Arg(3);

void BM_DmsLineIntegrals(benchmark::State& state) {
  const Setup& s = setup(static_cast<int>(state.range(0)));
  DmsTetrahedronBasis basis(s.degree);
  std::vector<double> out;
  std::size_t i = 0;
  const double infinity = std::numeric_limits<double>::infinity();
  for (auto _ : state) {
    const std::size_t k = i++ & 4095;
    basis.line_integrals(s.points[k], s.directions[k], -infinity, infinity, s.pointers(), out);
    benchmark::DoNotOptimize(out.data());
  }
  state.SetItemsProcessed(state.iterations());
}
BENCHMARK(BM_DmsLineIntegrals)->Arg(2)->Arg(3);

}  // namespace
