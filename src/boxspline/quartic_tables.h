#pragma once
// Inline kernels for quartics in Bernstein–Bézier form on the 24 tetrahedra of a unit cube:
// point location and de Casteljau evaluation with derivatives. They sit in a header so the hot
// loops of the evaluators (bezier_form.h, lattice_field.h) inline them; the public face is
// seven_direction_box_spline.h.
#include <array>
#include <cmath>

#include <Eigen/Core>

#include "volspline/boxspline/seven_direction_box_spline.h"

namespace volspline::quartic {

/// Multi-indices of degree d, ordered by descending β_0, then β_1, then β_2.
template <int D>
constexpr auto make_indices() {
  std::array<std::array<int, 4>, (D + 1) * (D + 2) * (D + 3) / 6> out{};
  int n = 0;
  for (int a = D; a >= 0; --a)
    for (int b = D - a; b >= 0; --b)
      for (int c = D - a - b; c >= 0; --c) out[n++] = {a, b, c, D - a - b - c};
  return out;
}

template <int D>
constexpr int index_of(int a, int b, int c) {
  const auto all = make_indices<D>();
  for (int i = 0; i < static_cast<int>(all.size()); ++i)
    if (all[i][0] == a && all[i][1] == b && all[i][2] == c) return i;
  return -1;
}

/// up[i][k]: the index, among degree-D multi-indices, of (multi-index i of degree D-1) + e_k.
template <int D>
constexpr auto make_up() {
  constexpr auto lower = make_indices<D - 1>();
  std::array<std::array<int, 4>, lower.size()> up{};
  for (int i = 0; i < static_cast<int>(lower.size()); ++i)
    for (int k = 0; k < 4; ++k) {
      auto m = lower[i];
      ++m[k];
      up[i][k] = index_of<D>(m[0], m[1], m[2]);
    }
  return up;
}

inline constexpr auto kIndices4 = make_indices<4>();
inline constexpr auto kUp4 = make_up<4>();
inline constexpr auto kUp3 = make_up<3>();
inline constexpr auto kUp2 = make_up<2>();

/// Decoded tetrahedron index: the face axis i with its side si, the edge axis j with side sj,
/// and the remaining axis k.
struct Axes {
  int i, j, k;
  double si, sj;
};

inline Axes tetrahedron_axes(int t) {
  const int sj = t & 1, jslot = (t >> 1) & 1, si = (t >> 2) & 1, i = t >> 3;
  const int j = jslot == 0 ? (i + 1) % 3 : (i + 2) % 3;
  return Axes{i, j, 3 - i - j, si ? 1.0 : -1.0, sj ? 1.0 : -1.0};
}

/// The tetrahedron of [0,1]³ holding (x, y, z) and its barycentric coordinates: with
/// d = p − (1/2,1/2,1/2), the face axis i has the largest |d_i|, the edge axis j the second; the
/// planes |d_i| = |d_j| are exactly the knot planes x_i ± x_j ∈ Z through the cube.
inline CubeLocation locate(double x, double y, double z) {
  const double d[3] = {x - 0.5, y - 0.5, z - 0.5};
  const double a[3] = {std::abs(d[0]), std::abs(d[1]), std::abs(d[2])};
  int i, j, k;
  if (a[0] >= a[1]) {
    if (a[0] >= a[2]) {
      i = 0;
      if (a[1] >= a[2]) j = 1, k = 2;
      else j = 2, k = 1;
    } else {
      i = 2, j = 0, k = 1;
    }
  } else {
    if (a[1] >= a[2]) {
      i = 1;
      if (a[0] >= a[2]) j = 0, k = 2;
      else j = 2, k = 0;
    } else {
      i = 2, j = 1, k = 0;
    }
  }
  const int si = d[i] >= 0.0, sj = d[j] >= 0.0;
  const int jslot = j == (i + 1) % 3 ? 0 : 1;
  const double ai = a[i], aj = a[j], ck = d[k];
  CubeLocation out;
  out.tetrahedron = ((i * 2 + si) * 2 + jslot) * 2 + sj;
  out.barycentric = {1.0 - 2.0 * ai, 2.0 * (ai - aj), aj - ck, aj + ck};
  return out;
}

/// A point d of a centred knot cube [-1/2, 1/2]³: its tetrahedron t (numbered as by locate) and
/// its barycentric coordinates there. The signed permutation of the axes taking d to
/// d0[a] = ±d[axis[a]] (face axis i to x, edge axis j to y, both to their negative sides, k to z)
/// maps tetrahedron t onto tetrahedron 0, and d0's barycentric coordinates in tetrahedron 0 are
/// the same numbers.
struct CanonicalLocation {
  int tetrahedron;
  double barycentric[4];
};

inline CanonicalLocation locate_canonical(double dx, double dy, double dz) {
  const double d[3] = {dx, dy, dz};
  const double a[3] = {std::abs(dx), std::abs(dy), std::abs(dz)};
  // The decisions of locate() as a table (random points make its branches unpredictable):
  // index bits a0 ≥ a1, a0 ≥ a2, a1 ≥ a2; entry (i, j, k, jslot).
  static constexpr signed char kOrder[8][4] = {{2, 1, 0, 1}, {2, 0, 1, 0}, {2, 1, 0, 1}, {0, 2, 1, 1},
                                               {1, 2, 0, 0}, {2, 0, 1, 0}, {1, 0, 2, 1}, {0, 1, 2, 0}};
  const auto& o = kOrder[(a[0] >= a[1]) | (a[0] >= a[2]) << 1 | (a[1] >= a[2]) << 2];
  const int i = o[0], j = o[1], k = o[2];
  const int si = d[i] >= 0.0, sj = d[j] >= 0.0;
  return CanonicalLocation{((i * 2 + si) * 2 + o[3]) * 2 + sj, {1.0 - 2.0 * a[i], 2.0 * (a[i] - a[j]), a[j] - d[k], a[j] + d[k]}};
}

/// de Casteljau on a quartic in BB form: value, and (optionally) gradient and Hessian in cube
/// units from the degree-1 and degree-2 intermediates (∂f/∂λ_k = 4 b¹_k,
/// ∂²f/∂λ_k∂λ_l = 12 b²_{e_k+e_l}) and the constant gradients of the λ's.
inline double evaluate(const double* bb, int t, const double* b, Eigen::Vector3d* gradient, Eigen::Matrix3d* hessian) {
  double c3[20], c2[10], c1[4];
  for (int n = 0; n < 20; ++n)
    c3[n] = b[0] * bb[kUp4[n][0]] + b[1] * bb[kUp4[n][1]] + b[2] * bb[kUp4[n][2]] + b[3] * bb[kUp4[n][3]];
  for (int n = 0; n < 10; ++n)
    c2[n] = b[0] * c3[kUp3[n][0]] + b[1] * c3[kUp3[n][1]] + b[2] * c3[kUp3[n][2]] + b[3] * c3[kUp3[n][3]];
  for (int n = 0; n < 4; ++n)
    c1[n] = b[0] * c2[kUp2[n][0]] + b[1] * c2[kUp2[n][1]] + b[2] * c2[kUp2[n][2]] + b[3] * c2[kUp2[n][3]];
  const double value = b[0] * c1[0] + b[1] * c1[1] + b[2] * c1[2] + b[3] * c1[3];
  if (gradient != nullptr || hessian != nullptr) {
    const Axes ax = tetrahedron_axes(t);
    // Rows of the 4 x 3 matrix of barycentric gradients, stored by the nonzero entries.
    double g[4][3] = {};
    g[0][ax.i] = -2.0 * ax.si;
    g[1][ax.i] = 2.0 * ax.si;
    g[1][ax.j] = -2.0 * ax.sj;
    g[2][ax.j] = ax.sj;
    g[2][ax.k] = -1.0;
    g[3][ax.j] = ax.sj;
    g[3][ax.k] = 1.0;
    if (gradient != nullptr) {
      for (int c = 0; c < 3; ++c) (*gradient)[c] = 4.0 * (c1[0] * g[0][c] + c1[1] * g[1][c] + c1[2] * g[2][c] + c1[3] * g[3][c]);
    }
    if (hessian != nullptr) {
      // c2 holds degree-2 multi-indices in make_indices<2>() order.
      constexpr auto i2 = make_indices<2>();
      double s[4][4];
      for (int n = 0; n < 10; ++n) {
        int p = -1, q = -1;
        for (int k = 0; k < 4; ++k)
          for (int r = 0; r < i2[n][k]; ++r) (p < 0 ? p : q) = k;
        s[p][q] = s[q][p] = c2[n];
      }
      for (int r = 0; r < 3; ++r)
        for (int c = 0; c < 3; ++c) {
          double h = 0.0;
          for (int p = 0; p < 4; ++p)
            for (int q = 0; q < 4; ++q) h += s[p][q] * g[p][r] * g[q][c];
          (*hessian)(r, c) = 12.0 * h;
        }
    }
  }
  return value;
}

}  // namespace volspline::quartic
