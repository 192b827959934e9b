// The 7-direction box spline (issue 6). Scattered evaluation of value + gradient, one thread,
// uniformly random points in the whole domain: LatticeField::evaluate (53 coefficients gathered
// from the lattice, one table of pieces for all tetrahedra by symmetry) against the piecewise
// Bernstein–Bézier form (BezierFormField, the previous fast path, 6720 bytes per knot cube) and
// against assembling from each tetrahedron's own pieces (evaluate_by_own_pieces, the
// straightforward exact method). And the cylinder intersection of Peters & Wittman Fig. 1c
// (control method, two subdivisions). And the n-ary smooth minimum of n nearly tied values
// (issue 16): its cost per value for n = 16 .. 65536 against the monomial form it replaced
// (O(n²), and wrong from n ≈ 60 on, kept here as the baseline only).
#include <benchmark/benchmark.h>

#include <algorithm>
#include <memory>
#include <random>
#include <span>

#include "volspline/boxspline/bezier_form.h"
#include "volspline/boxspline/blend_examples.h"
#include "volspline/boxspline/implicit_scene.h"
#include "volspline/boxspline/lattice_field.h"
#include "volspline/boxspline/zero_set.h"

namespace {

using namespace volspline;

// Fields by benchmark argument:
//  0: h = 0.25 on [-1,1]³, 13³ coefficients (BB form 4.9 MB, cache-sized)
//  1: h = 0.1 on [-1,1]³, 25³ coefficients (BB form 62 MB)
//  2: the Fig. 1c cylinder intersection after two refinements, 48³ coefficients (BB form 572 MB)
//  3: 96³ random coefficients (7 MB; the BB form would be 5.2 GB, beyond BezierFormField::kMaxCubes)
struct Setup {
  LatticeField field;
  std::vector<Eigen::Vector3d> points;
  std::unique_ptr<BezierFormField> form;
  explicit Setup(int which) {
    std::mt19937 rng(1);
    std::uniform_real_distribution<double> u(-1.0, 1.0);
    if (which == 2) {
      field = refine(scene_field(cylinder_intersection_scene()), 2);
    } else {
      const double h = which == 0 ? 0.25 : which == 1 ? 0.1 : 2.0 / 91.0;
      field = lattice_covering(Eigen::Vector3d::Constant(-1.0), Eigen::Vector3d::Constant(1.0), h);
      for (double& c : field.coefficients) c = u(rng);
    }
    const auto [lo, hi] = field.domain();
    std::uniform_real_distribution<double> t(0.0, 1.0);
    for (int i = 0; i < 1 << 20; ++i) {
      Eigen::Vector3d x;
      for (int d = 0; d < 3; ++d) x[d] = lo[d] + t(rng) * (hi[d] - lo[d]);
      points.push_back(x);
    }
    if (which <= 2) form = std::make_unique<BezierFormField>(field);
  }
};

const Setup& setup(int which) {
  static std::unique_ptr<Setup> fields[4];
  if (!fields[which]) fields[which] = std::make_unique<Setup>(which);
  return *fields[which];
}

void label(benchmark::State& state, const Setup& s) {
  state.SetLabel(std::to_string(s.field.size[0]) + "x" + std::to_string(s.field.size[1]) + "x" + std::to_string(s.field.size[2]));
  state.SetItemsProcessed(state.iterations());
}

void BM_ScatteredValueGradient_Lattice(benchmark::State& state) {
  const Setup& s = setup(static_cast<int>(state.range(0)));
  std::size_t i = 0;
  Eigen::Vector3d g;
  for (auto _ : state) {
    benchmark::DoNotOptimize(s.field.evaluate(s.points[i], &g));
    benchmark::DoNotOptimize(g);
    i = (i + 1) & (s.points.size() - 1);
  }
  label(state, s);
}
BENCHMARK(BM_ScatteredValueGradient_Lattice)->Arg(0)->Arg(1)->Arg(2)->Arg(3);

// The same through the narrower code paths (processors without AVX-512 or AVX2).
void ScatteredWithCode(benchmark::State& state, EvaluationCode code) {
  if (!evaluation_code_available(code)) {
    state.SkipWithError("not supported by this processor");
    return;
  }
  const Setup& s = setup(static_cast<int>(state.range(0)));
  std::size_t i = 0;
  Eigen::Vector3d g;
  for (auto _ : state) {
    benchmark::DoNotOptimize(evaluate_with_code(s.field, code, s.points[i], &g));
    benchmark::DoNotOptimize(g);
    i = (i + 1) & (s.points.size() - 1);
  }
  label(state, s);
}
void BM_ScatteredValueGradient_LatticeAvx2(benchmark::State& state) { ScatteredWithCode(state, EvaluationCode::Avx2); }
void BM_ScatteredValueGradient_LatticePortable(benchmark::State& state) { ScatteredWithCode(state, EvaluationCode::Portable); }
BENCHMARK(BM_ScatteredValueGradient_LatticeAvx2)->Arg(1)->Arg(3);
BENCHMARK(BM_ScatteredValueGradient_LatticePortable)->Arg(1)->Arg(3);

void BM_ScatteredValueGradient_BezierFormBaseline(benchmark::State& state) {
  const Setup& s = setup(static_cast<int>(state.range(0)));
  std::size_t i = 0;
  Eigen::Vector3d g;
  for (auto _ : state) {
    benchmark::DoNotOptimize(s.form->evaluate(s.points[i], &g));
    benchmark::DoNotOptimize(g);
    i = (i + 1) & (s.points.size() - 1);
  }
  label(state, s);
}
BENCHMARK(BM_ScatteredValueGradient_BezierFormBaseline)->Arg(0)->Arg(1)->Arg(2);

void BM_ScatteredValueGradient_OwnPiecesBaseline(benchmark::State& state) {
  const Setup& s = setup(static_cast<int>(state.range(0)));
  std::size_t i = 0;
  Eigen::Vector3d g;
  for (auto _ : state) {
    benchmark::DoNotOptimize(evaluate_by_own_pieces(s.field, s.points[i], &g));
    benchmark::DoNotOptimize(g);
    i = (i + 1) & (s.points.size() - 1);
  }
  label(state, s);
}
BENCHMARK(BM_ScatteredValueGradient_OwnPiecesBaseline)->Arg(0)->Arg(3);

void BM_BezierFormConstruction(benchmark::State& state) {
  const Setup& s = setup(1);
  for (auto _ : state) benchmark::DoNotOptimize(BezierFormField(s.field));
}
BENCHMARK(BM_BezierFormConstruction)->Unit(benchmark::kMillisecond);

// Fig. 1c: scene to mesh, control method, two subdivisions.
void BM_Fig1cCylinderIntersection_Control2(benchmark::State& state) {
  const Scene scene = cylinder_intersection_scene();
  std::size_t triangles = 0;
  for (auto _ : state) triangles = scene_zero_set(scene, {.levels = 2, .method = ZeroSetMethod::Control, .statistics = false}).mesh.num_triangles();
  state.counters["triangles"] = static_cast<double>(triangles);
}
BENCHMARK(BM_Fig1cCylinderIntersection_Control2)->Unit(benchmark::kMillisecond);

// Baseline: the same surface from exact spline values (exact method, same grid).
void BM_Fig1cCylinderIntersection_Exact2Baseline(benchmark::State& state) {
  const Scene scene = cylinder_intersection_scene();
  for (auto _ : state) benchmark::DoNotOptimize(scene_zero_set(scene, {.levels = 2, .method = ZeroSetMethod::Exact, .statistics = false}));
}
BENCHMARK(BM_Fig1cCylinderIntersection_Exact2Baseline)->Unit(benchmark::kMillisecond);

// n values within 1e-6 k of each other (a blend of n nearly equal children), k = 0.3.
std::vector<double> nearly_tied_values(std::int64_t n) {
  std::mt19937 rng(3);
  std::uniform_real_distribution<double> u(0.0, 0.3e-6);
  std::vector<double> values(static_cast<std::size_t>(n));
  for (double& v : values) v = 0.25 + u(rng);
  return values;
}

void BM_SmoothMinimum_NearlyTied(benchmark::State& state) {
  const std::vector<double> values = nearly_tied_values(state.range(0));
  for (auto _ : state) benchmark::DoNotOptimize(smooth_minimum(values, 0.3));
  state.SetItemsProcessed(state.iterations() * state.range(0));
}
BENCHMARK(BM_SmoothMinimum_NearlyTied)->RangeMultiplier(4)->Range(16, 65536);

void BM_SmoothMinimum_NearlyTiedWithDerivatives(benchmark::State& state) {
  const std::vector<double> values = nearly_tied_values(state.range(0));
  std::vector<double> derivatives(values.size());
  for (auto _ : state) benchmark::DoNotOptimize(smooth_minimum(values, 0.3, derivatives));
  state.SetItemsProcessed(state.iterations() * state.range(0));
}
BENCHMARK(BM_SmoothMinimum_NearlyTiedWithDerivatives)->RangeMultiplier(4)->Range(16, 65536);

// The monomial form smooth_minimum used before issue 16: the product of the factors c − τ
// expanded in powers of τ, panel by panel, O(m²) (its value is not used: it cancels).
double monomial_smooth_minimum(std::span<const double> values, double k) {
  const double least = *std::min_element(values.begin(), values.end());
  std::vector<double> tau;
  for (double v : values)
    if ((v - least) / k < 1.0) tau.push_back((v - least) / k);
  std::sort(tau.begin(), tau.end());
  std::vector<double> poly{1.0};
  double sum = 0.0;
  for (std::size_t r = 0; r < tau.size(); ++r) {
    std::vector<double> next(poly.size() + 1, 0.0);
    for (std::size_t d = 0; d < poly.size(); ++d) {
      next[d] += (1.0 + tau[r]) * poly[d];
      next[d + 1] -= poly[d];
    }
    poly = std::move(next);
    const double lo = tau[r], hi = r + 1 < tau.size() ? tau[r + 1] : 1.0;
    double plo = 0.0, phi = 0.0;
    for (std::size_t d = poly.size(); d-- > 0;) {
      plo = (plo + poly[d] / static_cast<double>(d + 1)) * lo;
      phi = (phi + poly[d] / static_cast<double>(d + 1)) * hi;
    }
    sum += phi - plo;
  }
  return least - 0.5 * k + k * sum;
}

void BM_SmoothMinimum_NearlyTied_MonomialBaseline(benchmark::State& state) {
  const std::vector<double> values = nearly_tied_values(state.range(0));
  for (auto _ : state) benchmark::DoNotOptimize(monomial_smooth_minimum(values, 0.3));
  state.SetItemsProcessed(state.iterations() * state.range(0));
}
BENCHMARK(BM_SmoothMinimum_NearlyTied_MonomialBaseline)->RangeMultiplier(4)->Range(16, 4096);

}  // namespace
