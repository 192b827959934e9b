#include "volspline/boxspline/seven_direction_box_spline.h"

#include <Eigen/Dense>

#include <algorithm>
#include <cmath>

#include "quartic_tables.h"

namespace volspline {

namespace {

/// A dense array over an integer box lo .. lo + size - 1, x fastest.
struct IntegerGrid {
  std::array<int, 3> lo{};
  std::array<int, 3> size{};
  std::vector<double> data;

  IntegerGrid(std::array<int, 3> low, std::array<int, 3> high) : lo(low) {
    for (int d = 0; d < 3; ++d) size[d] = high[d] - low[d] + 1;
    data.assign(static_cast<std::size_t>(size[0]) * size[1] * size[2], 0.0);
  }
  bool contains(int x, int y, int z) const {
    return x >= lo[0] && y >= lo[1] && z >= lo[2] && x < lo[0] + size[0] && y < lo[1] + size[1] && z < lo[2] + size[2];
  }
  std::size_t index(int x, int y, int z) const {
    return static_cast<std::size_t>(x - lo[0]) + size[0] * (static_cast<std::size_t>(y - lo[1]) + size[1] * static_cast<std::size_t>(z - lo[2]));
  }
  double at(int x, int y, int z) const { return contains(x, y, z) ? data[index(x, y, z)] : 0.0; }
  double& ref(int x, int y, int z) { return data[index(x, y, z)]; }
};

// M's support box in its own coordinates, and the mask's.
constexpr std::array<int, 3> kLow{-2, -2, 0};
constexpr std::array<int, 3> kHigh{3, 3, 5};

IntegerGrid refinement_mask() {
  IntegerGrid mask(kLow, kHigh);
  mask.ref(0, 0, 0) = 1.0;
  // ∏_ξ (1 + z^ξ): each factor adds a copy shifted by ξ. Every partial product stays in the box.
  for (const auto& xi : kBoxSplineDirections) {
    IntegerGrid next = mask;
    for (int z = kLow[2]; z <= kHigh[2]; ++z)
      for (int y = kLow[1]; y <= kHigh[1]; ++y)
        for (int x = kLow[0]; x <= kHigh[0]; ++x) next.ref(x, y, z) += mask.at(x - xi[0], y - xi[1], z - xi[2]);
    mask = std::move(next);
  }
  for (double& a : mask.data) a /= 16.0;
  return mask;
}

/// M at the integers: the solution of v(i) = Σ_l a(2i − l) v(l) with Σ v = 1 (the refinement
/// equation restricted to Z³; its eigenvalue 1 is simple).
IntegerGrid integer_values(const IntegerGrid& mask) {
  IntegerGrid v(kLow, kHigh);
  const int n = static_cast<int>(v.data.size());
  Eigen::MatrixXd system = Eigen::MatrixXd::Zero(n + 1, n);
  Eigen::VectorXd rhs = Eigen::VectorXd::Zero(n + 1);
  for (int z = kLow[2]; z <= kHigh[2]; ++z)
    for (int y = kLow[1]; y <= kHigh[1]; ++y)
      for (int x = kLow[0]; x <= kHigh[0]; ++x) {
        const int row = static_cast<int>(v.index(x, y, z));
        system(row, row) -= 1.0;
        for (int lz = kLow[2]; lz <= kHigh[2]; ++lz)
          for (int ly = kLow[1]; ly <= kHigh[1]; ++ly)
            for (int lx = kLow[0]; lx <= kHigh[0]; ++lx)
              system(row, static_cast<int>(v.index(lx, ly, lz))) += mask.at(2 * x - lx, 2 * y - ly, 2 * z - lz);
      }
  system.row(n).setOnes();
  rhs(n) = 1.0;
  const Eigen::VectorXd solution = system.colPivHouseholderQr().solve(rhs);
  for (int i = 0; i < n; ++i) v.data[static_cast<std::size_t>(i)] = std::abs(solution(i)) < 1e-13 ? 0.0 : solution(i);
  return v;
}

/// Coefficients on the lattice 2Z³ ... after one refinement of uncentred coefficients:
/// d_l = Σ_j c_j a_{l − 2j}.
IntegerGrid refine_uncentred(const IntegerGrid& c, const IntegerGrid& mask) {
  std::array<int, 3> lo{}, hi{};
  for (int d = 0; d < 3; ++d) {
    lo[d] = 2 * c.lo[d] + kLow[d];
    hi[d] = 2 * (c.lo[d] + c.size[d] - 1) + kHigh[d];
  }
  IntegerGrid fine(lo, hi);
  for (int z = c.lo[2]; z < c.lo[2] + c.size[2]; ++z)
    for (int y = c.lo[1]; y < c.lo[1] + c.size[1]; ++y)
      for (int x = c.lo[0]; x < c.lo[0] + c.size[0]; ++x) {
        const double cj = c.at(x, y, z);
        if (cj == 0.0) continue;
        for (int kz = kLow[2]; kz <= kHigh[2]; ++kz)
          for (int ky = kLow[1]; ky <= kHigh[1]; ++ky)
            for (int kx = kLow[0]; kx <= kHigh[0]; ++kx)
              fine.ref(2 * x + kx, 2 * y + ky, 2 * z + kz) += cj * mask.at(kx, ky, kz);
      }
  return fine;
}

double bernstein(const std::array<int, 4>& beta, const std::array<double, 4>& b) {
  static constexpr double kFactorial[5] = {1, 1, 2, 6, 24};
  double value = 24.0;
  for (int i = 0; i < 4; ++i) value *= std::pow(b[i], beta[i]) / kFactorial[beta[i]];
  return value;
}

}  // namespace

const std::array<std::array<int, 4>, kQuarticCoefficients>& quartic_multi_indices() {
  static const auto indices = [] {
    std::array<std::array<int, 4>, kQuarticCoefficients> out{};
    for (int i = 0; i < kQuarticCoefficients; ++i)
      for (int k = 0; k < 4; ++k) out[i][k] = quartic::kIndices4[i][k];
    return out;
  }();
  return indices;
}

CubeLocation locate_in_cube(const Eigen::Vector3d& local) { return quartic::locate(local.x(), local.y(), local.z()); }

std::array<Eigen::Vector3d, 4> cube_tetrahedron_vertices(int t) {
  const auto axes = quartic::tetrahedron_axes(t);
  Eigen::Vector3d c(0.5, 0.5, 0.5);
  Eigen::Vector3d f = c;
  f[axes.i] += 0.5 * axes.si;
  Eigen::Vector3d a = f, b = f;
  a[axes.j] += 0.5 * axes.sj;
  b[axes.j] += 0.5 * axes.sj;
  a[axes.k] -= 0.5;
  b[axes.k] += 0.5;
  return {c, f, a, b};
}

std::array<Eigen::Vector3d, 4> cube_tetrahedron_barycentric_gradients(int t) {
  const auto axes = quartic::tetrahedron_axes(t);
  std::array<Eigen::Vector3d, 4> g{Eigen::Vector3d::Zero(), Eigen::Vector3d::Zero(), Eigen::Vector3d::Zero(),
                                   Eigen::Vector3d::Zero()};
  g[0][axes.i] = -2.0 * axes.si;
  g[1][axes.i] = 2.0 * axes.si;
  g[1][axes.j] = -2.0 * axes.sj;
  g[2][axes.j] = axes.sj;
  g[2][axes.k] = -1.0;
  g[3][axes.j] = axes.sj;
  g[3][axes.k] = 1.0;
  return g;
}

double evaluate_cube_quartic(const double* bb, int t, const std::array<double, 4>& b, Eigen::Vector3d* gradient,
                             Eigen::Matrix3d* hessian) {
  return quartic::evaluate(bb, t, b.data(), gradient, hessian);
}

double SevenDirectionBoxSpline::value_at_eighths(const std::array<int, 3>& e) const {
  for (int d = 0; d < 3; ++d)
    if (e[d] < 8 * kLow[d] || e[d] > 8 * kHigh[d]) return 0.0;
  const std::size_t n = 8 * 5 + 1;
  return eighths[static_cast<std::size_t>(e[0] - 8 * kLow[0]) +
                 n * (static_cast<std::size_t>(e[1] - 8 * kLow[1]) + n * static_cast<std::size_t>(e[2] - 8 * kLow[2]))];
}

double SevenDirectionBoxSpline::value(const Eigen::Vector3d& x) const {
  const Eigen::Vector3d cube = x.array().floor();
  for (int d = 0; d < 3; ++d)
    if (!(cube[d] >= kLow[d] && cube[d] < kHigh[d])) return 0.0;
  const CubeLocation at = locate_in_cube(x - cube);
  for (const Piece& p : pieces)
    if (p.tetrahedron == at.tetrahedron && p.cube[0] == cube[0] && p.cube[1] == cube[1] && p.cube[2] == cube[2])
      return evaluate_cube_quartic(p.bb.data(), p.tetrahedron, at.barycentric, nullptr, nullptr);
  return 0.0;
}

const SevenDirectionBoxSpline& seven_direction_box_spline() {
  static const SevenDirectionBoxSpline tables = [] {
    SevenDirectionBoxSpline s;
    const IntegerGrid mask = refinement_mask();
    s.mask = mask.data;
    const IntegerGrid at_integers = integer_values(mask);

    // M(x) = Σ_l d_l M(8x − l) after three refinements of the single coefficient δ_0, so
    // M(p/8) = Σ_l d_l M(p − l).
    IntegerGrid delta({0, 0, 0}, {0, 0, 0});
    delta.ref(0, 0, 0) = 1.0;
    const IntegerGrid d = refine_uncentred(refine_uncentred(refine_uncentred(delta, mask), mask), mask);
    const int n = 8 * 5 + 1;
    s.eighths.assign(static_cast<std::size_t>(n) * n * n, 0.0);
    for (int pz = 0; pz < n; ++pz)
      for (int py = 0; py < n; ++py)
        for (int px = 0; px < n; ++px) {
          const int p[3] = {px + 8 * kLow[0], py + 8 * kLow[1], pz + 8 * kLow[2]};
          double sum = 0.0;
          for (int z = kLow[2]; z <= kHigh[2]; ++z)
            for (int y = kLow[1]; y <= kHigh[1]; ++y)
              for (int x = kLow[0]; x <= kHigh[0]; ++x) {
                const double v = at_integers.at(x, y, z);
                if (v != 0.0) sum += v * d.at(p[0] - x, p[1] - y, p[2] - z);
              }
          s.eighths[static_cast<std::size_t>(px) + n * (static_cast<std::size_t>(py) + n * static_cast<std::size_t>(pz))] = sum;
        }

    // BB coefficients interpolating M at the domain points (Σ γ_i V_i)/4 of every tetrahedron;
    // the collocation matrix is the same for all tetrahedra.
    const auto& beta = quartic_multi_indices();
    Eigen::MatrixXd collocation(kQuarticCoefficients, kQuarticCoefficients);
    for (int g = 0; g < kQuarticCoefficients; ++g) {
      const std::array<double, 4> b{beta[g][0] / 4.0, beta[g][1] / 4.0, beta[g][2] / 4.0, beta[g][3] / 4.0};
      for (int k = 0; k < kQuarticCoefficients; ++k) collocation(g, k) = bernstein(beta[k], b);
    }
    const Eigen::PartialPivLU<Eigen::MatrixXd> lu(collocation);
    for (int cz = kLow[2]; cz < kHigh[2]; ++cz)
      for (int cy = kLow[1]; cy < kHigh[1]; ++cy)
        for (int cx = kLow[0]; cx < kHigh[0]; ++cx)
          for (int t = 0; t < kCubeTetrahedra; ++t) {
            const auto v = cube_tetrahedron_vertices(t);
            Eigen::VectorXd values(kQuarticCoefficients);
            for (int g = 0; g < kQuarticCoefficients; ++g) {
              // 8 (r + Σ γ_i V_i / 4) = 8 r + Σ γ_i (2 V_i), an integer point.
              std::array<int, 3> e{8 * cx, 8 * cy, 8 * cz};
              for (int i = 0; i < 4; ++i)
                for (int c = 0; c < 3; ++c) e[c] += beta[g][i] * static_cast<int>(std::lround(2.0 * v[i][c]));
              values(g) = s.value_at_eighths(e);
            }
            if (values.cwiseAbs().maxCoeff() < 1e-14) continue;
            const Eigen::VectorXd bb = lu.solve(values);
            SevenDirectionBoxSpline::Piece piece{{cx, cy, cz}, t, {}};
            for (int k = 0; k < kQuarticCoefficients; ++k) piece.bb[k] = bb(k);
            s.pieces_on_tetrahedron[t].push_back(static_cast<int>(s.pieces.size()));
            s.pieces.push_back(piece);
          }
    // Tetrahedron 0 of uncentred knot cube q is tetrahedron 0 of the centred knot cube around
    // m = q − (0, 0, 2); a piece of cube p there belongs to the shift j = q − p = m + r.
    for (const int p : s.pieces_on_tetrahedron[0]) {
      const auto& piece = s.pieces[static_cast<std::size_t>(p)];
      s.canonical_offsets.push_back({-piece.cube[0], -piece.cube[1], 2 - piece.cube[2]});
      s.canonical_bb.push_back(piece.bb);
    }
    return s;
  }();
  return tables;
}

}  // namespace volspline
