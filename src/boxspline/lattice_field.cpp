#include "volspline/boxspline/lattice_field.h"

#include <cmath>
#include <cstdint>
#include <cstring>
#include <limits>
#include <string>

#include "quartic_tables.h"
#include "volspline/boxspline/seven_direction_box_spline.h"
#include "volspline/core/error.h"

namespace volspline {

namespace {

// M_c(x) = M(x + kShift): the centre of M's support.
const Eigen::Vector3d kShift(0.5, 0.5, 2.5);

void check_size(const std::array<int, 3>& size) {
  std::size_t total = 1;
  for (int d = 0; d < 3; ++d) {
    if (size[d] < 5)
      throw InvalidInput("expected at least 5 lattice points per axis (a field needs 2 beyond its domain on each side), got " +
                         std::to_string(size[d]));
    total *= static_cast<std::size_t>(size[d]);
    if (total > kMaxLatticePoints)
      throw InvalidInput("expected at most " + std::to_string(kMaxLatticePoints) + " lattice points, got " +
                         std::to_string(size[0]) + " x " + std::to_string(size[1]) + " x " + std::to_string(size[2]) +
                         " (use a larger spacing, a smaller box or fewer levels)");
  }
}

}  // namespace

LatticeField::LatticeField(const Eigen::Vector3d& o, double h, std::array<int, 3> n) : origin(o), spacing(h), size(n) {
  if (!(h > 0.0) || !std::isfinite(h)) throw InvalidInput("expected a positive, finite lattice spacing, got " + std::to_string(h));
  if (!o.allFinite()) throw InvalidInput("expected a finite lattice origin");
  check_size(n);
  coefficients.assign(static_cast<std::size_t>(n[0]) * n[1] * n[2], 0.0);
}

std::pair<Eigen::Vector3d, Eigen::Vector3d> LatticeField::domain() const {
  return {origin + spacing * Eigen::Vector3d::Constant(1.5),
          origin + spacing * Eigen::Vector3d(size[0] - 2.5, size[1] - 2.5, size[2] - 2.5)};
}

bool LatticeField::in_domain(const Eigen::Vector3d& x) const {
  const auto [lo, hi] = domain();
  return (x.array() >= lo.array()).all() && (x.array() <= hi.array()).all();
}

namespace {

/// The canonical pieces (SevenDirectionBoxSpline::canonical_offsets, canonical_bb) laid out for
/// the product in evaluate_in_field: rows padded to 40 columns (5 blocks of 8 lanes). For each
/// tetrahedron t, the signed permutation taking tetrahedron 0 to it: (S r)[axis[a]] = sign[a] r[a].
struct CanonicalTable {
  static constexpr int kMaxRows = 56;
  static constexpr int kColumns = 40;
  int rows = 0;
  std::array<int, 3> offset[kMaxRows] = {};
  alignas(64) double bb[kMaxRows * kColumns] = {};
  int axis[kCubeTetrahedra][3] = {};
  double sign[kCubeTetrahedra][3] = {};
};

const CanonicalTable& canonical_table() {
  static const CanonicalTable table = [] {
    const SevenDirectionBoxSpline& m = seven_direction_box_spline();
    CanonicalTable t;
    t.rows = static_cast<int>(m.canonical_offsets.size());
    if (t.rows > CanonicalTable::kMaxRows) throw Error("internal: more canonical box-spline pieces than expected");
    for (std::size_t p = 0; p < m.canonical_offsets.size(); ++p) {
      t.offset[p] = m.canonical_offsets[p];
      for (std::size_t k = 0; k < static_cast<std::size_t>(kQuarticCoefficients); ++k)
        t.bb[p * CanonicalTable::kColumns + k] = m.canonical_bb[p][k];
    }
    for (int tet = 0; tet < kCubeTetrahedra; ++tet) {
      // Tetrahedron 0 lies on the negative sides of its face axis (x) and edge axis (y).
      const quartic::Axes axes = quartic::tetrahedron_axes(tet);
      const int axis[3] = {axes.i, axes.j, axes.k};
      const double sign[3] = {-axes.si, -axes.sj, 1.0};
      for (int a = 0; a < 3; ++a) t.axis[tet][a] = axis[a], t.sign[tet][a] = sign[a];
    }
    return t;
  }();
  return table;
}

/// Per thread: the offsets Σ_a (S_t r)[a] stride_a of the canonical pieces for every
/// tetrahedron t, for the lattice dimensions last seen (they depend on size[0] and size[1] only).
struct GatherOffsets {
  int key[2];
  std::int32_t offset[kCubeTetrahedra][CanonicalTable::kMaxRows];
};
thread_local GatherOffsets gather_offsets{{0, 0}, {}};

const std::int32_t* offsets_for(const CanonicalTable& table, const std::array<int, 3>& size, int tetrahedron) {
  GatherOffsets& cache = gather_offsets;
  if (cache.key[0] != size[0] || cache.key[1] != size[1]) {
    const std::int64_t stride[3] = {1, size[0], static_cast<std::int64_t>(size[0]) * size[1]};
    for (int t = 0; t < kCubeTetrahedra; ++t)
      for (int p = 0; p < CanonicalTable::kMaxRows; ++p) {
        std::int64_t o = 0;
        for (int a = 0; a < 3; ++a)
          o += static_cast<std::int64_t>(table.sign[t][a]) * table.offset[p][static_cast<std::size_t>(a)] * stride[table.axis[t][a]];
        cache.offset[t][p] = static_cast<std::int32_t>(o);
      }
    cache.key[0] = size[0], cache.key[1] = size[1];
  }
  return cache.offset[tetrahedron];
}

/// LatticeField::evaluate. The knot cube of the centred field around lattice point m is
/// m + [-1/2, 1/2]³. A point d of it lies in tetrahedron t = S_t (tetrahedron 0) with the
/// barycentric coordinates of S_t⁻¹ d in tetrahedron 0, and M_c is S_t-invariant, so
///   f = Σ_r c_{m + S_t r} p_r(b),
/// p_r the canonical pieces: one 53 x 35 table serves all 24 tetrahedra (L1-resident), the 53
/// coefficients come from m + [-2, 2]³ (25 short runs of the lattice array), and the BB form is
/// one dense product followed by de Casteljau.
///
/// The product is written for kWidth-lane vectors: columns in chunks of kChunk vectors, rows
/// interleaved over kSets independent sums (shorter chains of dependent additions); the
/// instantiations below fit each instruction set's registers.
/// GCC vectors of 2, 4 or 8 doubles.
template <int kWidth>
struct LanesOf;
template <>
struct LanesOf<2> {
  typedef double type __attribute__((vector_size(16)));
};
template <>
struct LanesOf<4> {
  typedef double type __attribute__((vector_size(32)));
};
template <>
struct LanesOf<8> {
  typedef double type __attribute__((vector_size(64)));
};

template <int kWidth, int kChunk, int kSets>
[[gnu::always_inline]] inline double evaluate_in_field(const LatticeField& field, const Eigen::Vector3d& x, Eigen::Vector3d* gradient,
                                                       Eigen::Matrix3d* hessian) {
  using Lanes = typename LanesOf<kWidth>::type;
  constexpr int kBlocks = CanonicalTable::kColumns / kWidth;
  static_assert(kBlocks % kChunk == 0 && CanonicalTable::kMaxRows % kSets == 0);
  const CanonicalTable& table = canonical_table();
  const double slack = 1e-9;
  // u: lattice units; the domain is u ∈ [1.5, n − 2.5] per axis.
  double u[3];
  bool inside = true;
  for (int d = 0; d < 3; ++d) {
    u[d] = (x[d] - field.origin[d]) / field.spacing;
    inside = inside && u[d] >= 1.5 - slack && u[d] <= field.size[d] - 2.5 + slack;
  }
  if (!inside) throw InvalidInput("the point lies outside the domain of the box-spline field");
  int m[3];
  double local[3];
  for (int d = 0; d < 3; ++d) {
    m[d] = std::min(std::max(static_cast<int>(std::floor(u[d] + 0.5)), 2), field.size[d] - 3);
    local[d] = u[d] - m[d];
  }
  const quartic::CanonicalLocation at = quartic::locate_canonical(local[0], local[1], local[2]);
  const std::int32_t* offset = offsets_for(table, field.size, at.tetrahedron);
  const double* base = field.coefficients.data() + field.index(m[0], m[1], m[2]);
  double c[CanonicalTable::kMaxRows];
  for (int p = 0; p < CanonicalTable::kMaxRows; ++p) c[p] = base[offset[p]];
  alignas(64) double bb[CanonicalTable::kColumns];
  for (int k0 = 0; k0 < kBlocks; k0 += kChunk) {
    Lanes sum[kSets][kChunk] = {};
    for (int p = 0; p < CanonicalTable::kMaxRows; p += kSets)
      for (int s = 0; s < kSets; ++s) {
        const double cp = c[p + s];
        const Lanes* row = reinterpret_cast<const Lanes*>(table.bb + (p + s) * CanonicalTable::kColumns) + k0;
        for (int k = 0; k < kChunk; ++k) sum[s][k] += cp * row[k];
      }
    for (int k = 0; k < kChunk; ++k) {
      Lanes total = sum[0][k];
      for (int s = 1; s < kSets; ++s) total += sum[s][k];
      std::memcpy(bb + (k0 + k) * kWidth, &total, sizeof(total));
    }
  }
  Eigen::Vector3d g0;
  Eigen::Matrix3d h0;
  const double value = quartic::evaluate(bb, 0, at.barycentric, gradient != nullptr ? &g0 : nullptr, hessian != nullptr ? &h0 : nullptr);
  // Back from tetrahedron 0: f(d) = g(P d) with (P d)[a] = sign[a] d[axis[a]].
  const int* axis = table.axis[at.tetrahedron];
  const double* sign = table.sign[at.tetrahedron];
  const double inverse = 1.0 / field.spacing;
  if (gradient != nullptr)
    for (int a = 0; a < 3; ++a) (*gradient)[axis[a]] = sign[a] * g0[a] * inverse;
  if (hessian != nullptr)
    for (int a = 0; a < 3; ++a)
      for (int b = 0; b < 3; ++b) (*hessian)(axis[a], axis[b]) = sign[a] * sign[b] * h0(a, b) * inverse * inverse;
  return value;
}

using FieldEvaluator = double (*)(const LatticeField&, const Eigen::Vector3d&, Eigen::Vector3d*, Eigen::Matrix3d*);

[[gnu::flatten]] double evaluate_portable(const LatticeField& f, const Eigen::Vector3d& x, Eigen::Vector3d* g, Eigen::Matrix3d* h) {
  return evaluate_in_field<2, 5, 2>(f, x, g, h);
}

#if defined(__GNUC__) && !defined(__clang__) && defined(__x86_64__)
#define VOLSPLINE_HAVE_X86_CODE 1
// Instruction-set specific code (GCC, x86-64), chosen at run time. The AVX2 and AVX-512 code
// contracts to fused multiply-adds, so it may differ from the portable code in the last bits.
[[gnu::target("arch=x86-64-v3"), gnu::flatten]] double evaluate_avx2(const LatticeField& f, const Eigen::Vector3d& x, Eigen::Vector3d* g,
                                                                        Eigen::Matrix3d* h) {
  return evaluate_in_field<4, 5, 2>(f, x, g, h);
}
[[gnu::target("arch=x86-64-v4"), gnu::flatten]] double evaluate_avx512(const LatticeField& f, const Eigen::Vector3d& x, Eigen::Vector3d* g,
                                                                          Eigen::Matrix3d* h) {
  return evaluate_in_field<8, 5, 4>(f, x, g, h);
}
#endif

bool supports(EvaluationCode code) {
#ifdef VOLSPLINE_HAVE_X86_CODE
  __builtin_cpu_init();
  switch (code) {
    case EvaluationCode::Avx512:
      return __builtin_cpu_supports("avx512f") && __builtin_cpu_supports("avx512vl") && __builtin_cpu_supports("avx512bw") &&
             __builtin_cpu_supports("avx512dq") && supports(EvaluationCode::Avx2);
    case EvaluationCode::Avx2:
      return __builtin_cpu_supports("avx2") && __builtin_cpu_supports("fma") && __builtin_cpu_supports("bmi2");
    default:
      return true;
  }
#else
  return code == EvaluationCode::Best || code == EvaluationCode::Portable;
#endif
}

FieldEvaluator evaluator_for(EvaluationCode code) {
  switch (code) {
    case EvaluationCode::Best:
      return supports(EvaluationCode::Avx512) ? evaluator_for(EvaluationCode::Avx512)
             : supports(EvaluationCode::Avx2) ? evaluator_for(EvaluationCode::Avx2)
                                              : evaluate_portable;
#ifdef VOLSPLINE_HAVE_X86_CODE
    case EvaluationCode::Avx512:
      return evaluate_avx512;
    case EvaluationCode::Avx2:
      return evaluate_avx2;
#endif
    default:
      return evaluate_portable;
  }
}

}  // namespace

bool evaluation_code_available(EvaluationCode code) { return supports(code); }

double evaluate_with_code(const LatticeField& field, EvaluationCode code, const Eigen::Vector3d& x, Eigen::Vector3d* gradient,
                          Eigen::Matrix3d* hessian) {
  if (!supports(code)) throw InvalidInput("this processor cannot run the requested evaluation code");
  return evaluator_for(code)(field, x, gradient, hessian);
}

double LatticeField::evaluate(const Eigen::Vector3d& x, Eigen::Vector3d* gradient, Eigen::Matrix3d* hessian) const {
  static const FieldEvaluator best = evaluator_for(EvaluationCode::Best);
  return best(*this, x, gradient, hessian);
}

double evaluate_by_own_pieces(const LatticeField& field, const Eigen::Vector3d& x, Eigen::Vector3d* gradient,
                              Eigen::Matrix3d* hessian) {
  if (!x.allFinite() || !field.in_domain(x)) throw InvalidInput("the point lies outside the domain of the box-spline field");
  const Eigen::Vector3d u = (x - field.origin) / field.spacing + kShift;
  // Knot cubes whose every piece has its coefficients (see domain()).
  const int q_lo[3] = {2, 2, 4};
  const int q_hi[3] = {field.size[0] - 3, field.size[1] - 3, field.size[2] - 1};
  int q[3];
  Eigen::Vector3d local;
  for (int d = 0; d < 3; ++d) {
    q[d] = std::min(std::max(static_cast<int>(std::floor(u[d])), q_lo[d]), q_hi[d]);
    local[d] = u[d] - q[d];
  }
  const CubeLocation loc = quartic::locate(local.x(), local.y(), local.z());
  const SevenDirectionBoxSpline& m = seven_direction_box_spline();
  double bb[kQuarticCoefficients] = {};
  for (const int p : m.pieces_on_tetrahedron[loc.tetrahedron]) {
    const auto& piece = m.pieces[static_cast<std::size_t>(p)];
    const double c = field.at(q[0] - piece.cube[0], q[1] - piece.cube[1], q[2] - piece.cube[2]);
    for (int k = 0; k < kQuarticCoefficients; ++k) bb[k] += c * piece.bb[k];
  }
  const double value = quartic::evaluate(bb, loc.tetrahedron, loc.barycentric.data(), gradient, hessian);
  if (gradient != nullptr) *gradient /= field.spacing;
  if (hessian != nullptr) *hessian /= field.spacing * field.spacing;
  return value;
}

LatticeField refine(const LatticeField& field) {
  const auto& n = field.size;
  std::array<int, 3> fine_size{2 * n[0] - 4, 2 * n[1] - 4, 2 * n[2] - 4};
  check_size(fine_size);
  // Uncentred fine indices 0 .. 2n-1: each coefficient copied to its 8 children, i.e. the
  // factors (1 + z^e_i) of the mask applied to the upsampled lattice.
  const std::array<int, 3> w_size{2 * n[0], 2 * n[1], 2 * n[2]};
  const auto w_index = [&](int i, int j, int k) {
    return static_cast<std::size_t>(i) + w_size[0] * (static_cast<std::size_t>(j) + w_size[1] * static_cast<std::size_t>(k));
  };
  std::vector<double> w(static_cast<std::size_t>(w_size[0]) * w_size[1] * w_size[2]);
  for (int k = 0; k < w_size[2]; ++k)
    for (int j = 0; j < w_size[1]; ++j)
      for (int i = 0; i < w_size[0]; ++i) w[w_index(i, j, k)] = field.at(i / 2, j / 2, k / 2);
  // The four diagonal factors (1 + z^ξ)/2, one after the other (§7). Every ξ has ξ_z = +1, so
  // sweeping z downwards reads only entries not yet averaged in this pass. Entries whose
  // partner lies outside stay wrong and are cropped below.
  for (int dir = 3; dir < 7; ++dir) {
    const auto& xi = kBoxSplineDirections[static_cast<std::size_t>(dir)];
    for (int k = w_size[2] - 1; k >= 1; --k)
      for (int j = 0; j < w_size[1]; ++j) {
        const int j0 = j - xi[1];
        if (j0 < 0 || j0 >= w_size[1]) continue;
        const int i_lo = std::max(0, xi[0]), i_hi = std::min(w_size[0], w_size[0] + xi[0]);
        const std::size_t row = w_index(0, j, k), from = w_index(0, j0, k - 1);
        for (int i = i_lo; i < i_hi; ++i) w[row + i] = 0.5 * (w[row + i] + w[from + i - xi[0]]);
      }
  }
  // Centred fine index l = uncentred − (0, 0, 2); keep l ∈ [2, 2n − 3], which are exactly the
  // coefficients whose whole stencil lies on the coarse lattice.
  LatticeField fine(field.origin + 0.75 * field.spacing * Eigen::Vector3d::Ones(), 0.5 * field.spacing, fine_size);
  for (int k = 0; k < fine_size[2]; ++k)
    for (int j = 0; j < fine_size[1]; ++j) {
      const double* src = &w[w_index(2, j + 2, k + 4)];
      double* dst = &fine.at(0, j, k);
      for (int i = 0; i < fine_size[0]; ++i) dst[i] = src[i];
    }
  return fine;
}

LatticeField refine(const LatticeField& field, int levels) {
  if (levels < 0) throw InvalidInput("expected a number of refinement levels >= 0, got " + std::to_string(levels));
  LatticeField out = field;
  for (int l = 0; l < levels; ++l) out = refine(out);
  return out;
}

std::vector<std::pair<std::array<int, 3>, double>> point_value_stencil(const Eigen::Vector3d& offset) {
  std::array<int, 3> half{};
  for (int d = 0; d < 3; ++d) {
    const double twice = 2.0 * offset[d];
    if (!(twice == 0.0 || twice == 1.0))
      throw InvalidInput("expected an offset with coordinates 0 or 1/2 (lattice point, face or cube centre)");
    half[d] = static_cast<int>(twice);
  }
  const SevenDirectionBoxSpline& m = seven_direction_box_spline();
  std::vector<std::pair<std::array<int, 3>, double>> stencil;
  for (int z = -3; z <= 3; ++z)
    for (int y = -3; y <= 3; ++y)
      for (int x = -3; x <= 3; ++x) {
        // 8 (m + offset + shift), shift = (1/2, 1/2, 5/2).
        const std::array<int, 3> e{8 * x + 4 * half[0] + 4, 8 * y + 4 * half[1] + 4, 8 * z + 4 * half[2] + 20};
        const double w = m.value_at_eighths(e);
        if (w != 0.0) stencil.push_back({{x, y, z}, w});
      }
  return stencil;
}

std::vector<double> point_values(const LatticeField& field, const Eigen::Vector3d& offset) {
  const auto stencil = point_value_stencil(offset);
  std::vector<double> out(field.coefficients.size(), std::numeric_limits<double>::quiet_NaN());
  const auto& n = field.size;
  int lo[3], hi[3];
  for (int d = 0; d < 3; ++d) {
    lo[d] = static_cast<int>(std::ceil(1.5 - offset[d]));
    hi[d] = static_cast<int>(std::floor(n[d] - 2.5 - offset[d]));
  }
  for (int k = lo[2]; k <= hi[2]; ++k)
    for (int j = lo[1]; j <= hi[1]; ++j)
      for (int i = lo[0]; i <= hi[0]; ++i) {
        double sum = 0.0;
        for (const auto& [m, w] : stencil) sum += w * field.at(i - m[0], j - m[1], k - m[2]);
        out[field.index(i, j, k)] = sum;
      }
  return out;
}

void quasi_interpolate(LatticeField& field, const std::function<double(const Eigen::Vector3d&)>& function) {
  const auto& n = field.size;
  const int s[3] = {n[0] + 2, n[1] + 2, n[2] + 2};
  const auto sample_index = [&](int i, int j, int k) {
    return static_cast<std::size_t>(i + 1) + s[0] * (static_cast<std::size_t>(j + 1) + s[1] * static_cast<std::size_t>(k + 1));
  };
  std::vector<double> p(static_cast<std::size_t>(s[0]) * s[1] * s[2]);
  for (int k = -1; k <= n[2]; ++k)
    for (int j = -1; j <= n[1]; ++j)
      for (int i = -1; i <= n[0]; ++i) p[sample_index(i, j, k)] = function(field.lattice_point(i, j, k));
  for (int k = 0; k < n[2]; ++k)
    for (int j = 0; j < n[1]; ++j)
      for (int i = 0; i < n[0]; ++i) {
        const double centre = p[sample_index(i, j, k)];
        const double laplacian = p[sample_index(i + 1, j, k)] + p[sample_index(i - 1, j, k)] + p[sample_index(i, j + 1, k)] +
                                 p[sample_index(i, j - 1, k)] + p[sample_index(i, j, k + 1)] + p[sample_index(i, j, k - 1)] -
                                 6.0 * centre;
        field.at(i, j, k) = centre - 5.0 / 24.0 * laplacian;
      }
}

LatticeField lattice_covering(const Eigen::Vector3d& lo, const Eigen::Vector3d& hi, double spacing) {
  if (!(spacing > 0.0) || !std::isfinite(spacing))
    throw InvalidInput("expected a positive, finite spacing, got " + std::to_string(spacing));
  if (!lo.allFinite() || !hi.allFinite() || !((hi.array() > lo.array()).all()))
    throw InvalidInput("expected a box with min < max in every coordinate");
  std::array<int, 3> size{};
  for (int d = 0; d < 3; ++d) {
    const double cells = std::ceil((hi[d] - lo[d]) / spacing - 1e-9);
    if (!(cells + 5.0 <= static_cast<double>(kMaxLatticePoints)))
      throw InvalidInput("expected at most " + std::to_string(kMaxLatticePoints) +
                         " lattice points, the box is too large for the spacing");
    size[d] = static_cast<int>(cells) + 5;
  }
  return LatticeField(lo - 2.0 * spacing * Eigen::Vector3d::Ones(), spacing, size);
}

}  // namespace volspline
