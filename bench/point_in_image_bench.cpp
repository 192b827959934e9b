// Membership in the image of a swept solid (analysis/point_in_image.h): queries per second of
// SplineImage<4> on s(u, v, w, t) = g(u, v, w) + t d, for the exact rational ball (a capsule)
// and a box (the hull of two boxes), at four kinds of points: 1e-6 of the size inside and
// outside the analytic boundary (the trimming's queries, the hardest), deep inside and outside
// in the bounding box. Counters: cells tested and Newton runs per query, Undecided answers.
#include <benchmark/benchmark.h>

#include <algorithm>
#include <functional>
#include <random>
#include <vector>

#include "support/swept_solids.h"
#include "volspline/analysis/point_in_image.h"
#include "volspline/construct/primitives.h"

namespace {

using namespace volspline;

using test_support::translated_along;

struct Model {
  SplineImage<4> image;
  // Signed distance to the analytic boundary (negative inside).
  std::function<double(const Eigen::Vector3d&)> signed_distance;
  Eigen::Vector3d centre;
};

const Eigen::Vector3d kOffset(1.2, -0.7, 0.9);

const Model& capsule() {
  static const Model model{SplineImage<4>({translated_along(ball(0.6), kOffset)}),
                           [](const Eigen::Vector3d& x) {
                             const double t = std::clamp(x.dot(kOffset) / kOffset.squaredNorm(), 0.0, 1.0);
                             return (x - t * kOffset).norm() - 0.6;
                           },
                           0.5 * kOffset};
  return model;
}

const Model& box_hull() {
  // Inside iff some t in [0, 1] puts x - t d in the unit cube; the "distance" here is the
  // bisection parameter of the ray only, so the boundary points come from bisection below.
  static const Model model{SplineImage<4>({translated_along(box(Eigen::Vector3d(1, 1, 1), Eigen::Vector3d(0.5, 0.5, 0.5)), kOffset)}),
                           [](const Eigen::Vector3d& x) {
                             double low = 0, high = 1;
                             for (int a = 0; a < 3; ++a) {
                               double t0 = x[a] / kOffset[a], t1 = (x[a] - 1) / kOffset[a];
                               if (t0 > t1) std::swap(t0, t1);
                               low = std::max(low, t0);
                               high = std::min(high, t1);
                             }
                             return low <= high ? -1.0 : 1.0;
                           },
                           Eigen::Vector3d(0.5, 0.5, 0.5) + 0.5 * kOffset};
  return model;
}

enum Kind { NearInside, NearOutside, DeepInside, FarOutside };

std::vector<Eigen::Vector3d> query_points(const Model& m, Kind kind, int count) {
  std::mt19937 rng(7);
  std::normal_distribution<double> normal;
  const double size = m.image.size();
  std::vector<Eigen::Vector3d> points;
  while (static_cast<int>(points.size()) < count) {
    const Eigen::Vector3d d = Eigen::Vector3d(normal(rng), normal(rng), normal(rng)).normalized();
    if (kind == NearInside || kind == NearOutside) {
      double in = 0, out = size;
      for (int k = 0; k < 80; ++k) {
        const double mid = 0.5 * (in + out);
        (m.signed_distance(m.centre + mid * d) <= 0 ? in : out) = mid;
      }
      points.push_back(m.centre + (kind == NearInside ? in - 1e-6 * size : out + 1e-6 * size) * d);
      continue;
    }
    std::uniform_real_distribution<double> unit(0, 1);
    const Eigen::AlignedBox3d& b = m.image.bounding_box();
    const Eigen::Vector3d x = b.min() + (b.max() - b.min()).cwiseProduct(Eigen::Vector3d(unit(rng), unit(rng), unit(rng)));
    const double s = m.signed_distance(x);
    if ((kind == DeepInside && s < -0.05 * size) || (kind == FarOutside && s > 0.05 * size)) points.push_back(x);
  }
  return points;
}

void run(benchmark::State& state, const Model& m) {
  const Kind kind = static_cast<Kind>(state.range(0));
  const std::vector<Eigen::Vector3d> points = query_points(m, kind, 512);
  const ImageMembership expected = (kind == NearInside || kind == DeepInside) ? ImageMembership::Inside : ImageMembership::Outside;
  std::size_t i = 0;
  double cells = 0, newton = 0, undecided = 0, wrong = 0;
  for (auto _ : state) {
    const auto q = m.image.query(points[i++ % points.size()]);
    cells += q.cells_tested;
    newton += q.newton_runs;
    undecided += q.membership == ImageMembership::Undecided;
    wrong += q.membership != ImageMembership::Undecided && q.membership != expected;
    benchmark::DoNotOptimize(q);
  }
  if (wrong > 0) state.SkipWithError("a query disagreed with the analytic answer");
  state.SetItemsProcessed(state.iterations());
  state.counters["cells"] = benchmark::Counter(cells, benchmark::Counter::kAvgIterations);
  state.counters["newton"] = benchmark::Counter(newton, benchmark::Counter::kAvgIterations);
  state.counters["undecided"] = benchmark::Counter(undecided, benchmark::Counter::kAvgIterations);
}

void BM_CapsuleQueries(benchmark::State& state) { run(state, capsule()); }
void BM_BoxHullQueries(benchmark::State& state) { run(state, box_hull()); }
// Arguments: 0 near inside, 1 near outside (1e-6 of the size), 2 deep inside, 3 outside.
BENCHMARK(BM_CapsuleQueries)->DenseRange(0, 3)->Unit(benchmark::kMicrosecond);
BENCHMARK(BM_BoxHullQueries)->DenseRange(0, 3)->Unit(benchmark::kMicrosecond);

void BM_CapsuleConstruction(benchmark::State& state) {
  const BSplineHypervolume sweep = translated_along(ball(0.6), kOffset);
  for (auto _ : state) {
    SplineImage<4> image({sweep});
    benchmark::DoNotOptimize(image);
  }
}
BENCHMARK(BM_CapsuleConstruction)->Unit(benchmark::kMillisecond);

}  // namespace
