// DMS simplex spline volumes on a domain of about 2,000 tetrahedra (Hua–He–Qin; issue 13's
// targets): evaluation of geometry + one attribute with gradient, memoised against the plain
// recurrence per basis function in the same run; X-ray pictures against ray marching with
// adaptive quadrature at the same accuracy; the incremental update of eq. 12.
//
// Run: build/bin/simplex_volume_bench (docs/performance.md records the figures).
#include <algorithm>
#include <cmath>
#include <functional>
#include <map>
#include <random>
#include <Eigen/Dense>

#include <benchmark/benchmark.h>

#include "support/simplex_domains.h"
#include "volspline/render/xray_image.h"
#include "volspline/simplex/dms_spline_evaluator.h"
#include "volspline/simplex/dms_tetrahedron_basis.h"
#include "volspline/simplex/simplex_spline.h"

namespace volspline {
namespace {

// 8 x 8 x 8 jittered grid points: about 2,370 Delaunay tetrahedra. Shared control vectors (the
// paper's class, evaluated by the DMS step from degree n − 1) unless `per_tetrahedron` (all
// degree-n basis functions).
const DmsSplineVolume& volume(int degree, bool per_tetrahedron = false) {
  static std::map<std::pair<int, bool>, DmsSplineVolume> volumes;
  auto it = volumes.find({degree, per_tetrahedron});
  if (it == volumes.end()) {
    DmsSplineVolume v = test_support::cube_simplex_volume(degree, per_tetrahedron ? DmsControlSharing::PerTetrahedron : DmsControlSharing::Shared, 8);
    for (Eigen::Index r = 0; r < v.control_vectors().rows(); ++r) v.control_vectors()(r, 3) = 1.0 + 0.5 * std::sin(0.37 * static_cast<double>(r));
    it = volumes.emplace(std::pair{degree, per_tetrahedron}, std::move(v)).first;
  }
  return it->second;
}

std::vector<Eigen::Vector3d> random_points(int count) {
  std::mt19937 rng(4);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  std::vector<Eigen::Vector3d> points(static_cast<std::size_t>(count));
  for (auto& p : points) p = Eigen::Vector3d(u(rng), u(rng), u(rng));
  return points;
}

// One point per iteration, the points in turn, value and gradient: the loop every single-point
// evaluation benchmark times.
void evaluate_in_turn(benchmark::State& state, DmsSplineEvaluator& evaluator, const std::vector<Eigen::Vector3d>& points) {
  DmsSplinePoint out;
  std::size_t i = 0;
  for (auto _ : state) {
    evaluator.evaluate(points[i++ % points.size()], 1, out);
    benchmark::DoNotOptimize(out.value.data());
  }
}

void BM_EvaluateMemoised(benchmark::State& state) {
  const DmsSplineVolume& v = volume(static_cast<int>(state.range(0)));
  DmsSplineEvaluator evaluator(v);
  const auto points = random_points(4096);
  evaluate_in_turn(state, evaluator, points);
  state.counters["tetrahedra"] = static_cast<double>(v.domain().tetrahedra.size());
  std::vector<int> candidates;
  double total = 0;
  for (const auto& p : points) {
    evaluator.support_candidates(p, candidates);
    total += static_cast<double>(candidates.size());
  }
  state.counters["candidates_per_point"] = total / static_cast<double>(points.size());
  state.counters["points_per_s"] = benchmark::Counter(static_cast<double>(state.iterations()), benchmark::Counter::kIsRate);
}
BENCHMARK(BM_EvaluateMemoised)->Arg(2)->Arg(3);

// The same spline with its control vectors per tetrahedron (eq. 6 in general): no DMS step, every
// degree-n basis function of every candidate tetrahedron.
void BM_EvaluateMemoisedPerTetrahedron(benchmark::State& state) {
  const DmsSplineVolume& v = volume(static_cast<int>(state.range(0)), true);
  DmsSplineEvaluator evaluator(v);
  const auto points = random_points(4096);
  evaluate_in_turn(state, evaluator, points);
  state.counters["points_per_s"] = benchmark::Counter(static_cast<double>(state.iterations()), benchmark::Counter::kIsRate);
}
BENCHMARK(BM_EvaluateMemoisedPerTetrahedron)->Arg(2)->Arg(3);

// The batch API on scattered points (range(2) per call: the first 4,096 are those of
// BM_EvaluateMemoised), its sort included: shared control vectors (range(1) = 0) and per
// tetrahedron (1).
void BM_EvaluateBatch(benchmark::State& state) {
  const DmsSplineVolume& v = volume(static_cast<int>(state.range(0)), state.range(1) != 0);
  DmsSplineEvaluator evaluator(v);
  const auto points = random_points(static_cast<int>(state.range(2)));
  std::vector<DmsSplinePoint> out;
  for (auto _ : state) {
    evaluator.evaluate(points, 1, out);
    benchmark::DoNotOptimize(out.data());
  }
  state.counters["points_per_s"] =
      benchmark::Counter(static_cast<double>(state.iterations()) * static_cast<double>(points.size()), benchmark::Counter::kIsRate);
}
BENCHMARK(BM_EvaluateBatch)->ArgsProduct({{2, 3}, {0, 1}, {4096, 65536}});

// The same points in the order of the tetrahedra that hold them, as grids, slices and rays visit
// a domain: each tetrahedron's plan is evaluated while it is in the cache.
void BM_EvaluateMemoisedCoherent(benchmark::State& state) {
  const DmsSplineVolume& v = volume(static_cast<int>(state.range(0)));
  DmsSplineEvaluator evaluator(v);
  auto points = random_points(4096);
  std::vector<std::pair<int, Eigen::Vector3d>> located;
  for (const auto& p : points) located.emplace_back(evaluator.locate(p), p);
  std::sort(located.begin(), located.end(), [](const auto& a, const auto& b) { return a.first < b.first; });
  for (std::size_t i = 0; i < points.size(); ++i) points[i] = located[i].second;
  evaluate_in_turn(state, evaluator, points);
  state.counters["points_per_s"] = benchmark::Counter(static_cast<double>(state.iterations()), benchmark::Counter::kIsRate);
}
BENCHMARK(BM_EvaluateMemoisedCoherent)->Arg(2)->Arg(3);

// The baseline: the same candidate tetrahedra, but every basis function's value and its three
// derivatives by the plain recurrence (eq. 1 and eq. 2), nothing shared.
void BM_EvaluatePlainRecurrence(benchmark::State& state) {
  const int degree = static_cast<int>(state.range(0));
  const DmsSplineVolume& v = volume(degree);
  DmsSplineEvaluator evaluator(v);
  const auto points = random_points(4096);
  const auto betas = dms_multi_indices(degree);
  std::vector<int> candidates;
  std::vector<Eigen::Vector3d> knots;
  std::size_t i = 0;
  for (auto _ : state) {
    const Eigen::Vector3d& x = points[i++ % points.size()];
    Eigen::Vector4d value = Eigen::Vector4d::Zero();
    Eigen::Matrix<double, 4, 3> gradient = Eigen::Matrix<double, 4, 3>::Zero();
    evaluator.support_candidates(x, candidates);
    for (const int t : candidates) {
      const auto& tet = v.domain().tetrahedra[static_cast<std::size_t>(t)];
      for (std::size_t b = 0; b < betas.size(); ++b) {
        knots.clear();
        std::array<Eigen::Vector3d, 4> last;
        for (int c = 0; c < 4; ++c) {
          const Eigen::Vector3d* cloud = v.knots().cloud(tet[static_cast<std::size_t>(c)]);
          for (int m = 0; m <= betas[b][static_cast<std::size_t>(c)]; ++m) knots.push_back(cloud[m]);
          last[static_cast<std::size_t>(c)] = cloud[betas[b][static_cast<std::size_t>(c)]];
        }
        Eigen::Matrix3d edges;
        edges << last[1] - last[0], last[2] - last[0], last[3] - last[0];
        const double scale = std::abs(edges.determinant());
        const double n = scale * simplex_spline_value(x, knots);
        Eigen::Vector3d g;
        for (int d = 0; d < 3; ++d) g[d] = scale * simplex_spline_directional_derivative(x, knots, Eigen::Vector3d::Unit(d));
        const auto c = v.control_vectors().row(v.control_row(t, static_cast<int>(b))).head<4>();
        value += n * c.transpose();
        gradient += c.transpose() * g.transpose();
      }
    }
    benchmark::DoNotOptimize(value.data());
    benchmark::DoNotOptimize(gradient.data());
  }
  state.counters["points_per_s"] = benchmark::Counter(static_cast<double>(state.iterations()), benchmark::Counter::kIsRate);
}
BENCHMARK(BM_EvaluatePlainRecurrence)->Arg(2)->Arg(3);

void BM_XrayQuadratic512(benchmark::State& state) {
  const DmsSplineVolume& v = volume(2);
  XrayOptions options;
  options.width = options.height = 512;
  for (auto _ : state) {
    const XrayRenderer renderer(v, options);
    benchmark::DoNotOptimize(renderer.picture().line_integrals.data());
  }
  state.SetLabel("512 x 512, analytic line integrals");
}
BENCHMARK(BM_XrayQuadratic512)->Unit(benchmark::kSecond)->Iterations(1);

// Adaptive Simpson on g along one chord to a relative tolerance.
double adaptive_simpson(const std::function<double(double)>& f, double a, double b, double fa, double fm, double fb, double whole,
                        double tolerance, int depth) {
  const double m = (a + b) / 2, lm = (a + m) / 2, rm = (m + b) / 2;
  const double flm = f(lm), frm = f(rm);
  const double left = (m - a) / 6 * (fa + 4 * flm + fm), right = (b - m) / 6 * (fm + 4 * frm + fb);
  // At least 6 levels: a piecewise polynomial can fool the error estimate of a coarse level.
  if (depth <= 0 || (depth < 34 && std::abs(left + right - whole) <= 15 * tolerance)) return left + right + (left + right - whole) / 15;
  return adaptive_simpson(f, a, m, fa, flm, fm, left, tolerance / 2, depth - 1) +
         adaptive_simpson(f, m, b, fm, frm, fb, right, tolerance / 2, depth - 1);
}

// Ray marching with numerical quadrature, per ray, at 1e-6 relative accuracy, against the
// analytic integrals of the same rays: rays per second of each, and their largest difference.
void BM_XrayRayMarchingBaseline(benchmark::State& state) {
  const DmsSplineVolume& v = volume(2);
  XrayOptions options;
  options.width = options.height = 512;
  const XrayRenderer renderer(v, options);
  DmsSplineEvaluator evaluator(v);
  double worst = 0;
  long long rays = 0;
  int pixel = 0;
  for (auto _ : state) {
    const int x = 128 + (pixel * 37) % 256, y = 128 + (pixel * 91) % 256;
    ++pixel;
    Eigen::Vector3d o, d;
    renderer.pixel_ray(x, y, o, d);
    // The chord through the unit cube.
    double t0 = -1e300, t1 = 1e300;
    for (int a = 0; a < 3; ++a) {
      double u = -o[a] / d[a], w = (1 - o[a]) / d[a];
      if (u > w) std::swap(u, w);
      t0 = std::max(t0, u), t1 = std::min(t1, w);
    }
    if (!(t0 < t1)) continue;
    const auto f = [&](double t) { return evaluator.evaluate(o + t * d).value[3]; };
    const double fa = f(t0), fm = f((t0 + t1) / 2), fb = f(t1);
    const double whole = (t1 - t0) / 6 * (fa + 4 * fm + fb);
    const double value = adaptive_simpson(f, t0, t1, fa, fm, fb, whole, 1e-6 * std::abs(whole), 40);
    const double exact = renderer.picture().line_integrals[static_cast<std::size_t>(y * 512 + x)];
    worst = std::max(worst, std::abs(value - exact) / std::max(std::abs(exact), 1e-300));
    ++rays;
  }
  state.counters["rays_per_s"] = benchmark::Counter(static_cast<double>(rays), benchmark::Counter::kIsRate);
  state.counters["largest_relative_difference"] = worst;
  state.counters["analytic_rays_per_s"] = 512.0 * 512.0 / renderer.picture().seconds;
}
BENCHMARK(BM_XrayRayMarchingBaseline)->Iterations(300);

void BM_XrayIncrementalUpdate(benchmark::State& state) {
  DmsSplineVolume v = volume(2);
  XrayOptions options;
  options.width = options.height = 512;
  XrayRenderer renderer(v, options);
  int row = 0;
  for (auto _ : state) {
    row = (row + 97) % v.control_vector_count();
    v.control_vectors()(row, 3) += 0.1;
    benchmark::DoNotOptimize(renderer.update_coefficient(row, 0.1));
  }
  state.SetLabel("one control coefficient, 512 x 512");
}
BENCHMARK(BM_XrayIncrementalUpdate)->Unit(benchmark::kMillisecond);

}  // namespace
}  // namespace volspline
