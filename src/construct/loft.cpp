#include "volspline/construct/loft.h"

#include <algorithm>
#include <cmath>
#include <string>

#include <Eigen/Dense>

#include "volspline/core/error.h"
#include "volspline/spline/degree_elevation.h"
#include "volspline/spline/knot_insertion.h"

namespace volspline {

namespace {

// Knots closer than this on [0, 1] are one knot (rounding of the affine domain map).
constexpr double kKnotTolerance = 1e-12;

std::string section_name(std::size_t i) { return "sections[" + std::to_string(i) + "]"; }

BSplineSurface with_knots(const BSplineSurface& s, std::array<KnotVector, 2> knots, bool rational) {
  if (rational == s.is_rational()) return BSplineSurface::from_homogeneous(std::move(knots), s.dimension(), rational, s.homogeneous());
  // polynomial -> rational with weight 1: the homogeneous form of a point x is (x, 1)
  const int dim = s.dimension(), n = s.num_control_points_total();
  std::vector<double> h;
  h.reserve(static_cast<std::size_t>(n * (dim + 1)));
  for (int i = 0; i < n; ++i) {
    for (int c = 0; c < dim; ++c) h.push_back(s.points()[static_cast<std::size_t>(i * dim + c)]);
    h.push_back(1.0);
  }
  return BSplineSurface::from_homogeneous(std::move(knots), dim, true, std::move(h));
}

// The affine map of the domain onto [0, 1]: same basis functions of the new parameter.
KnotVector unit_domain(const KnotVector& k) {
  const double a = k.domain_min(), b = k.domain_max();
  std::vector<double> t = k.knots();
  for (double& x : t) x = (x - a) / (b - a);
  // clamped: the ends are exactly a and b, so exactly 0 and 1, but keep them exact regardless
  for (int i = 0; i <= k.degree(); ++i) t[static_cast<std::size_t>(i)] = 0.0, t[t.size() - 1 - static_cast<std::size_t>(i)] = 1.0;
  return KnotVector(k.degree(), std::move(t));
}

double distance(const double* a, const double* b, int n) {
  double s = 0.0;
  for (int c = 0; c < n; ++c) s += (a[c] - b[c]) * (a[c] - b[c]);
  return std::sqrt(s);
}

void check_sections(const std::vector<BSplineSurface>& sections) {
  for (std::size_t i = 1; i < sections.size(); ++i)
    if (sections[i].dimension() != sections[0].dimension())
      throw InvalidInput("lies in R^" + std::to_string(sections[i].dimension()) + " but sections[0] in R^" +
                             std::to_string(sections[0].dimension()),
                         section_name(i));
}

// eq. 7: the control nets of the (compatible) sections stacked as the w layers of a volume.
BSplineVolume stack(const std::vector<BSplineSurface>& nets, const KnotVector& kw) {
  std::vector<double> coefficients;
  for (const auto& s : nets) coefficients.insert(coefficients.end(), s.homogeneous().begin(), s.homogeneous().end());
  const auto& f = nets.front();
  return BSplineVolume::from_homogeneous({f.knot_vector(0), f.knot_vector(1), kw}, f.dimension(), f.is_rational(),
                                         std::move(coefficients));
}

}  // namespace

void make_compatible(std::vector<BSplineSurface>& sections) {
  check_sections(sections);
  const bool rational = std::any_of(sections.begin(), sections.end(), [](const BSplineSurface& s) { return s.is_rational(); });
  std::array<int, 2> degree{1, 1};
  for (auto& s : sections) {
    s = clamp(s);
    s = with_knots(s, {unit_domain(s.knot_vector(0)), unit_domain(s.knot_vector(1))}, rational);
    for (int d = 0; d < 2; ++d) degree[static_cast<std::size_t>(d)] = std::max(degree[static_cast<std::size_t>(d)], s.degrees()[static_cast<std::size_t>(d)]);
  }
  // Elevate before merging: elevation raises every knot's multiplicity by the same amount.
  for (auto& s : sections)
    for (int d = 0; d < 2; ++d) s = elevate_degree(s, d, degree[static_cast<std::size_t>(d)] - s.degrees()[static_cast<std::size_t>(d)]);
  if (sections.size() < 2) return;
  for (int d = 0; d < 2; ++d) {
    // Representative interior knot values with their largest multiplicity over the sections.
    std::vector<std::pair<double, int>> merged;
    auto representative = [&](double x) -> std::pair<double, int>* {
      for (auto& m : merged)
        if (std::abs(m.first - x) <= kKnotTolerance) return &m;
      return nullptr;
    };
    for (const auto& s : sections) {
      const auto& kv = s.knot_vector(d);
      for (double x : kv.breakpoints()) {
        if (x <= 0.0 || x >= 1.0) continue;
        if (auto* m = representative(x)) m->second = std::max(m->second, kv.multiplicity(x));
        else merged.emplace_back(x, kv.multiplicity(x));
      }
    }
    for (auto& s : sections) {
      std::vector<double> t = s.knot_vector(d).knots();
      for (double& x : t)
        if (x > 0.0 && x < 1.0) x = representative(x)->first;
      auto knots = s.knot_vectors();
      knots[static_cast<std::size_t>(d)] = KnotVector(s.degrees()[static_cast<std::size_t>(d)], std::move(t));
      s = with_knots(s, std::move(knots), rational);
      std::vector<double> missing;
      for (const auto& [x, m] : merged)
        for (int c = s.knot_vector(d).multiplicity(x); c < m; ++c) missing.push_back(x);
      if (!missing.empty()) s = refine_knots(s, d, missing);
    }
  }
}

BSplineVolume ruled_volume(const BSplineSurface& a, const BSplineSurface& b) {
  std::vector<BSplineSurface> nets{a, b};
  make_compatible(nets);
  return stack(nets, KnotVector::bezier(1));
}

std::vector<double> loft_parameters(const std::vector<BSplineSurface>& sections, LoftParameterization parameterization) {
  const std::size_t n = sections.size();
  for (std::size_t i = 1; i < n; ++i)
    if (sections[i].knot_vectors() != sections[0].knot_vectors() || sections[i].is_rational() != sections[0].is_rational() ||
        sections[i].dimension() != sections[0].dimension())
      throw InvalidInput("is not compatible with sections[0] (call make_compatible first)", section_name(i));
  std::vector<double> t(n, 0.0);
  if (n < 2) return t;
  const int cs = sections[0].coefficient_size(), count = sections[0].num_control_points_total();
  std::vector<double> chord(n);
  int used = 0;
  for (int m = 0; m < count; ++m) {
    chord[0] = 0.0;
    for (std::size_t k = 1; k < n; ++k) {
      const double d = distance(sections[k].homogeneous().data() + m * cs, sections[k - 1].homogeneous().data() + m * cs, cs);
      chord[k] = chord[k - 1] + (parameterization == LoftParameterization::Centripetal ? std::sqrt(d) : d);
    }
    if (chord[n - 1] == 0.0) continue;  // a control point shared by all sections says nothing
    for (std::size_t k = 1; k < n; ++k) t[k] += chord[k] / chord[n - 1];
    ++used;
  }
  if (used == 0) throw InvalidInput("all sections have the same control net", "sections");
  for (std::size_t k = 1; k + 1 < n; ++k) t[k] /= used;
  t[n - 1] = 1.0;
  for (std::size_t k = 1; k < n; ++k)
    if (!(t[k] > t[k - 1])) throw InvalidInput("has the same control net as " + section_name(k - 1), section_name(k));
  return t;
}

BSplineVolume loft(const std::vector<BSplineSurface>& sections, int degree_w, LoftParameterization parameterization) {
  if (sections.size() < 2)
    throw InvalidInput("a loft needs at least 2 sections, got " + std::to_string(sections.size()), "sections");
  if (degree_w < 1) throw InvalidInput("the degree in w must be >= 1, got " + std::to_string(degree_w), "degree");
  std::vector<BSplineSurface> nets = sections;
  make_compatible(nets);
  const auto t = loft_parameters(nets, parameterization);
  const int n = static_cast<int>(nets.size()), p = std::min(degree_w, n - 1);
  // Knots by averaging (Piegl-Tiller eq. 9.8): every span holds a parameter, so the
  // collocation matrix is nonsingular (Schoenberg-Whitney).
  std::vector<double> knots(static_cast<std::size_t>(p + 1), 0.0);
  for (int j = 1; j <= n - 1 - p; ++j) {
    double s = 0.0;
    for (int i = j; i < j + p; ++i) s += t[static_cast<std::size_t>(i)];
    knots.push_back(s / p);
  }
  knots.insert(knots.end(), static_cast<std::size_t>(p + 1), 1.0);
  const KnotVector kw(p, std::move(knots));
  Eigen::MatrixXd A = Eigen::MatrixXd::Zero(n, n);
  std::vector<double> basis(static_cast<std::size_t>(p + 1));
  for (int k = 0; k < n; ++k) {
    const int span = kw.find_span(t[static_cast<std::size_t>(k)]);
    kw.basis(span, t[static_cast<std::size_t>(k)], basis.data());
    for (int j = 0; j <= p; ++j) A(k, span - p + j) = basis[static_cast<std::size_t>(j)];
  }
  // One right-hand side per homogeneous coordinate of every control point of the net.
  const int columns = nets[0].coefficient_size() * nets[0].num_control_points_total();
  Eigen::MatrixXd B(n, columns);
  for (int k = 0; k < n; ++k)
    for (int c = 0; c < columns; ++c) B(k, c) = nets[static_cast<std::size_t>(k)].homogeneous()[static_cast<std::size_t>(c)];
  const Eigen::MatrixXd X = A.partialPivLu().solve(B);
  std::vector<double> coefficients(static_cast<std::size_t>(n) * static_cast<std::size_t>(columns));
  for (int l = 0; l < n; ++l)
    for (int c = 0; c < columns; ++c) coefficients[static_cast<std::size_t>(l) * static_cast<std::size_t>(columns) + static_cast<std::size_t>(c)] = X(l, c);
  const auto& f = nets.front();
  if (f.is_rational()) {
    const int cs = f.coefficient_size();
    for (std::size_t i = static_cast<std::size_t>(cs - 1); i < coefficients.size(); i += static_cast<std::size_t>(cs))
      if (coefficients[i] < 0.0)
        throw InvalidInput("interpolating the weights of the rational sections makes a weight negative; use a lower degree or "
                           "sections with more similar weights",
                           "sections");
  }
  return BSplineVolume::from_homogeneous({f.knot_vector(0), f.knot_vector(1), kw}, f.dimension(), f.is_rational(),
                                         std::move(coefficients));
}

}  // namespace volspline
