#include "volspline/construct/volume_data_examples.h"

#include <cmath>
#include <numbers>
#include <stdexcept>

#include "volspline/core/error.h"

namespace volspline {
namespace {

std::vector<Eigen::Vector3d> grid_points(int n, double lo, double hi) {
  if (n < 2) throw InvalidInput("expected at least 2 samples per axis, got " + std::to_string(n));
  std::vector<Eigen::Vector3d> points;
  points.reserve(static_cast<std::size_t>(n) * n * n);
  const auto at = [&](int i) { return lo + (hi - lo) * i / (n - 1); };
  for (int k = 0; k < n; ++k)
    for (int j = 0; j < n; ++j)
      for (int i = 0; i < n; ++i) points.emplace_back(at(i), at(j), at(k));
  return points;
}

}  // namespace

double marschner_lobb(const Eigen::Vector3d& x) {
  constexpr double alpha = 0.25, f_m = 6, pi = std::numbers::pi;
  const double r = std::hypot(x.x(), x.y());
  return (1 - std::sin(pi * x.z() / 2) + alpha * (1 + std::cos(2 * pi * f_m * std::cos(pi * r / 2)))) / (2 * (1 + alpha));
}

VolumeData sampled_volume_data(const std::vector<Eigen::Vector3d>& points, const std::string& name,
                               const std::function<double(const Eigen::Vector3d&)>& f) {
  VolumeData data;
  data.points = points;
  data.attribute_names = {name};
  data.attributes.resize(static_cast<Eigen::Index>(points.size()), 1);
  for (std::size_t i = 0; i < points.size(); ++i) data.attributes(static_cast<Eigen::Index>(i), 0) = f(points[i]);
  return data;
}

VolumeData marschner_lobb_data(int n) { return sampled_volume_data(grid_points(n, -1, 1), "rho", marschner_lobb); }

double two_material(const Eigen::Vector3d& x, double tilt) {
  return (x.x() + tilt * x.y() < 0.5 ? 1.0 : 2.0) + 0.1 * (x.y() + x.z());
}

VolumeData two_material_data(int n, double tilt) {
  return sampled_volume_data(grid_points(n, 0, 1), "material", [tilt](const Eigen::Vector3d& x) { return two_material(x, tilt); });
}

namespace {

struct GeneratedName {
  bool marschner_lobb = false;
  int n = 0;
  double tilt = 0;
};

// The parameters of a generated-data name, nothing for another name.
std::optional<GeneratedName> parse_generated_name(const std::string& name) {
  GeneratedName g;
  std::string rest;
  if (name.rfind("marschner-lobb:", 0) == 0) {
    g.marschner_lobb = true;
    rest = name.substr(15);
  } else if (name.rfind("two-material:", 0) == 0) {
    rest = name.substr(13);
  } else {
    return std::nullopt;
  }
  const std::string expected = g.marschner_lobb ? "expected marschner-lobb:N with N in 2..400, got '" + name + "'"
                                                : "expected two-material:N or two-material:N:TILT with N in 2..400 and a finite tilt, got '" +
                                                      name + "'";
  const std::size_t colon = rest.find(':');
  if (g.marschner_lobb && colon != std::string::npos) throw InvalidInput(expected, "DATA");
  try {
    std::size_t used = 0;
    const std::string count = rest.substr(0, colon);
    g.n = std::stoi(count, &used);
    if (used != count.size()) throw InvalidInput(expected, "DATA");
    if (colon != std::string::npos) {
      const std::string t = rest.substr(colon + 1);
      g.tilt = std::stod(t, &used);
      if (used != t.size() || !std::isfinite(g.tilt)) throw InvalidInput(expected, "DATA");
    }
  } catch (const std::logic_error&) {
    throw InvalidInput(expected, "DATA");
  }
  if (g.n < 2 || g.n > 400) throw InvalidInput(expected, "DATA");
  return g;
}

}  // namespace

std::optional<VolumeData> generated_volume_data(const std::string& name) {
  const std::optional<GeneratedName> g = parse_generated_name(name);
  if (!g) return std::nullopt;
  return g->marschner_lobb ? marschner_lobb_data(g->n) : two_material_data(g->n, g->tilt);
}

std::function<Eigen::VectorXd(const Eigen::Vector3d&)> generated_volume_truth(const std::string& name) {
  const std::optional<GeneratedName> g = parse_generated_name(name);
  if (!g) return {};
  if (g->marschner_lobb) return [](const Eigen::Vector3d& x) { return Eigen::VectorXd::Constant(1, marschner_lobb(x)); };
  const double tilt = g->tilt;
  return [tilt](const Eigen::Vector3d& x) { return Eigen::VectorXd::Constant(1, two_material(x, tilt)); };
}

}  // namespace volspline
