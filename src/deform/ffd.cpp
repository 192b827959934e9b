#include "volspline/deform/ffd.h"

#include <algorithm>
#include <cmath>
#include <string>

#include <Eigen/Geometry>

#include "volspline/core/bernstein_tensor.h"
#include "volspline/core/error.h"
#include "volspline/core/format.h"
#include "volspline/mesh/mesh_checks.h"
#include "volspline/spline/bezier_extraction.h"

namespace volspline {

namespace {

Eigen::Vector3d clamp_unit(const Eigen::Vector3d& c) { return c.cwiseMax(0.0).cwiseMin(1.0); }

// Combines the lattice value at the clamped coordinates with the point (see deform_point): inside
// the domain the value itself, so the identity property rests on Greville reproduction alone.
Eigen::Vector3d combine(const Lattice& lattice, const Eigen::Vector3d& point, const Eigen::Vector3d& c,
                        const Eigen::Vector3d& clamped, const double* value) {
  const Eigen::Vector3d f(value[0], value[1], value[2]);
  if (clamped == c) return f;
  return point + (f - lattice_box_point(lattice, clamped));
}

// acc += vector * g for a scalar polynomial g of acc's degrees: one lattice control point times
// its basis function.
template <int D>
void accumulate_outer(BernsteinTensor<D>& acc, const double* vector, const BernsteinTensor<D>& g) {
  const std::size_t k = static_cast<std::size_t>(acc.components);
  for (std::size_t i = 0; i < g.coefficients.size(); ++i)
    for (std::size_t j = 0; j < k; ++j) acc.coefficients[i * k + j] += vector[j] * g.coefficients[i];
}

template <int D>
BernsteinTensor<D> constant_one() {
  BernsteinTensor<D> one(std::array<int, D>{}, 1);
  one.coefficients[0] = 1.0;
  return one;
}

// The lattice's Bernstein basis functions of one direction with the object substituted:
// B_i^p(s) = C(p,i) s^i (1 - s)^(p-i) with s = S / W, times W^p to stay polynomial:
// C(p,i) S^i (W - S)^(p-i), of degree p times the object's.
// The products are Bernstein products (core/bernstein_tensor.h): all their weights are positive,
// so polynomials with coefficients of one sign multiply without cancellation.
template <int D>
std::vector<BernsteinTensor<D>> substituted_basis(int p, const BernsteinTensor<D>& S, const BernsteinTensor<D>& W) {
  BernsteinTensor<D> R = W;
  for (std::size_t i = 0; i < R.coefficients.size(); ++i) R.coefficients[i] -= S.coefficients[i];
  std::vector<BernsteinTensor<D>> s_powers{constant_one<D>()}, r_powers{constant_one<D>()};
  for (int i = 1; i <= p; ++i) {
    s_powers.push_back(i == 1 ? S : bernstein_product(s_powers.back(), S));
    r_powers.push_back(i == 1 ? R : bernstein_product(r_powers.back(), R));
  }
  std::vector<BernsteinTensor<D>> basis;
  for (int i = 0; i <= p; ++i) {
    // Degree-0 factors have degrees 0; the product handles them like any other polynomial.
    BernsteinTensor<D> b = bernstein_product(s_powers[static_cast<std::size_t>(i)], r_powers[static_cast<std::size_t>(p - i)]);
    for (double& x : b.coefficients) x *= binomial_coefficient(p, i);
    basis.push_back(std::move(b));
  }
  return basis;
}

// One Bézier piece of the object composed with one Bézier cell of the lattice, in homogeneous
// form: returns coefficients with `out_size` numbers per Bernstein coefficient.
template <int D>
BernsteinTensor<D> compose_piece(const TensorSpline<D>& piece, const Lattice& lattice, const BSplineVolume& cell,
                           const std::array<double, 3>& cell_min, const std::array<double, 3>& cell_max) {
  const auto d = piece.degrees();
  const int k = piece.coefficient_size();
  const bool object_rational = piece.is_rational();
  const std::size_t n = static_cast<std::size_t>(piece.num_control_points_total());
  const auto& h = piece.homogeneous();

  // Lattice coordinates are affine in the object's point (eq. 10-11), so in homogeneous form
  // S_m = r_m . (X_h - P0 W) with the Cramer rows r_m; then to the cell's own [0, 1]:
  // S'_m = (S_m - a_m W) / (b_m - a_m).
  const Eigen::Vector3d U = lattice.axes.col(0), V = lattice.axes.col(1), W = lattice.axes.col(2);
  const Eigen::Vector3d vw = V.cross(W), uw = U.cross(W), uv = U.cross(V);
  const std::array<Eigen::Vector3d, 3> rows{vw / vw.dot(U), uw / uw.dot(V), uv / uv.dot(W)};
  std::array<BernsteinTensor<D>, 3> S;
  BernsteinTensor<D> weight(d, 1);
  for (int m = 0; m < 3; ++m) S[m] = BernsteinTensor<D>(d, 1);
  for (std::size_t i = 0; i < n; ++i) {
    const Eigen::Vector3d x(h[i * k], h[i * k + 1], h[i * k + 2]);
    const double w = object_rational ? h[i * k + 3] : 1.0;
    weight.coefficients[i] = w;
    for (int m = 0; m < 3; ++m) {
      const double s = rows[m].dot(x - lattice.origin * w);
      S[m].coefficients[i] = (s - cell_min[m] * w) / (cell_max[m] - cell_min[m]);
    }
  }

  const auto p = cell.degrees();
  const int kl = cell.coefficient_size();
  const auto& c = cell.homogeneous();
  const auto B0 = substituted_basis(p[0], S[0], weight);
  const auto B1 = substituted_basis(p[1], S[1], weight);
  const auto B2 = substituted_basis(p[2], S[2], weight);
  // Sum factorisation: sum_ijk c_ijk B0_i B1_j B2_k = sum_i B0_i (sum_j B1_j (sum_k c_ijk B2_k)),
  // so the expensive products are taken (p+1)(q+1) + (p+1) times instead of (p+1)(q+1)(r+1).
  BernsteinTensor<D> result;
  for (int i = 0; i <= p[0]; ++i) {
    BernsteinTensor<D> Hi;
    for (int j = 0; j <= p[1]; ++j) {
      BernsteinTensor<D> G(B2[0].degrees, kl);
      for (int l = 0; l <= p[2]; ++l) {
        const std::size_t index = static_cast<std::size_t>(i + (p[0] + 1) * (j + (p[1] + 1) * l));
        accumulate_outer(G, c.data() + index * kl, B2[l]);
      }
      BernsteinTensor<D> term = bernstein_product(G, B1[static_cast<std::size_t>(j)]);
      if (j == 0) Hi = std::move(term); else bernstein_add(Hi, term);
    }
    BernsteinTensor<D> term = bernstein_product(Hi, B0[static_cast<std::size_t>(i)]);
    if (i == 0) result = std::move(term); else bernstein_add(result, term);
  }
  if (cell.is_rational() || !object_rational) return result;
  // Polynomial lattice, rational object: result = W^(p+q+r) F(S / W), so F is the rational
  // function with numerator `result` and denominator W^(p+q+r).
  const BernsteinTensor<D> denominator = bernstein_power(weight, p[0] + p[1] + p[2]);
  BernsteinTensor<D> out(result.degrees, 4);
  for (std::size_t i = 0; i < denominator.coefficients.size(); ++i) {
    for (std::size_t j = 0; j < 3; ++j) out.coefficients[i * 4 + j] = result.coefficients[i * 3 + j];
    out.coefficients[i * 4 + 3] = denominator.coefficients[i];
  }
  return out;
}

// The lattice cell [min, max] (index: per direction) that contains the whole object.
struct LatticeCell {
  std::array<double, 3> min{}, max{};
  std::array<int, 3> index{};
};

template <int D>
LatticeCell containing_cell(const Lattice& lattice, const TensorSpline<D>& object) {
  // The lattice coordinates of the control points bound those of the whole object (convex hull
  // property, also for positive weights), so checking them places the object in the domain and
  // in one cell.
  const double tolerance = 1e-12;
  std::array<double, 3> lo{INFINITY, INFINITY, INFINITY}, hi{-INFINITY, -INFINITY, -INFINITY};
  for (int i = 0; i < object.num_control_points_total(); ++i) {
    if (object.is_rational() && object.weights()[static_cast<std::size_t>(i)] == 0.0) {
      throw InvalidInput("the object has a point at infinity (weight 0), which no lattice box contains",
                         "control_points[" + std::to_string(i) + "]");
    }
    const double* x = object.points().data() + 3 * static_cast<std::size_t>(i);
    const Eigen::Vector3d c = lattice_coordinates(lattice, Eigen::Vector3d(x[0], x[1], x[2]));
    for (int m = 0; m < 3; ++m) {
      lo[m] = std::min(lo[m], c[m]);
      hi[m] = std::max(hi[m], c[m]);
    }
  }
  LatticeCell cell;
  for (int m = 0; m < 3; ++m) {
    if (lo[m] < -tolerance || hi[m] > 1 + tolerance) {
      throw InvalidInput("the object's control points leave the deformation domain (lattice coordinate " +
                         std::to_string(m) + " spans [" + format_double(lo[m]) + ", " + format_double(hi[m]) +
                         "], not inside [0, 1]): make the lattice around them, or with a larger margin");
    }
    const auto breaks = lattice.volume.knot_vector(m).breakpoints();
    bool found = false;
    for (std::size_t c = 0; c + 1 < breaks.size() && !found; ++c) {
      if (lo[m] >= breaks[c] - tolerance && hi[m] <= breaks[c + 1] + tolerance) {
        cell.min[m] = breaks[c];
        cell.max[m] = breaks[c + 1];
        cell.index[m] = static_cast<int>(c);
        found = true;
      }
    }
    if (!found) {
      throw InvalidInput("the object crosses the knot planes of the segmented lattice (lattice coordinate " +
                         std::to_string(m) + " spans [" + format_double(lo[m]) + ", " + format_double(hi[m]) +
                         "]), where the deformation is a different polynomial on each side, so no single "
                         "composition is exact: use a single-cell (Bézier) lattice, or deform a tessellation "
                         "with deform_mesh");
    }
  }
  return cell;
}

}  // namespace

Eigen::Vector3d deform_point(const Lattice& lattice, const Eigen::Vector3d& point) {
  if (!point.allFinite()) throw InvalidInput("cannot deform a point that is not finite");
  const Eigen::Vector3d c = lattice_coordinates(lattice, point);
  const Eigen::Vector3d clamped = clamp_unit(c);
  double value[3];
  // evaluate_derivatives of order 0 is what evaluate_points runs per point, so the single and
  // the batch results are the same bits.
  lattice.volume.evaluate_derivatives({clamped.x(), clamped.y(), clamped.z()}, 0, value);
  return combine(lattice, point, c, clamped, value);
}

std::vector<Eigen::Vector3d> deform_points(const Lattice& lattice, const std::vector<Eigen::Vector3d>& points) {
  std::vector<Eigen::Vector3d> coordinates(points.size()), clamped(points.size());
  std::vector<BSplineVolume::Parameter> parameters(points.size());
  for (std::size_t i = 0; i < points.size(); ++i) {
    if (!points[i].allFinite()) throw InvalidInput("cannot deform a point that is not finite", "points[" + std::to_string(i) + "]");
    coordinates[i] = lattice_coordinates(lattice, points[i]);
    clamped[i] = clamp_unit(coordinates[i]);
    parameters[i] = {clamped[i].x(), clamped[i].y(), clamped[i].z()};
  }
  const std::vector<double> values = lattice.volume.evaluate_points(parameters, 0);
  std::vector<Eigen::Vector3d> out(points.size());
  for (std::size_t i = 0; i < points.size(); ++i) {
    out[i] = combine(lattice, points[i], coordinates[i], clamped[i], values.data() + 3 * i);
  }
  return out;
}

TriangleMesh deform_mesh(const Lattice& lattice, const TriangleMesh& mesh) {
  validate_mesh(mesh);
  TriangleMesh out = mesh;
  out.positions = deform_points(lattice, mesh.positions);
  return out;
}

template <int D>
TensorSpline<D> compose(const Lattice& lattice, const TensorSpline<D>& object) {
  validate_lattice(lattice);
  if (object.dimension() != 3) {
    throw InvalidInput("only objects in 3-space can be deformed, got dimension " + std::to_string(object.dimension()));
  }
  const auto d = object.degrees();
  const auto p = lattice.volume.degrees();
  const int n = p[0] + p[1] + p[2];
  for (int m = 0; m < D; ++m) {
    if (static_cast<long long>(n) * d[m] > kMaxModelDegree) {
      throw InvalidInput("the composition would have degree " + std::to_string(n * d[m]) + " (= (" + std::to_string(p[0]) +
                         " + " + std::to_string(p[1]) + " + " + std::to_string(p[2]) + ") x " + std::to_string(d[m]) +
                         "), above the limit " + std::to_string(kMaxModelDegree) +
                         ": use lower degrees or deform a tessellation with deform_mesh");
    }
  }

  const LatticeCell where = containing_cell(lattice, object);
  const std::array<double, 3>& cell_min = where.min;
  const std::array<double, 3>& cell_max = where.max;
  const std::array<int, 3>& cell_index = where.index;
  const auto cells = bezier_pieces(lattice.volume);
  const std::array<int, 3> spans{lattice.volume.knot_vector(0).num_spans(), lattice.volume.knot_vector(1).num_spans(),
                                 lattice.volume.knot_vector(2).num_spans()};
  const BSplineVolume& cell = cells[static_cast<std::size_t>(cell_index[0] + spans[0] * (cell_index[1] + spans[1] * cell_index[2]))];

  // Compose piece by piece and join the pieces with knots of multiplicity N = n d_m, which makes
  // the joined B-spline's control points exactly the pieces' Bézier points.
  const auto pieces = bezier_pieces(object);
  std::array<std::vector<double>, D> breaks;
  std::array<KnotVector, D> knots = object.knot_vectors();
  std::array<int, D> degree{}, counts{};
  std::size_t total = 1;
  for (int m = 0; m < D; ++m) {
    breaks[m] = object.knot_vector(m).breakpoints();
    degree[m] = n * d[m];
    std::vector<double> k(static_cast<std::size_t>(degree[m] + 1), breaks[m].front());
    for (std::size_t b = 1; b + 1 < breaks[m].size(); ++b) k.insert(k.end(), static_cast<std::size_t>(degree[m]), breaks[m][b]);
    k.insert(k.end(), static_cast<std::size_t>(degree[m] + 1), breaks[m].back());
    knots[m] = KnotVector(degree[m], std::move(k));
    counts[m] = static_cast<int>(breaks[m].size() - 1) * degree[m] + 1;
    total *= static_cast<std::size_t>(counts[m]);
  }
  const bool rational = object.is_rational() || lattice.volume.is_rational();
  const int size = rational ? 4 : 3;
  std::vector<double> coefficients(total * static_cast<std::size_t>(size));
  for (std::size_t piece = 0; piece < pieces.size(); ++piece) {
    const BernsteinTensor<D> b = compose_piece(pieces[piece], lattice, cell, cell_min, cell_max);
    std::array<int, D> offset{};
    std::size_t rest = piece;
    for (int m = 0; m < D; ++m) {
      const std::size_t cells_m = breaks[m].size() - 1;
      offset[m] = static_cast<int>(rest % cells_m) * degree[m];
      rest /= cells_m;
    }
    for (std::size_t a = 0; a < b.count(); ++a) {
      const std::array<int, D> local = b.multi_index(a);
      std::size_t index = 0, stride = 1;
      for (int m = 0; m < D; ++m) {
        index += static_cast<std::size_t>(offset[m] + local[m]) * stride;
        stride *= static_cast<std::size_t>(counts[m]);
      }
      // Neighbouring pieces share their boundary coefficients (equal up to rounding); the later
      // piece's copy is kept.
      for (int j = 0; j < size; ++j) coefficients[index * size + j] = b.coefficients[a * size + j];
    }
  }
  return TensorSpline<D>::from_homogeneous(std::move(knots), 3, rational, std::move(coefficients));
}

template BSplineCurve compose(const Lattice&, const BSplineCurve&);
template BSplineSurface compose(const Lattice&, const BSplineSurface&);
template BSplineVolume compose(const Lattice&, const BSplineVolume&);

}  // namespace volspline
