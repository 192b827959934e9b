#include "volspline/extract/sheet_line_crossing.h"

#include <algorithm>
#include <functional>
#include <cmath>
#include <limits>
#include <vector>

#include <Eigen/Geometry>
#include <Eigen/LU>

namespace volspline {

namespace {

template <int D>
struct SheetDerivativeTable {
  // index[i][j]: the position of d^2 s / dp_i dp_j in derivative_multi_indices<D>(2); first[i]
  // that of ds / dp_i.
  std::array<std::size_t, D> first{};
  std::array<std::array<std::size_t, D>, D> second{};
  std::size_t count = 0;

  SheetDerivativeTable() {
    const auto alphas = derivative_multi_indices<D>(2);
    count = alphas.size();
    auto find = [&](std::array<int, D> alpha) {
      return static_cast<std::size_t>(std::find(alphas.begin(), alphas.end(), alpha) - alphas.begin());
    };
    for (int i = 0; i < D; ++i) {
      std::array<int, D> e{};
      e[static_cast<std::size_t>(i)] = 1;
      first[static_cast<std::size_t>(i)] = find(e);
      for (int j = 0; j < D; ++j) {
        std::array<int, D> f = e;
        ++f[static_cast<std::size_t>(j)];
        second[static_cast<std::size_t>(i)][static_cast<std::size_t>(j)] = find(f);
      }
    }
  }
};

double sheet_det(const Eigen::Vector3d& x, const Eigen::Vector3d& y, const Eigen::Vector3d& z) { return x.dot(y.cross(z)); }

}  // namespace

template <int D>
std::optional<SheetLineCrossing<D>> sheet_line_crossing(const TensorSpline<D>& s, const SupersetSheet& sheet,
                                                        const std::array<double, D>& start, double lambda_start,
                                                        const Eigen::Vector3d& a, const Eigen::Vector3d& b) {
  static const SheetDerivativeTable<D> table;
  std::array<int, D> free{};
  int k = 0;
  for (int d = 0; d < D; ++d)
    if (!((sheet.fixed >> d) & 1)) free[static_cast<std::size_t>(k++)] = d;
  // Constraints beyond the three coordinates: none on a face, J = 0 on a fold, two
  // sub-Jacobians on the rank-deficient set.
  const int constraints = k - 2;
  if (constraints < 0 || (constraints == 1 && !sheet.fold) || (constraints == 2 && (sheet.fold || D != 4)) || constraints > 2)
    return std::nullopt;
  const int n = k + 1;
  const int order = constraints > 0 ? 2 : 1;
  const Eigen::Vector3d direction = b - a;
  const double length = direction.norm();
  if (!(length > 0)) return std::nullopt;

  std::array<double, D> p = start;
  for (int d = 0; d < D; ++d) p[static_cast<std::size_t>(d)] = std::clamp(p[static_cast<std::size_t>(d)], s.domain_min(d), s.domain_max(d));
  double lambda = lambda_start;
  std::vector<double> values(table.count * 3);
  auto column = [&](std::size_t alpha) { return Eigen::Vector3d(values[3 * alpha], values[3 * alpha + 1], values[3 * alpha + 2]); };
  auto partial = [&](int d) { return column(table.first[static_cast<std::size_t>(d)]); };
  auto second = [&](int d, int e) { return column(table.second[static_cast<std::size_t>(d)][static_cast<std::size_t>(e)]); };

  // The rank-deficient set's pair (a, b): the two columns spanning the image plane best at the
  // start, kept throughout so that the equations do not change under Newton.
  std::array<int, 4> rank_columns{0, 1, 2, 3};
  using Matrix = Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, 0, 5, 5>;
  using Vector = Eigen::Matrix<double, Eigen::Dynamic, 1, 0, 5, 1>;
  Matrix jacobian(n, n);
  Vector residual(n);
  bool first_iteration = true;
  // The determinants are divided by the product of the three longest free columns at the start,
  // kept throughout. (Dividing each by the product of its own columns' lengths, as before, is
  // discontinuous where a column vanishes on the sheet: det[s_a s_b s_u] / |s_u| changes sign
  // with u - u0 where the map doubles back with s_u = 0, Fig. 7's fold, and Newton failed
  // there on 33 of 36 test segments.)
  double constraint_scale = 1;
  for (int iteration = 0; iteration < 24; ++iteration) {
    s.evaluate_derivatives(p, order, values.data());
    const Eigen::Vector3d position = column(0);
    if (first_iteration && constraints > 0) {
      std::array<double, 4> norms{0, 0, 0, 0};
      for (int j = 0; j < k; ++j) norms[static_cast<std::size_t>(j)] = partial(free[static_cast<std::size_t>(j)]).norm();
      std::sort(norms.begin(), norms.end(), std::greater<>());
      constraint_scale = std::max(norms[0] * norms[1] * norms[2], 1e-300);
    }
    if (first_iteration && constraints == 2) {
      double best = -1;
      for (int i = 0; i < 4; ++i)
        for (int j = i + 1; j < 4; ++j) {
          const double c = partial(i).cross(partial(j)).norm();
          if (c > best) {
            best = c;
            int o = 0;
            rank_columns = {i, j, 0, 0};
            for (int m = 0; m < 4; ++m)
              if (m != i && m != j) rank_columns[static_cast<std::size_t>(2 + o++)] = m;
          }
        }
    }
    first_iteration = false;
    residual.head<3>() = position - a - lambda * direction;
    for (int j = 0; j < k; ++j) jacobian.block<3, 1>(0, j) = partial(free[static_cast<std::size_t>(j)]);
    jacobian.block<3, 1>(0, k) = -direction;
    // det[s_x s_y s_z] and its gradient over the free parameters (product rule on the columns).
    auto constraint_row = [&](int row, int x, int y, int z) {
      const Eigen::Vector3d sx = partial(x), sy = partial(y), sz = partial(z);
      const double scale = constraint_scale;
      residual(row) = sheet_det(sx, sy, sz) / scale;
      for (int j = 0; j < k; ++j) {
        const int f = free[static_cast<std::size_t>(j)];
        jacobian(row, j) = (sheet_det(second(x, f), sy, sz) + sheet_det(sx, second(y, f), sz) + sheet_det(sx, sy, second(z, f))) / scale;
      }
      jacobian(row, k) = 0;
    };
    if (constraints == 1) constraint_row(3, free[0], free[1], free[2]);
    if (constraints == 2) {
      constraint_row(3, rank_columns[0], rank_columns[1], rank_columns[2]);
      constraint_row(4, rank_columns[0], rank_columns[1], rank_columns[3]);
    }
    const bool converged = residual.head<3>().norm() <= 1e-10 * length && (constraints == 0 || residual.tail(constraints).norm() <= 1e-9);
    if (converged) {
      if (lambda < -1e-9 || lambda > 1 + 1e-9) return std::nullopt;
      // A determinant that vanishes because a column does marks no fold where the column
      // vanishes for the parameterisation's sake: a face of the domain collapsed to a curve or a
      // point (a ball's pole, a cylinder's axis, swept), across which J keeps its sign. Such a
      // point lies on the domain's boundary in a free parameter. Inside the domain a vanishing
      // column is the map doubling back on itself (Fig. 7's generator, whose interior control
      // points are pulled out beyond its side, turns back along u at its equator: s_u = 0 on the
      // fold there), a true fold whose image bounds the swept volume.
      if (constraints > 0) {
        double smallest = std::numeric_limits<double>::infinity(), largest = 0;
        for (int j = 0; j < k; ++j) {
          const double norm = partial(free[static_cast<std::size_t>(j)]).norm();
          smallest = std::min(smallest, norm);
          largest = std::max(largest, norm);
        }
        bool on_face = false;
        for (int j = 0; j < k; ++j) {
          const int f = free[static_cast<std::size_t>(j)];
          // 1e-6 of the range: Newton may stop a little off a collapsed face, where J is tiny
          // without a fold (an independent review's point).
          const double x = p[static_cast<std::size_t>(f)], margin = 1e-6 * (s.domain_max(f) - s.domain_min(f));
          on_face = on_face || x <= s.domain_min(f) + margin || x >= s.domain_max(f) - margin;
        }
        if (smallest < 1e-3 * largest && on_face) return std::nullopt;
      }
      SheetLineCrossing<D> out;
      out.parameter = p;
      out.lambda = std::clamp(lambda, 0.0, 1.0);
      // The image plane: the two free columns (all four on the rank-deficient set) whose cross
      // product is largest.
      Eigen::Vector3d normal = Eigen::Vector3d::Zero();
      double scale = 0;
      const int columns = constraints == 2 ? 4 : k;
      for (int i = 0; i < columns; ++i) {
        const Eigen::Vector3d si = partial(constraints == 2 ? i : free[static_cast<std::size_t>(i)]);
        for (int j = i + 1; j < columns; ++j) {
          const Eigen::Vector3d sj = partial(constraints == 2 ? j : free[static_cast<std::size_t>(j)]);
          const Eigen::Vector3d c = si.cross(sj);
          if (c.norm() > normal.norm()) normal = c;
          scale = std::max(scale, si.norm() * sj.norm());
        }
      }
      if (normal.norm() > 1e-6 * scale) out.normal = normal.normalized();
      return out;
    }
    const Eigen::FullPivLU<Matrix> lu(jacobian);
    if (!lu.isInvertible()) return std::nullopt;
    Vector step = -lu.solve(residual);
    if (!step.allFinite()) return std::nullopt;
    // Damping: at most a quarter of the domain per parameter and one segment length.
    double shrink = 1;
    for (int j = 0; j < k; ++j) {
      const int f = free[static_cast<std::size_t>(j)];
      const double limit = 0.25 * (s.domain_max(f) - s.domain_min(f));
      if (std::abs(step(j)) > limit) shrink = std::min(shrink, limit / std::abs(step(j)));
    }
    if (std::abs(step(k)) > 1) shrink = std::min(shrink, 1 / std::abs(step(k)));
    step *= shrink;
    for (int j = 0; j < k; ++j) {
      const int f = free[static_cast<std::size_t>(j)];
      auto& x = p[static_cast<std::size_t>(f)];
      x = std::clamp(x + step(j), s.domain_min(f), s.domain_max(f));
    }
    lambda += step(k);
    if (lambda < -2 || lambda > 3) return std::nullopt;
  }
  return std::nullopt;
}

template std::optional<SheetLineCrossing<3>> sheet_line_crossing<3>(const TensorSpline<3>&, const SupersetSheet&, const std::array<double, 3>&,
                                                                    double, const Eigen::Vector3d&, const Eigen::Vector3d&);
template std::optional<SheetLineCrossing<4>> sheet_line_crossing<4>(const TensorSpline<4>&, const SupersetSheet&, const std::array<double, 4>&,
                                                                    double, const Eigen::Vector3d&, const Eigen::Vector3d&);

}  // namespace volspline
