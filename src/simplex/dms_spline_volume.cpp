#include "volspline/simplex/dms_spline_volume.h"

#include <algorithm>
#include <map>
#include <set>

#include "volspline/core/error.h"
#include "volspline/simplex/dms_tetrahedron_basis.h"
#include "volspline/simplex/simplex_spline.h"

namespace volspline {
namespace {

// The domain point of β as the multiset of its n vertex indices (p repeated i times, ...): two
// tetrahedra share a control vector exactly when these multisets agree, which happens only for β
// on their common face, edge or vertex.
using DomainPointKey = std::array<int, kMaxSimplexSplineDegree>;

DomainPointKey domain_point_key(const std::array<int, 4>& tetrahedron, const std::array<int, 4>& beta) {
  DomainPointKey key;
  key.fill(-1);
  int at = 0;
  for (int c = 0; c < 4; ++c)
    for (int m = 0; m < beta[static_cast<std::size_t>(c)]; ++m) key[static_cast<std::size_t>(at++)] = tetrahedron[static_cast<std::size_t>(c)];
  // Insertion sort of the at <= 5 entries (std::sort here trips GCC 12's -Warray-bounds).
  for (int i = 1; i < at; ++i)
    for (int j = i; j > 0 && key[static_cast<std::size_t>(j - 1)] > key[static_cast<std::size_t>(j)]; --j)
      std::swap(key[static_cast<std::size_t>(j - 1)], key[static_cast<std::size_t>(j)]);
  return key;
}

void check_attribute_name(const std::string& name, const std::vector<std::string>& existing, const std::string& where) {
  if (name.empty()) throw InvalidInput("expected a nonempty attribute name, got \"\"", where);
  if (name == "x" || name == "y" || name == "z")
    throw InvalidInput("expected an attribute name other than x, y and z (the geometry's coordinates), got \"" + name + "\"", where);
  if (std::find(existing.begin(), existing.end(), name) != existing.end())
    throw InvalidInput("expected each attribute name once, got \"" + name + "\" twice", where);
}

}  // namespace

DmsSplineVolume::DmsSplineVolume(TetrahedralMesh domain, KnotClouds knots, DmsControlSharing sharing,
                                 std::vector<std::string> attribute_names)
    : domain_(std::move(domain)), knots_(std::move(knots)), sharing_(sharing) {
  const int n = knots_.degree;
  if (n < 0 || n > kMaxSimplexSplineDegree)
    throw InvalidInput("expected a degree from 0 to " + std::to_string(kMaxSimplexSplineDegree) + ", got " + std::to_string(n), "degree");
  if (sharing_ == DmsControlSharing::Shared && n == 0)
    throw InvalidInput("shared control vectors need degree >= 1 (a degree-0 spline is constant on each tetrahedron: use per-tetrahedron control vectors)",
                       "control");
  validate_tetrahedral_mesh(domain_);
  const std::size_t expected_knots = domain_.points.size() * static_cast<std::size_t>(n + 1);
  if (knots_.knots.size() != expected_knots)
    throw InvalidInput("expected " + std::to_string(expected_knots) + " knots (" + std::to_string(n + 1) + " per domain point), got " +
                           std::to_string(knots_.knots.size()),
                       "knot_clouds");
  validate_knot_clouds(domain_, knots_);
  for (std::size_t a = 0; a < attribute_names.size(); ++a) {
    check_attribute_name(attribute_names[a], std::vector<std::string>(attribute_names.begin(), attribute_names.begin() + static_cast<std::ptrdiff_t>(a)),
                         "attributes[" + std::to_string(a) + "]");
  }
  attribute_names_ = std::move(attribute_names);

  const std::vector<std::array<int, 4>> betas = dms_multi_indices(n);
  basis_per_tetrahedron_ = static_cast<int>(betas.size());
  const std::size_t tetrahedra = domain_.tetrahedra.size();
  control_index_.resize(tetrahedra * betas.size());
  if (sharing_ == DmsControlSharing::PerTetrahedron) {
    uses_.resize(control_index_.size());
    for (std::size_t t = 0; t < tetrahedra; ++t)
      for (std::size_t b = 0; b < betas.size(); ++b) {
        const std::size_t row = t * betas.size() + b;
        control_index_[row] = static_cast<int>(row);
        uses_[row].push_back({static_cast<int>(t), static_cast<int>(b)});
      }
  } else {
    std::map<DomainPointKey, int> rows;
    for (std::size_t t = 0; t < tetrahedra; ++t)
      for (std::size_t b = 0; b < betas.size(); ++b) {
        const auto [it, added] = rows.emplace(domain_point_key(domain_.tetrahedra[t], betas[b]), static_cast<int>(uses_.size()));
        if (added) uses_.emplace_back();
        control_index_[t * betas.size() + b] = it->second;
        uses_[static_cast<std::size_t>(it->second)].push_back({static_cast<int>(t), static_cast<int>(b)});
      }
  }
  control_ = Eigen::MatrixXd::Zero(static_cast<Eigen::Index>(uses_.size()), dimension());
  for (int row = 0; row < control_vector_count(); ++row) {
    const auto [t, b] = uses_[static_cast<std::size_t>(row)].front();
    const std::vector<Eigen::Vector3d> arguments = dms_blossom_arguments(*this, t, b);
    Eigen::Vector3d point = Eigen::Vector3d::Zero();
    // The blossom of the identity is the mean of its arguments; degree 0 has none, so its one
    // control point per tetrahedron is the centroid.
    if (arguments.empty()) point = domain_point(row);
    else {
      for (const Eigen::Vector3d& a : arguments) point += a;
      point /= static_cast<double>(arguments.size());
    }
    control_.row(row).head<3>() = point.transpose();
  }
}

Eigen::Vector3d DmsSplineVolume::domain_point(int row) const {
  const auto [t, b] = uses_.at(static_cast<std::size_t>(row)).front();
  const std::array<int, 4>& tet = domain_.tetrahedra[static_cast<std::size_t>(t)];
  const std::array<int, 4> beta = dms_multi_indices(degree())[static_cast<std::size_t>(b)];
  Eigen::Vector3d point = Eigen::Vector3d::Zero();
  if (degree() == 0) {
    for (int c = 0; c < 4; ++c) point += domain_.points[static_cast<std::size_t>(tet[static_cast<std::size_t>(c)])];
    return point / 4.0;
  }
  for (int c = 0; c < 4; ++c)
    point += beta[static_cast<std::size_t>(c)] * domain_.points[static_cast<std::size_t>(tet[static_cast<std::size_t>(c)])];
  return point / static_cast<double>(degree());
}

int DmsSplineVolume::attribute_column(const std::string& name) const {
  const auto it = std::find(attribute_names_.begin(), attribute_names_.end(), name);
  if (it != attribute_names_.end()) return 3 + static_cast<int>(it - attribute_names_.begin());
  std::string names;
  for (const std::string& a : attribute_names_) names += (names.empty() ? "" : ", ") + a;
  throw InvalidInput("no attribute \"" + name + "\" (the volume has " + (names.empty() ? std::string("none") : names) + ")");
}

void DmsSplineVolume::add_attribute(const std::string& name) {
  check_attribute_name(name, attribute_names_, "attributes");
  attribute_names_.push_back(name);
  control_.conservativeResize(Eigen::NoChange, dimension());
  control_.col(dimension() - 1).setZero();
}

std::vector<Eigen::Vector3d> dms_blossom_arguments(const DmsSplineVolume& volume, int tetrahedron, int beta_position) {
  const std::array<int, 4>& tet = volume.domain().tetrahedra.at(static_cast<std::size_t>(tetrahedron));
  const std::array<int, 4> beta = dms_multi_indices(volume.degree()).at(static_cast<std::size_t>(beta_position));
  std::vector<Eigen::Vector3d> arguments;
  arguments.reserve(static_cast<std::size_t>(volume.degree()));
  for (int c = 0; c < 4; ++c) {
    const Eigen::Vector3d* cloud = volume.knots().cloud(tet[static_cast<std::size_t>(c)]);
    for (int m = 0; m < beta[static_cast<std::size_t>(c)]; ++m) arguments.push_back(cloud[m]);
  }
  return arguments;
}

void set_column_from_blossom(DmsSplineVolume& volume, int column,
                             const std::function<double(std::span<const Eigen::Vector3d>)>& blossom) {
  if (column < 0 || column >= volume.dimension())
    throw InvalidInput("expected a column from 0 to " + std::to_string(volume.dimension() - 1) + ", got " + std::to_string(column));
  for (int row = 0; row < volume.control_vector_count(); ++row) {
    const auto [t, b] = volume.control_row_uses()[static_cast<std::size_t>(row)].front();
    const std::vector<Eigen::Vector3d> arguments = dms_blossom_arguments(volume, t, b);
    volume.control_vectors()(row, column) = blossom(arguments);
  }
}

}  // namespace volspline
