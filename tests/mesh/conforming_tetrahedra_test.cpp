// Conforming tetrahedra of adaptive tilings: they fill the kept boxes exactly (volumes add up) and
// meet face to face (every interior triangle is shared by exactly two tetrahedra), however
// unevenly neighbouring boxes are split.
#include "volspline/mesh/conforming_tetrahedra.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <map>
#include <random>

#include <Eigen/Geometry>

#include "volspline/core/error.h"

namespace volspline {
namespace {

// A random dyadic tiling of [0, 2^levels)^3: boxes halved along a random axis, each with
// probability `split`, down to extent 2.
std::vector<LatticeBox> random_tiling(std::mt19937& rng, int levels, double split) {
  std::vector<LatticeBox> done, todo{{{0, 0, 0}, {1 << levels, 1 << levels, 1 << levels}, true}};
  std::uniform_real_distribution<double> chance(0.0, 1.0);
  std::uniform_int_distribution<int> axis_of(0, 2);
  while (!todo.empty()) {
    LatticeBox box = todo.back();
    todo.pop_back();
    const int axis = axis_of(rng);
    const auto a = static_cast<std::size_t>(axis);
    if (box.extent[a] <= 2 || chance(rng) > split) {
      done.push_back(box);
      continue;
    }
    LatticeBox low = box, high = box;
    low.extent[a] /= 2;
    high.extent[a] /= 2;
    high.origin[a] += low.extent[a];
    todo.push_back(low);
    todo.push_back(high);
  }
  return done;
}

Eigen::Vector3d point_of(const LatticePoint& p) { return Eigen::Vector3d(static_cast<double>(p[0]), static_cast<double>(p[1]), static_cast<double>(p[2])); }

double volume_of(const LatticeBox& b) {
  return static_cast<double>(b.extent[0]) * static_cast<double>(b.extent[1]) * static_cast<double>(b.extent[2]);
}

// How many tetrahedra use each triangle (sorted point ids).
std::map<std::array<int, 3>, int> triangle_uses(const ConformingTetrahedralMesh& mesh) {
  std::map<std::array<int, 3>, int> faces;
  for (const auto& tet : mesh.tetrahedra) {
    for (int skip = 0; skip < 4; ++skip) {
      std::array<int, 3> f{};
      for (int k = 0, n = 0; k < 4; ++k) {
        if (k != skip) f[static_cast<std::size_t>(n++)] = tet[static_cast<std::size_t>(k)];
      }
      std::sort(f.begin(), f.end());
      ++faces[f];
    }
  }
  return faces;
}

// Checks volume and conformity of the tetrahedra of the kept boxes; returns the area of the
// triangles used by one tetrahedron only (the boundary of the kept region).
double expect_conforming(const std::vector<LatticeBox>& boxes) {
  const ConformingTetrahedralMesh mesh = conforming_tetrahedra(boxes);
  double kept_volume = 0;
  for (const LatticeBox& b : boxes) kept_volume += b.kept ? volume_of(b) : 0.0;
  double volume = 0;
  for (const auto& tet : mesh.tetrahedra) {
    std::array<Eigen::Vector3d, 4> x;
    for (std::size_t k = 0; k < 4; ++k) x[k] = point_of(mesh.points[static_cast<std::size_t>(tet[k])]);
    const double six = std::abs((x[1] - x[0]).dot((x[2] - x[0]).cross(x[3] - x[0])));
    EXPECT_GT(six, 0.0) << "degenerate tetrahedron";
    volume += six / 6.0;
  }
  const std::map<std::array<int, 3>, int> faces = triangle_uses(mesh);
  EXPECT_NEAR(volume, kept_volume, 1e-9 * kept_volume);
  double once = 0;
  for (const auto& [face, count] : faces) {
    EXPECT_LE(count, 2) << "a triangle shared by more than two tetrahedra";
    if (count != 1) continue;
    const Eigen::Vector3d a = point_of(mesh.points[static_cast<std::size_t>(face[0])]), b = point_of(mesh.points[static_cast<std::size_t>(face[1])]),
                          c = point_of(mesh.points[static_cast<std::size_t>(face[2])]);
    once += 0.5 * (b - a).cross(c - a).norm();
  }
  return once;
}

TEST(ConformingTetrahedra, FillAndConformOnRandomAdaptiveTilings) {
  std::mt19937 rng(7);
  for (int trial = 0; trial < 12; ++trial) {
    const std::vector<LatticeBox> boxes = random_tiling(rng, 5, 0.8);
    // All kept: the triangles used once cover the six faces of the cube [0, 32]^3 and nothing
    // else (a crack inside would add its two sides).
    EXPECT_NEAR(expect_conforming(boxes), 6.0 * 32 * 32, 1e-9);
  }
}

TEST(ConformingTetrahedra, TrianglesUsedOnceLieOnTheBoundaryOfTheKeptRegion) {
  std::mt19937 rng(19);
  for (int trial = 0; trial < 8; ++trial) {
    std::vector<LatticeBox> boxes = random_tiling(rng, 4, 0.85);
    std::bernoulli_distribution keep(0.5);
    for (LatticeBox& b : boxes) b.kept = keep(rng);
    const ConformingTetrahedralMesh mesh = conforming_tetrahedra(boxes);
    expect_conforming(boxes);
    // A triangle used once must lie in a plane of constant coordinate (a face of a kept box).
    for (const auto& [f, count] : triangle_uses(mesh)) {
      if (count != 1) continue;
      bool planar = false;
      for (std::size_t a = 0; a < 3; ++a) {
        const auto c = mesh.points[static_cast<std::size_t>(f[0])][a];
        planar = planar || (mesh.points[static_cast<std::size_t>(f[1])][a] == c && mesh.points[static_cast<std::size_t>(f[2])][a] == c);
      }
      EXPECT_TRUE(planar);
    }
  }
}

TEST(ConformingTetrahedra, NothingKeptGivesNothing) {
  std::mt19937 rng(2);
  std::vector<LatticeBox> boxes = random_tiling(rng, 3, 0.5);
  for (LatticeBox& b : boxes) b.kept = false;
  const ConformingTetrahedralMesh mesh = conforming_tetrahedra(boxes);
  EXPECT_TRUE(mesh.points.empty());
  EXPECT_TRUE(mesh.tetrahedra.empty());
}

TEST(ConformingTetrahedra, RejectOddOrEmptyExtents) {
  EXPECT_THROW(conforming_tetrahedra({{{0, 0, 0}, {2, 3, 2}, true}}), InvalidInput);
  EXPECT_THROW(conforming_tetrahedra({{{0, 0, 0}, {2, 0, 2}, true}}), InvalidInput);
  EXPECT_NO_THROW(conforming_tetrahedra({{{0, 0, 0}, {2, 4, 2}, true}}));
}

}  // namespace
}  // namespace volspline
