// Evaluation throughput of a tricubic B-spline volume with 8 x 8 x 8 control points
// (issue: >= 20 M grid points/s with first derivatives, >= 10 M scattered points/s without
// derivatives, >= 3 M with). Each volspline benchmark has a baseline in the same run: the
// textbook point-by-point evaluation (Piegl & Tiller A3.5 extended to volumes: span search,
// Cox-de Boor basis per direction, a triple sum over the 4 x 4 x 4 block, derivatives from
// A2.3 basis derivatives), so the ratio of items_per_second is the figure to quote.
#include <benchmark/benchmark.h>

#include <random>
#include <vector>

#include "volspline/spline/tensor_spline.h"

namespace {

using volspline::BSplineVolume;
using volspline::KnotVector;

BSplineVolume make_volume() {
  const KnotVector kv = KnotVector::uniform_clamped(3, 5);  // 8 control points
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> jitter(-0.1, 0.1);
  std::vector<double> points;
  for (int k = 0; k < 8; ++k)
    for (int j = 0; j < 8; ++j)
      for (int i = 0; i < 8; ++i) {
        points.push_back(i / 7.0 + jitter(rng));
        points.push_back(j / 7.0 + jitter(rng) + 0.2 * (i / 7.0) * (i / 7.0));
        points.push_back(k / 7.0 + jitter(rng));
      }
  return BSplineVolume({kv, kv, kv}, 3, std::move(points));
}

const BSplineVolume& volume() {
  static const BSplineVolume v = make_volume();
  return v;
}

std::vector<std::array<double, 3>> scattered(std::size_t n) {
  std::mt19937 rng(8);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  std::vector<std::array<double, 3>> t(n);
  for (auto& x : t) x = {u(rng), u(rng), u(rng)};
  return t;
}

// The textbook evaluation, written the way most codes do it.
void textbook_evaluate(const BSplineVolume& v, const std::array<double, 3>& t, int order, double* out) {
  const auto& P = v.points();
  const auto n = v.num_control_points();
  double N[3][2][4];
  int span[3];
  for (int d = 0; d < 3; ++d) {
    const KnotVector& kv = v.knot_vector(d);
    span[d] = kv.find_span(t[static_cast<std::size_t>(d)]);
    double ders[2 * 4];
    kv.basis_derivatives(span[d], t[static_cast<std::size_t>(d)], order, ders);
    for (int r = 0; r <= order; ++r)
      for (int j = 0; j < 4; ++j) N[d][r][j] = ders[r * 4 + j];
  }
  const int combos[4][3] = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, 0, 1}};
  for (int a = 0; a < (order ? 4 : 1); ++a) {
    double s[3] = {0, 0, 0};
    for (int k = 0; k < 4; ++k)
      for (int j = 0; j < 4; ++j)
        for (int i = 0; i < 4; ++i) {
          const double b = N[0][combos[a][0]][i] * N[1][combos[a][1]][j] * N[2][combos[a][2]][k];
          const std::size_t idx = static_cast<std::size_t>((span[0] - 3 + i) + n[0] * ((span[1] - 3 + j) + n[1] * (span[2] - 3 + k)));
          for (int c = 0; c < 3; ++c) s[c] += b * P[3 * idx + static_cast<std::size_t>(c)];
        }
    for (int c = 0; c < 3; ++c) out[3 * a + c] = s[c];
  }
}

void BM_Scattered(benchmark::State& state) {
  const int order = static_cast<int>(state.range(0));
  const auto t = scattered(4096);
  std::vector<double> out(12);
  for (auto _ : state) {
    for (const auto& x : t) {
      volume().evaluate_derivatives(x, order, out.data());
      benchmark::DoNotOptimize(out.data());
    }
  }
  state.SetItemsProcessed(state.iterations() * static_cast<int64_t>(t.size()));
}

void BM_ScatteredTextbook(benchmark::State& state) {
  const int order = static_cast<int>(state.range(0));
  const auto t = scattered(4096);
  std::vector<double> out(12);
  for (auto _ : state) {
    for (const auto& x : t) {
      textbook_evaluate(volume(), x, order, out.data());
      benchmark::DoNotOptimize(out.data());
    }
  }
  state.SetItemsProcessed(state.iterations() * static_cast<int64_t>(t.size()));
}

// The same scattered points through the parallel batch interface (all cores).
void BM_ScatteredBatchParallel(benchmark::State& state) {
  const int order = static_cast<int>(state.range(0));
  const auto t = scattered(1 << 16);
  for (auto _ : state) {
    auto out = volume().evaluate_points(t, order);
    benchmark::DoNotOptimize(out.data());
  }
  state.SetItemsProcessed(state.iterations() * static_cast<int64_t>(t.size()));
}

std::array<std::vector<double>, 3> grid(int n) {
  std::array<std::vector<double>, 3> s;
  for (auto& v : s)
    for (int i = 0; i < n; ++i) v.push_back(i / (n - 1.0));
  return s;
}

void BM_Grid(benchmark::State& state) {
  const int order = static_cast<int>(state.range(0));
  const int n = static_cast<int>(state.range(1));
  const auto samples = grid(n);
  std::vector<double> values(static_cast<std::size_t>(n) * n * n * 3 * (order ? 4 : 1));
  for (auto _ : state) {
    volume().evaluate_grid(samples, order, values.data());
    benchmark::DoNotOptimize(values.data());
  }
  state.SetItemsProcessed(state.iterations() * static_cast<int64_t>(n) * n * n);
}

void BM_GridTextbook(benchmark::State& state) {
  const int order = static_cast<int>(state.range(0));
  const int n = static_cast<int>(state.range(1));
  const auto samples = grid(n);
  std::vector<double> out(static_cast<std::size_t>(n) * n * n * 12);
  for (auto _ : state) {
    std::size_t p = 0;
    for (double w : samples[2])
      for (double v : samples[1])
        for (double u : samples[0]) textbook_evaluate(volume(), {u, v, w}, order, &out[12 * p++]);
    benchmark::DoNotOptimize(out.data());
  }
  state.SetItemsProcessed(state.iterations() * static_cast<int64_t>(n) * n * n);
}

}  // namespace

BENCHMARK(BM_Scattered)->ArgName("order")->Arg(0)->Arg(1);
BENCHMARK(BM_ScatteredBatchParallel)->ArgName("order")->Arg(0)->Arg(1)->UseRealTime();
BENCHMARK(BM_ScatteredTextbook)->ArgName("order")->Arg(0)->Arg(1);
BENCHMARK(BM_Grid)->ArgNames({"order", "n"})->Args({0, 64})->Args({1, 64})->Args({1, 128});
BENCHMARK(BM_GridTextbook)->ArgNames({"order", "n"})->Args({0, 64})->Args({1, 64});
