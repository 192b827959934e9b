// Reading and writing a mid-size model in every exchange format: a rational tricubic B-spline
// volume with 20 x 20 x 20 control points (17^3 = 4913 Bezier pieces). The baseline is the
// volspline JSON model file in the same run: the ratio of bytes_per_second (or of times) to
// the JSON figures is what docs/performance.md quotes. Text only: no disk access is timed.
#include <benchmark/benchmark.h>

#include <random>
#include <string>
#include <vector>

#include "volspline/io/model_formats.h"
#include "volspline/spline/tensor_spline.h"

namespace {

using namespace volspline;

Model make_model() {
  constexpr int n = 20;
  const KnotVector kv = KnotVector::uniform_clamped(3, n - 3);
  std::mt19937 rng(11);
  std::uniform_real_distribution<double> jitter(-0.01, 0.01), weight(0.8, 1.25);
  std::vector<double> points, weights;
  for (int k = 0; k < n; ++k)
    for (int j = 0; j < n; ++j)
      for (int i = 0; i < n; ++i) {
        const double u = i / (n - 1.0), v = j / (n - 1.0), w = k / (n - 1.0);
        points.push_back(u + jitter(rng));
        points.push_back(v + 0.2 * u * u + jitter(rng));
        points.push_back(w + 0.1 * u * v + jitter(rng));
        weights.push_back(weight(rng));
      }
  Model model;
  model.objects.push_back({"bench", false, BSplineVolume({kv, kv, kv}, 3, std::move(points), std::move(weights)), nullptr});
  return model;
}

const Model& model() {
  static const Model m = make_model();
  return m;
}

void write_format(benchmark::State& state, const char* name) {
  const ModelFormat& format = model_format_named(name);
  std::size_t bytes = 0;
  for (auto _ : state) {
    std::string text = format.text(model());
    bytes = text.size();
    benchmark::DoNotOptimize(text);
  }
  state.SetBytesProcessed(static_cast<std::int64_t>(state.iterations() * bytes));
  state.counters["file_MB"] = static_cast<double>(bytes) / 1e6;
}

void read_format(benchmark::State& state, const char* name) {
  const ModelFormat& format = model_format_named(name);
  const std::string text = format.text(model());
  for (auto _ : state) {
    Model m = format.parse(text, "bench");
    benchmark::DoNotOptimize(m);
  }
  state.SetBytesProcessed(static_cast<std::int64_t>(state.iterations() * text.size()));
  state.counters["file_MB"] = static_cast<double>(text.size()) / 1e6;
}

}  // namespace

BENCHMARK_CAPTURE(write_format, json_baseline, "json")->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(write_format, gismo_xml, "gismo")->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(write_format, irit_itd, "irit")->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(write_format, vtu, "vtu")->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(read_format, json_baseline, "json")->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(read_format, gismo_xml, "gismo")->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(read_format, irit_itd, "irit")->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(read_format, vtu, "vtu")->Unit(benchmark::kMillisecond);
