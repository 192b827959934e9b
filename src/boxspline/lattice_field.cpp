#include "volspline/boxspline/lattice_field.h"

#include <cmath>
#include <limits>
#include <string>

#include "volspline/boxspline/quartic_tables.h"
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

double LatticeField::evaluate(const Eigen::Vector3d& x, Eigen::Vector3d* gradient, Eigen::Matrix3d* hessian) const {
  const auto [lo, hi] = domain();
  const double slack = 1e-9 * spacing;
  if (!x.allFinite() || ((x.array() < lo.array() - slack) || (x.array() > hi.array() + slack)).any())
    throw InvalidInput("the point lies outside the domain of the box-spline field");
  const Eigen::Vector3d u = (x - origin) / spacing + kShift;
  // Knot cubes whose every piece has its coefficients (see domain()).
  const int q_lo[3] = {2, 2, 4};
  const int q_hi[3] = {size[0] - 3, size[1] - 3, size[2] - 1};
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
    const double c = at(q[0] - piece.cube[0], q[1] - piece.cube[1], q[2] - piece.cube[2]);
    for (int k = 0; k < kQuarticCoefficients; ++k) bb[k] += c * piece.bb[k];
  }
  const double value = quartic::evaluate(bb, loc.tetrahedron, loc.barycentric.data(), gradient, hessian);
  if (gradient != nullptr) *gradient /= spacing;
  if (hessian != nullptr) *hessian /= spacing * spacing;
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
