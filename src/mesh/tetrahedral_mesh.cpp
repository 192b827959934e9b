#include "volspline/mesh/tetrahedral_mesh.h"

#include <algorithm>
#include <cmath>
#include <string>
#include <tuple>

#include <Eigen/Geometry>

#include "exact_orientation.h"
#include "volspline/core/error.h"

namespace volspline {
namespace {

std::string tetrahedron_name(std::size_t t) { return "tetrahedra[" + std::to_string(t) + "]"; }

std::string corners_text(const std::array<int, 4>& t) {
  return "(" + std::to_string(t[0]) + ", " + std::to_string(t[1]) + ", " + std::to_string(t[2]) + ", " +
         std::to_string(t[3]) + ")";
}

// One outward face of one tetrahedron, keyed by its sorted vertices; `parity` is that of the
// permutation from the outward order to the sorted one, so two tetrahedra on opposite sides of a
// shared face give opposite parities.
struct FaceRecord {
  std::array<int, 3> key;
  int tetrahedron;
  int opposite_corner;
  bool parity;
  bool operator<(const FaceRecord& o) const {
    return std::tie(key, tetrahedron, opposite_corner) < std::tie(o.key, o.tetrahedron, o.opposite_corner);
  }
};

std::vector<FaceRecord> face_records(const TetrahedralMesh& mesh) {
  std::vector<FaceRecord> faces;
  faces.reserve(4 * mesh.tetrahedra.size());
  for (std::size_t t = 0; t < mesh.tetrahedra.size(); ++t) {
    for (int f = 0; f < 4; ++f) {
      std::array<int, 3> v;
      for (int k = 0; k < 3; ++k) v[k] = mesh.tetrahedra[t][kOutwardTetrahedronFaces[f][k]];
      bool parity = false;
      // Bubble sort of three, counting swaps.
      for (int pass = 0; pass < 2; ++pass) {
        for (int k = 0; k + 1 < 3 - pass; ++k) {
          if (v[k] > v[k + 1]) {
            std::swap(v[k], v[k + 1]);
            parity = !parity;
          }
        }
      }
      faces.push_back({v, static_cast<int>(t), f, parity});
    }
  }
  std::sort(faces.begin(), faces.end());
  return faces;
}

void check_points_finite(const TetrahedralMesh& mesh) {
  for (std::size_t i = 0; i < mesh.points.size(); ++i) {
    if (!mesh.points[i].allFinite()) {
      throw InvalidInput("coordinate is not finite", "points[" + std::to_string(i) + "]");
    }
  }
}

void check_indices(const TetrahedralMesh& mesh, std::size_t t) {
  const auto& tet = mesh.tetrahedra[t];
  for (int k = 0; k < 4; ++k) {
    if (tet[k] < 0 || static_cast<std::size_t>(tet[k]) >= mesh.points.size()) {
      throw InvalidInput("corner " + std::to_string(k) + " is point " + std::to_string(tet[k]) + ", not one of the " +
                             std::to_string(mesh.points.size()) + " points",
                         tetrahedron_name(t));
    }
  }
  for (int a = 0; a < 4; ++a) {
    for (int b = a + 1; b < 4; ++b) {
      if (tet[a] == tet[b]) {
        throw InvalidInput("corners " + std::to_string(a) + " and " + std::to_string(b) + " are the same point " +
                               std::to_string(tet[a]),
                           tetrahedron_name(t));
      }
    }
  }
}

int tetrahedron_orientation(const TetrahedralMesh& mesh, const std::array<int, 4>& t) {
  return exact::orientation(mesh.points[t[0]], mesh.points[t[1]], mesh.points[t[2]], mesh.points[t[3]]);
}

[[noreturn]] void throw_degenerate(const TetrahedralMesh& mesh, std::size_t t) {
  throw InvalidInput("degenerate: its corners " + corners_text(mesh.tetrahedra[t]) + " are coplanar (zero volume)",
                     tetrahedron_name(t));
}

}  // namespace

std::vector<BoundaryFace> boundary_faces(const TetrahedralMesh& mesh) {
  const std::vector<FaceRecord> faces = face_records(mesh);
  std::vector<BoundaryFace> boundary;
  for (std::size_t i = 0; i < faces.size();) {
    std::size_t j = i + 1;
    while (j < faces.size() && faces[j].key == faces[i].key) ++j;
    if (j == i + 1) {
      const auto& tet = mesh.tetrahedra[faces[i].tetrahedron];
      const auto& local = kOutwardTetrahedronFaces[faces[i].opposite_corner];
      boundary.push_back({{tet[local[0]], tet[local[1]], tet[local[2]]}, faces[i].tetrahedron, faces[i].opposite_corner});
    }
    i = j;
  }
  std::sort(boundary.begin(), boundary.end(), [](const BoundaryFace& a, const BoundaryFace& b) {
    return std::tie(a.tetrahedron, a.opposite_corner) < std::tie(b.tetrahedron, b.opposite_corner);
  });
  return boundary;
}

std::vector<bool> boundary_vertices(const TetrahedralMesh& mesh) {
  std::vector<bool> on_boundary(mesh.points.size(), false);
  for (const BoundaryFace& f : boundary_faces(mesh)) {
    for (int v : f.vertices) on_boundary[v] = true;
  }
  return on_boundary;
}

void orient_positively(TetrahedralMesh& mesh) {
  check_points_finite(mesh);
  for (std::size_t t = 0; t < mesh.tetrahedra.size(); ++t) {
    check_indices(mesh, t);
    const int sign = tetrahedron_orientation(mesh, mesh.tetrahedra[t]);
    if (sign == 0) throw_degenerate(mesh, t);
    if (sign < 0) std::swap(mesh.tetrahedra[t][2], mesh.tetrahedra[t][3]);
  }
}

void validate_tetrahedral_mesh(const TetrahedralMesh& mesh) {
  if (mesh.tetrahedra.empty()) throw InvalidInput("a tetrahedral mesh needs at least one tetrahedron", "tetrahedra");
  check_points_finite(mesh);
  std::vector<bool> used(mesh.points.size(), false);
  for (std::size_t t = 0; t < mesh.tetrahedra.size(); ++t) {
    check_indices(mesh, t);
    const int sign = tetrahedron_orientation(mesh, mesh.tetrahedra[t]);
    if (sign == 0) throw_degenerate(mesh, t);
    if (sign < 0) {
      throw InvalidInput("negatively oriented: det[b-a, c-a, d-a] < 0 for its corners " +
                             corners_text(mesh.tetrahedra[t]) + " (orient_positively swaps two corners)",
                         tetrahedron_name(t));
    }
    for (int v : mesh.tetrahedra[t]) used[v] = true;
  }
  const std::vector<FaceRecord> faces = face_records(mesh);
  for (std::size_t i = 0; i < faces.size();) {
    std::size_t j = i + 1;
    while (j < faces.size() && faces[j].key == faces[i].key) ++j;
    const auto& key = faces[i].key;
    const std::string face = "face (" + std::to_string(key[0]) + ", " + std::to_string(key[1]) + ", " +
                             std::to_string(key[2]) + ")";
    if (j - i > 2) {
      throw InvalidInput("its " + face + " is shared by " + std::to_string(j - i) + " tetrahedra (also " +
                             tetrahedron_name(faces[i + 1].tetrahedron) + "); a proper mesh shares a face by at most two",
                         tetrahedron_name(faces[i].tetrahedron));
    }
    if (j - i == 2 && faces[i].parity == faces[i + 1].parity) {
      throw InvalidInput("it overlaps " + tetrahedron_name(faces[i + 1].tetrahedron) + ": both lie on the same side of their shared " +
                             face,
                         tetrahedron_name(faces[i].tetrahedron));
    }
    i = j;
  }
  const auto unused = std::find(used.begin(), used.end(), false);
  if (unused != used.end()) {
    throw InvalidInput("no tetrahedron uses this point", "points[" + std::to_string(unused - used.begin()) + "]");
  }
}

double tetrahedral_mesh_volume(const TetrahedralMesh& mesh) {
  double volume = 0;
  for (const auto& t : mesh.tetrahedra) {
    const Eigen::Vector3d& a = mesh.points[t[0]];
    volume += (mesh.points[t[1]] - a).cross(mesh.points[t[2]] - a).dot(mesh.points[t[3]] - a);
  }
  return volume / 6;
}

std::vector<int> tetrahedron_parts(const TetrahedralMesh& mesh) {
  // Union-find over the points; a tetrahedron joins its four corners.
  std::vector<int> parent(mesh.points.size());
  for (std::size_t i = 0; i < parent.size(); ++i) parent[i] = static_cast<int>(i);
  const auto root = [&](int v) {
    while (parent[static_cast<std::size_t>(v)] != v) {
      parent[static_cast<std::size_t>(v)] = parent[static_cast<std::size_t>(parent[static_cast<std::size_t>(v)])];
      v = parent[static_cast<std::size_t>(v)];
    }
    return v;
  };
  for (const std::array<int, 4>& t : mesh.tetrahedra)
    for (int c = 1; c < 4; ++c) {
      const int a = root(t[0]), b = root(t[static_cast<std::size_t>(c)]);
      if (a != b) parent[static_cast<std::size_t>(std::max(a, b))] = std::min(a, b);
    }
  std::vector<int> part_of_root(mesh.points.size(), -1);
  std::vector<int> parts(mesh.tetrahedra.size());
  int next = 0;
  for (std::size_t t = 0; t < mesh.tetrahedra.size(); ++t) {
    int& p = part_of_root[static_cast<std::size_t>(root(mesh.tetrahedra[t][0]))];
    if (p < 0) p = next++;
    parts[t] = p;
  }
  return parts;
}

}  // namespace volspline
