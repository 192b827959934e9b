#include "simplex_lattice.h"

#include <algorithm>
#include <cmath>
#include <map>

#include <Eigen/Geometry>

namespace volspline {
namespace {

// A lattice point (a_0, a_1, a_2, a_3)/k of a domain tetrahedron, named by its nonzero
// barycentric numerators and the global vertex indices they belong to (sorted), so that the same
// point reached from two tetrahedra gets the same name.
using LatticeKey = std::array<std::int64_t, 8>;

LatticeKey lattice_key(const std::array<int, 4>& sorted_vertices, const std::array<int, 4>& numerators) {
  LatticeKey key;
  key.fill(-1);
  int at = 0;
  for (int c = 0; c < 4; ++c)
    if (numerators[static_cast<std::size_t>(c)] > 0) {
      key[static_cast<std::size_t>(2 * at)] = sorted_vertices[static_cast<std::size_t>(c)];
      key[static_cast<std::size_t>(2 * at + 1)] = numerators[static_cast<std::size_t>(c)];
      ++at;
    }
  return key;
}

// The edgewise subdivision of the Kuhn simplex {k >= y1 >= y2 >= y3 >= 0}: the Freudenthal
// simplices of the unit cubes of [0, k]^3 that lie in it (k^3 of them), as lattice points y.
std::vector<std::array<Eigen::Vector3i, 4>> edgewise_subdivision(int k) {
  std::vector<std::array<Eigen::Vector3i, 4>> simplices;
  std::array<int, 3> order{0, 1, 2};
  auto in_simplex = [k](const Eigen::Vector3i& y) { return k >= y[0] && y[0] >= y[1] && y[1] >= y[2] && y[2] >= 0; };
  for (int a = 0; a < k; ++a)
    for (int b = 0; b < k; ++b)
      for (int c = 0; c < k; ++c) {
        order = {0, 1, 2};
        do {
          std::array<Eigen::Vector3i, 4> s;
          s[0] = Eigen::Vector3i(a, b, c);
          for (int m = 0; m < 3; ++m) s[static_cast<std::size_t>(m + 1)] = s[static_cast<std::size_t>(m)] + Eigen::Vector3i::Unit(order[static_cast<std::size_t>(m)]);
          if (std::all_of(s.begin(), s.end(), in_simplex)) simplices.push_back(s);
        } while (std::next_permutation(order.begin(), order.end()));
      }
  return simplices;
}

}  // namespace

SimplexLattice simplex_lattice(const TetrahedralMesh& domain, int k) {
  SimplexLattice lattice;
  lattice.subdivisions = k;
  const std::vector<std::array<Eigen::Vector3i, 4>> pieces = edgewise_subdivision(k);
  std::map<LatticeKey, std::int64_t> ids;
  lattice.tetrahedra.reserve(domain.tetrahedra.size() * pieces.size());
  for (const std::array<int, 4>& tet : domain.tetrahedra) {
    std::array<int, 4> w = tet;
    std::sort(w.begin(), w.end());
    const auto P = [&](int c) -> const Eigen::Vector3d& { return domain.points[static_cast<std::size_t>(w[static_cast<std::size_t>(c)])]; };
    for (const auto& piece : pieces) {
      std::array<std::int64_t, 4> corners;
      for (int c = 0; c < 4; ++c) {
        const Eigen::Vector3i& y = piece[static_cast<std::size_t>(c)];
        const std::array<int, 4> numerators{k - y[0], y[0] - y[1], y[1] - y[2], y[2]};
        const auto [it, added] = ids.emplace(lattice_key(w, numerators), static_cast<std::int64_t>(lattice.points.size()));
        if (added) {
          Eigen::Vector3d x = Eigen::Vector3d::Zero();
          for (int m = 0; m < 4; ++m) x += numerators[static_cast<std::size_t>(m)] * P(m);
          lattice.points.push_back(x / k);
        }
        corners[static_cast<std::size_t>(c)] = it->second;
      }
      lattice.tetrahedra.push_back(corners);
    }
  }
  return lattice;
}

}  // namespace volspline
