#include "volspline/extract/interior_face_sweeps.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <string>
#include <tuple>

#include "volspline/analysis/sub_jacobians.h"
#include "volspline/core/error.h"
#include "volspline/spline/bezier_extraction.h"
#include "volspline/spline/iso_restriction.h"

namespace volspline {

namespace {

// The weak sign of J123 = det[s_u s_v s_w] on the whole patch (+1, -1), or 0 where it takes
// both signs or vanishes: from the Bernstein coefficients of every Bézier piece (convex hull
// property), a coefficient counting as zero within 1e-10 of the largest (the margin rule of the
// 3-face folds, docs/envelopes.md "The superset").
int weak_jacobian_sign(const BSplineHypervolume& patch) {
  std::vector<double> coefficients;
  double largest = 0;
  for (const BSplineHypervolume& piece : bezier_pieces(patch.translated_to_local_origin())) {
    const BernsteinTensor<4> j123 = bernstein_components(sub_jacobian_coefficients(piece).minors, 0);
    coefficients.insert(coefficients.end(), j123.coefficients.begin(), j123.coefficients.end());
    largest = std::max(largest, bernstein_max_abs(j123));
  }
  if (!(largest > 0)) return 0;
  const double margin = 1e-10 * largest;
  const bool positive = std::all_of(coefficients.begin(), coefficients.end(), [&](double c) { return c >= -margin; });
  const bool negative = std::all_of(coefficients.begin(), coefficients.end(), [&](double c) { return c <= margin; });
  return positive == negative ? 0 : (positive ? 1 : -1);
}

// One of the eight symmetries of the square of a face's two parameters: H(x0, x1, t) =
// G(psi(x0, x1), t) with psi swapping the two (swap) and then reversing each (reverse0/1);
// orientation = det D psi.
struct FaceSymmetry {
  bool swap = false, reverse0 = false, reverse1 = false;
  int orientation() const { return (swap ? -1 : 1) * (reverse0 ? -1 : 1) * (reverse1 ? -1 : 1); }
};

bool same_knots(const KnotVector& a, const KnotVector& b, bool reversed) {
  if (a.degree() != b.degree() || a.knots().size() != b.knots().size()) return false;
  const double lo = b.domain_min(), hi = b.domain_max();
  const double tolerance = 1e-12 * std::max({1.0, std::abs(lo), std::abs(hi)});
  const std::size_t n = a.knots().size();
  for (std::size_t i = 0; i < n; ++i) {
    const double k = reversed ? lo + hi - b.knots()[n - 1 - i] : b.knots()[i];
    if (std::abs(a.knots()[i] - k) > tolerance) return false;
  }
  return true;
}

// Whether f = g o psi as maps, psi a symmetry of the parameters 0 and 1 (a face's two
// parameters, D = 3, t kept; or a square's two, D = 2): equal knots and homogeneous control
// points (within 1e-12 of their scale) once g's net is permuted by the symmetry.
template <int D>
bool same_map_under(const TensorSpline<D>& f, const TensorSpline<D>& g, const FaceSymmetry& symmetry) {
  if (f.is_rational() != g.is_rational() || f.dimension() != g.dimension()) return false;
  const int g0 = symmetry.swap ? 1 : 0, g1 = symmetry.swap ? 0 : 1;
  if (!same_knots(f.knot_vector(0), g.knot_vector(g0), symmetry.reverse0) || !same_knots(f.knot_vector(1), g.knot_vector(g1), symmetry.reverse1))
    return false;
  for (int d = 2; d < D; ++d)
    if (!same_knots(f.knot_vector(d), g.knot_vector(d), false)) return false;
  const auto n = f.num_control_points();
  const auto m = g.num_control_points();
  if (n[0] != m[static_cast<std::size_t>(g0)] || n[1] != m[static_cast<std::size_t>(g1)]) return false;
  for (std::size_t d = 2; d < static_cast<std::size_t>(D); ++d)
    if (n[d] != m[d]) return false;
  const std::vector<double>& a = f.homogeneous();
  const std::vector<double>& b = g.homogeneous();
  double scale = 0;
  for (double x : a) scale = std::max(scale, std::abs(x));
  for (double x : b) scale = std::max(scale, std::abs(x));
  const double tolerance = 1e-12 * std::max(scale, 1e-300);
  const auto size = static_cast<std::size_t>(f.coefficient_size());
  std::array<int, D> i{};
  for (;;) {
    const int i0 = symmetry.reverse0 ? n[0] - 1 - i[0] : i[0];
    const int i1 = symmetry.reverse1 ? n[1] - 1 - i[1] : i[1];
    std::array<int, D> from = i;
    from[0] = symmetry.swap ? i1 : i0;
    from[1] = symmetry.swap ? i0 : i1;
    const auto p = static_cast<std::size_t>(f.linear_index(i)) * size;
    const auto q = static_cast<std::size_t>(g.linear_index(from)) * size;
    for (std::size_t c = 0; c < size; ++c)
      if (std::abs(a[p + c] - b[q + c]) > tolerance) return false;
    std::size_t d = 0;
    while (d < static_cast<std::size_t>(D) && ++i[d] == n[d]) i[d++] = 0;
    if (d == static_cast<std::size_t>(D)) return true;
  }
}

void check_in_r3(const std::vector<BSplineHypervolume>& patches) {
  for (std::size_t p = 0; p < patches.size(); ++p)
    if (patches[p].dimension() != 3)
      throw InvalidInput("expected control points in R^3, got dimension " + std::to_string(patches[p].dimension()),
                         "patches[" + std::to_string(p) + "]");
}

}  // namespace

std::vector<RepeatedSquare> duplicate_squares(const std::vector<BSplineHypervolume>& patches) {
  check_in_r3(patches);
  struct Square {
    PatchSquare id;
    BSplineSurface map;
  };
  std::vector<Square> squares;
  for (std::size_t p = 0; p < patches.size(); ++p)
    for (int a = 0; a < 4; ++a)
      for (int b = a + 1; b < 4; ++b)
        for (int at_max = 0; at_max < 4; ++at_max) {
          const int bits = at_max & 1 ? 1 << a : 0, more = at_max & 2 ? 1 << b : 0;
          const double value_a = at_max & 1 ? patches[p].domain_max(a) : patches[p].domain_min(a);
          const double value_b = at_max & 2 ? patches[p].domain_max(b) : patches[p].domain_min(b);
          // Restricted along b first, so that a keeps its index.
          squares.push_back({{static_cast<int>(p), (1 << a) | (1 << b), bits | more},
                             restrict_to_iso(restrict_to_iso(patches[p], b, value_b), a, value_a)});
        }
  std::sort(squares.begin(), squares.end(), [](const Square& x, const Square& y) {
    return std::tie(x.id.patch, x.id.fixed, x.id.at_max) < std::tie(y.id.patch, y.id.fixed, y.id.at_max);
  });
  std::vector<RepeatedSquare> out;
  std::vector<char> repeat(squares.size(), 0);
  for (std::size_t g = 0; g < squares.size(); ++g)
    for (std::size_t f = 0; f < g && !repeat[g]; ++f) {
      if (repeat[f]) continue;
      for (int s = 0; s < 8 && !repeat[g]; ++s)
        if (same_map_under(squares[g].map, squares[f].map, FaceSymmetry{(s & 1) != 0, (s & 2) != 0, (s & 4) != 0})) {
          repeat[g] = 1;
          out.push_back({squares[g].id, squares[f].id});
        }
    }
  return out;
}

std::vector<PatchFace> interior_face_sweeps(const std::vector<BSplineHypervolume>& patches) {
  check_in_r3(patches);
  struct Face {
    PatchFace id;
    BSplineVolume sweep;
    // Which side of the face the patch lies on, against the normal F_a x F_b of the face's own
    // parameters a < b: n . (inward s_c) = perm(c) J123 with perm = +1, -1, +1 for c = u, v, w
    // ((s_1 x s_2) . s_0 = J, (s_0 x s_2) . s_1 = -J, (s_0 x s_1) . s_2 = J), inward = +s_c at
    // the minimum and -s_c at the maximum.
    int side = 0;
  };
  std::vector<Face> faces;
  for (std::size_t p = 0; p < patches.size(); ++p) {
    const int sign = weak_jacobian_sign(patches[p]);
    if (sign == 0) continue;  // folds (or is not a volume): its faces may bound the generator
    for (int c = 0; c < 3; ++c)
      for (int end = 0; end < 2; ++end) {
        const double value = end ? patches[p].domain_max(c) : patches[p].domain_min(c);
        faces.push_back({{static_cast<int>(p), c, end}, restrict_to_iso(patches[p], c, value), sign * (c == 1 ? -1 : 1) * (end ? -1 : 1)});
      }
  }
  std::vector<char> interior(faces.size(), 0);
  for (std::size_t f = 0; f < faces.size(); ++f)
    for (std::size_t g = f + 1; g < faces.size(); ++g) {
      if (interior[f] && interior[g]) continue;
      for (int s = 0; s < 8; ++s) {
        const FaceSymmetry symmetry{(s & 1) != 0, (s & 2) != 0, (s & 4) != 0};
        if (!same_map_under(faces[f].sweep, faces[g].sweep, symmetry)) continue;
        // faces[f] = faces[g] o psi, so their normals differ by det D psi: opposite sides when
        // side_f * side_g * orientation = -1.
        if (faces[f].side * faces[g].side * symmetry.orientation() < 0) interior[f] = interior[g] = 1;
        break;
      }
    }
  std::vector<PatchFace> out;
  for (std::size_t f = 0; f < faces.size(); ++f)
    if (interior[f]) out.push_back(faces[f].id);
  return out;
}

}  // namespace volspline
