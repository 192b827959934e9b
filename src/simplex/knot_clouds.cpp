#include "volspline/simplex/knot_clouds.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <deque>
#include <limits>
#include <numbers>
#include <optional>
#include <string>

#include <CGAL/Gmpzf.h>
#include <CGAL/QP_functions.h>
#include <CGAL/QP_models.h>
#include <Eigen/Geometry>

#include "../mesh/exact_orientation.h"
#include "volspline/core/error.h"
#include "volspline/core/format.h"
#include "volspline/mesh/tetrahedron_locator.h"

namespace volspline {
namespace {

using exact::Point;

constexpr std::array<char, 4> kCornerNames{'p', 'q', 'r', 's'};

std::string tetrahedron_name(std::size_t t) { return "tetrahedra[" + std::to_string(t) + "]"; }

std::string point_text(const Eigen::Vector3d& p) {
  return "(" + format_double(p.x()) + ", " + format_double(p.y()) + ", " + format_double(p.z()) + ")";
}

// The distinct face planes of those sub-tetrahedra: the face opposite corner m with knot
// indices (the other three corners') summing to at most n. Every sub-tetrahedron having that
// face puts a knot of corner m on the same side of it once all are positively oriented, so the
// intersection of the sub-tetrahedra is the intersection of these half-spaces.
struct HalfSpace {
  int corner;                  // m: the slot the free point takes
  std::array<int, 4> indices;  // knot index per corner; indices[m] unused
};

std::vector<HalfSpace> half_spaces(int n) {
  std::vector<HalfSpace> result;
  for (int m = 0; m < 4; ++m) {
    for (const auto& sub : knot_tetrahedron_indices(n)) {
      if (sub[m] != 0) continue;
      result.push_back({m, sub});
    }
  }
  return result;
}

// A fixed, deterministic rotation per vertex (Shoemake's uniform quaternion from a hash of the
// index), so that clouds of neighbouring vertices do not repeat one pattern: repeated patterns
// make many knot quadruples coplanar, which the spline tolerates but generic knots avoid.
Eigen::Matrix3d vertex_rotation(int vertex) {
  std::uint64_t z = static_cast<std::uint64_t>(vertex) + 0x9e3779b97f4a7c15ULL;
  z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ULL;
  z = (z ^ (z >> 27)) * 0x94d049bb133111ebULL;
  z ^= z >> 31;
  const double u1 = double(z & 0x1fffff) / double(1 << 21);
  const double u2 = double((z >> 21) & 0x1fffff) / double(1 << 21);
  const double u3 = double((z >> 42) & 0x1fffff) / double(1 << 21);
  const double two_pi = 2 * std::numbers::pi;
  const Eigen::Quaterniond q(std::sqrt(u1) * std::cos(two_pi * u3), std::sqrt(1 - u1) * std::sin(two_pi * u2),
                             std::sqrt(1 - u1) * std::cos(two_pi * u2), std::sqrt(u1) * std::sin(two_pi * u3));
  return q.normalized().toRotationMatrix();
}

// n well-spread unit directions: the spherical Fibonacci points (none antipodal, so no three
// knots of a cloud are collinear with its vertex).
std::vector<Eigen::Vector3d> spread_directions(int n) {
  std::vector<Eigen::Vector3d> d;
  const double golden_angle = std::numbers::pi * (3 - std::sqrt(5.0));
  // The first n of n + 1 spherical Fibonacci points: the n points alone are symmetric (z_i =
  // −z_{n−1−i}, angles averaging to the middle one's), which for odd n puts the vertex and three
  // of its sub-knots on one plane, a flat four with 1/|det| ~ 1e20 (simplex splines at knots).
  for (int i = 0; i < n; ++i) {
    const double z = 1 - (2.0 * i + 1) / (n + 1);
    const double r = std::sqrt(std::max(0.0, 1 - z * z));
    d.emplace_back(r * std::cos(golden_angle * i), r * std::sin(golden_angle * i), z);
  }
  return d;
}

// The knots as CGAL points, cloud after cloud.
struct CloudPoints {
  int degree;
  std::vector<Point> points;
  const Point& knot(int vertex, int l) const { return points[static_cast<std::size_t>(vertex) * (degree + 1) + l]; }
};

enum class Violation { kNone, kDegenerate, kInverted, kEmptyIntersection };

struct TetrahedronCheck {
  Violation violation = Violation::kNone;
  std::array<int, 4> sub{};  // the offending sub-tetrahedron for kDegenerate / kInverted
};

// The point of half-space h with `x` in its free slot.
int half_space_sign(const CloudPoints& clouds, const std::array<int, 4>& tet, const HalfSpace& h, const Point& x) {
  std::array<const Point*, 4> corners;
  for (int c = 0; c < 4; ++c) corners[c] = c == h.corner ? &x : &clouds.knot(tet[c], h.indices[c]);
  return exact::orientation(*corners[0], *corners[1], *corners[2], *corners[3]);
}

// Exact 3-vectors for the linear programme.
using Exact = CGAL::Gmpzf;
struct ExactVector {
  Exact x, y, z;
};
ExactVector exact_vector(const Point& p) { return {Exact(p.x()), Exact(p.y()), Exact(p.z())}; }
ExactVector operator-(const ExactVector& a, const ExactVector& b) { return {a.x - b.x, a.y - b.y, a.z - b.z}; }
Exact determinant(const ExactVector& a, const ExactVector& b, const ExactVector& c) {
  return a.x * (b.y * c.z - b.z * c.y) - a.y * (b.x * c.z - b.z * c.x) + a.z * (b.x * c.y - b.y * c.x);
}
Exact orientation_determinant(const std::array<ExactVector, 4>& v) {
  return determinant(v[1] - v[0], v[2] - v[0], v[3] - v[0]);
}

// Eq. 3 decided exactly: maximise s subject to f_h(x) >= s for every half-space h, where
// f_h(x) = det of the half-space's face with x in the free slot (affine in x), and s <= 1. The
// common interior is non-empty iff the optimum is positive.
bool common_interior_is_nonempty(const CloudPoints& clouds, const std::array<int, 4>& tet,
                                 const std::vector<HalfSpace>& spaces) {
  // Variables x0, x1, x2 free, s (index 3) <= 1; constraints -g.x + s <= h.
  CGAL::Quadratic_program<Exact> lp(CGAL::SMALLER, false, Exact(0), false, Exact(0));
  const std::array<ExactVector, 4> unit{{{Exact(0), Exact(0), Exact(0)},
                                         {Exact(1), Exact(0), Exact(0)},
                                         {Exact(0), Exact(1), Exact(0)},
                                         {Exact(0), Exact(0), Exact(1)}}};
  for (std::size_t i = 0; i < spaces.size(); ++i) {
    const HalfSpace& h = spaces[i];
    std::array<ExactVector, 4> v;
    for (int c = 0; c < 4; ++c) {
      if (c != h.corner) v[c] = exact_vector(clouds.knot(tet[c], h.indices[c]));
    }
    std::array<Exact, 4> value;  // f at 0, e_x, e_y, e_z
    for (int e = 0; e < 4; ++e) {
      v[h.corner] = unit[e];
      value[e] = orientation_determinant(v);
    }
    const int row = static_cast<int>(i);
    for (int k = 0; k < 3; ++k) lp.set_a(k, row, -(value[k + 1] - value[0]));
    lp.set_a(3, row, Exact(1));
    lp.set_b(row, value[0]);
  }
  lp.set_u(3, true, Exact(1));
  lp.set_c(3, Exact(-1));
  const auto solution = CGAL::solve_linear_program(lp, Exact());
  return solution.is_optimal() && CGAL::is_negative(solution.objective_value());
}

bool is_common_interior_point(const CloudPoints& clouds, const std::array<int, 4>& tet,
                              const std::vector<HalfSpace>& spaces, const Point& x) {
  for (const auto& h : spaces) {
    if (half_space_sign(clouds, tet, h, x) <= 0) return false;
  }
  return true;
}

// A candidate interior point by the relaxation method for linear inequalities (Agmon;
// Motzkin–Schoenberg 1954): from `start`, repeatedly reflect-with-overshoot the point across the
// most violated half-space (in doubles, unit normals). For an intersection with interior it
// reaches a point inside in few steps; the caller certifies it exactly. nullopt if no candidate
// is found within the step budget.
std::optional<Point> relaxation_witness(const CloudPoints& clouds, const std::array<int, 4>& tet,
                                        const std::vector<HalfSpace>& spaces, const Point& start) {
  struct Plane {
    Eigen::Vector3d normal;  // unit, pointing into the half-space
    Eigen::Vector3d origin;
  };
  std::vector<Plane> planes;
  planes.reserve(spaces.size());
  const auto vec = [](const Point& p) { return Eigen::Vector3d(p.x(), p.y(), p.z()); };
  for (const auto& h : spaces) {
    std::array<Eigen::Vector3d, 3> fixed;
    int f = 0;
    for (int c = 0; c < 4; ++c) {
      if (c != h.corner) fixed[f++] = vec(clouds.knot(tet[c], h.indices[c]));
    }
    // orientation with x in slot m = (-1)^(3-m) ((B-A) x (C-A)) . (x - A), (A, B, C) the other
    // three slots in order: moving x to the last slot takes 3 - m transpositions.
    Eigen::Vector3d normal = (fixed[1] - fixed[0]).cross(fixed[2] - fixed[0]);
    if ((3 - h.corner) % 2 == 1) normal = -normal;
    const double length = normal.norm();
    if (!(length > 0) || !std::isfinite(length)) return std::nullopt;
    planes.push_back({normal / length, fixed[0]});
  }
  Eigen::Vector3d x = vec(start);
  constexpr int kSteps = 200;
  constexpr double kOvershoot = 1.9;  // in (0, 2): Agmon's relaxation parameter
  for (int step = 0; step < kSteps; ++step) {
    double worst = std::numeric_limits<double>::infinity();
    const Plane* violated = nullptr;
    for (const Plane& plane : planes) {
      const double value = plane.normal.dot(x - plane.origin);
      if (value < worst) {
        worst = value;
        violated = &plane;
      }
    }
    if (worst > 0) return Point(x.x(), x.y(), x.z());
    x -= kOvershoot * worst * violated->normal;
  }
  return std::nullopt;
}

TetrahedronCheck check_tetrahedron(const CloudPoints& clouds, const std::array<int, 4>& tet,
                                   const std::vector<std::array<int, 4>>& subs, const std::vector<HalfSpace>& spaces,
                                   bool decide_exactly) {
  for (const auto& sub : subs) {
    const int sign = exact::orientation(clouds.knot(tet[0], sub[0]), clouds.knot(tet[1], sub[1]),
                                        clouds.knot(tet[2], sub[2]), clouds.knot(tet[3], sub[3]));
    if (sign <= 0) return {sign == 0 ? Violation::kDegenerate : Violation::kInverted, sub};
  }
  // Certificates: a point strictly inside every half-space, tested exactly (a rounded point is
  // as good a witness as an exact one). First I's centroid; where that fails, a point found by
  // the relaxation method; only where both fail, the exact linear programme.
  const Point centroid = CGAL::centroid(clouds.knot(tet[0], 0), clouds.knot(tet[1], 0), clouds.knot(tet[2], 0),
                                        clouds.knot(tet[3], 0));
  if (is_common_interior_point(clouds, tet, spaces, centroid)) return {};
  if (decide_exactly) {
    if (const auto witness = relaxation_witness(clouds, tet, spaces, centroid);
        witness && is_common_interior_point(clouds, tet, spaces, *witness)) {
      return {};
    }
    if (common_interior_is_nonempty(clouds, tet, spaces)) return {};
  }
  return {Violation::kEmptyIntersection, {}};
}

std::string knots_text(const KnotClouds& clouds, const std::array<int, 4>& tet, const std::array<int, 4>& sub) {
  std::string text;
  for (int c = 0; c < 4; ++c) {
    if (c > 0) text += ", ";
    text += std::string(1, kCornerNames[c]) + "_" + std::to_string(sub[c]) + " = " +
            point_text(clouds.cloud(tet[c])[sub[c]]);
  }
  return text;
}

InvalidInput tetrahedron_error(const KnotClouds& clouds, const TetrahedralMesh& domain, std::size_t t,
                               const TetrahedronCheck& check) {
  const auto& tet = domain.tetrahedra[t];
  const int n = clouds.degree;
  const std::string vertices = "(p, q, r, s) = points " + std::to_string(tet[0]) + ", " + std::to_string(tet[1]) +
                               ", " + std::to_string(tet[2]) + ", " + std::to_string(tet[3]);
  switch (check.violation) {
    case Violation::kDegenerate:
    case Violation::kInverted:
      return InvalidInput(
          "the knot tetrahedron [" + knots_text(clouds, tet, check.sub) + "] of " + vertices + " is " +
              (check.violation == Violation::kDegenerate ? "degenerate (its knots are coplanar)"
                                                         : "oriented opposite to the tetrahedron") +
              "; §3.2 needs every [p_i, q_j, r_k, s_l] with i+j+k+l <= " + std::to_string(n) +
              " non-degenerate with the tetrahedron's orientation",
          tetrahedron_name(t));
    case Violation::kEmptyIntersection: {
      std::string knots;
      for (int c = 0; c < 4; ++c) {
        for (int l = 0; l <= n; ++l) {
          knots += std::string(knots.empty() ? "" : ", ") + kCornerNames[c] + "_" + std::to_string(l) + " = " +
                   point_text(clouds.cloud(tet[c])[l]);
        }
      }
      return InvalidInput("the knot tetrahedra [p_i, q_j, r_k, s_l], i+j+k+l <= " + std::to_string(n) + ", of " +
                              vertices + " have no common interior point (eq. 3); knots " + knots,
                          tetrahedron_name(t));
    }
    case Violation::kNone:
      break;
  }
  return InvalidInput("internal: no violation", tetrahedron_name(t));
}

// Where the sub-knots of boundary vertices must lie outside Ω: for each boundary vertex, one
// boundary face (and its tetrahedron) to name in errors.
struct BoundaryVertex {
  int vertex;
  BoundaryFace face;
};

std::vector<BoundaryVertex> boundary_vertex_faces(const TetrahedralMesh& domain,
                                                  const std::vector<BoundaryFace>& faces) {
  std::vector<int> face_of(domain.points.size(), -1);
  for (std::size_t f = 0; f < faces.size(); ++f) {
    for (int v : faces[f].vertices) {
      if (face_of[v] < 0) face_of[v] = static_cast<int>(f);
    }
  }
  std::vector<BoundaryVertex> result;
  for (std::size_t v = 0; v < face_of.size(); ++v) {
    if (face_of[v] >= 0) result.push_back({static_cast<int>(v), faces[face_of[v]]});
  }
  return result;
}

// Point location in the part of Ω (tetrahedron_parts) that holds each vertex: a domain of parts
// that touch along an interface without sharing points is one spline per part, so a boundary
// vertex's sub-knots must lie outside its own part (§3.2 per part) and may lie in another.
class KnotPartLocators {
 public:
  explicit KnotPartLocators(const TetrahedralMesh& domain) {
    const std::vector<int> parts = tetrahedron_parts(domain);
    const int count = parts.empty() ? 0 : *std::max_element(parts.begin(), parts.end()) + 1;
    part_of_point_.assign(domain.points.size(), 0);
    meshes_.resize(static_cast<std::size_t>(count));
    tetrahedra_.resize(static_cast<std::size_t>(count));
    std::vector<int> local(domain.points.size(), -1);  // a point's index in its part's mesh
    for (std::size_t t = 0; t < parts.size(); ++t) {
      const auto p = static_cast<std::size_t>(parts[t]);
      std::array<int, 4> tet{};
      for (int c = 0; c < 4; ++c) {
        const auto v = static_cast<std::size_t>(domain.tetrahedra[t][static_cast<std::size_t>(c)]);
        if (local[v] < 0) {
          local[v] = static_cast<int>(meshes_[p].points.size());
          meshes_[p].points.push_back(domain.points[v]);
        }
        tet[static_cast<std::size_t>(c)] = local[v];
        part_of_point_[v] = parts[t];
      }
      meshes_[p].tetrahedra.push_back(tet);
      tetrahedra_[p].push_back(static_cast<int>(t));
    }
    for (const TetrahedralMesh& m : meshes_) locators_.emplace_back(m);
  }
  // The tetrahedron (of the whole domain) of `vertex`'s part whose closed region holds x, or -1.
  int locate(int vertex, const Eigen::Vector3d& x) const {
    const auto p = static_cast<std::size_t>(part_of_point_[static_cast<std::size_t>(vertex)]);
    const int t = locators_[p].locate(x);
    return t < 0 ? -1 : tetrahedra_[p][static_cast<std::size_t>(t)];
  }

 private:
  std::vector<int> part_of_point_;
  std::vector<TetrahedralMesh> meshes_;  // each part's tetrahedra and points
  std::vector<std::vector<int>> tetrahedra_;
  std::deque<TetrahedronLocator> locators_;  // they point into meshes_, which no longer grows
};

// The first sub-knot l >= 1 of `vertex` that lies in its part of Ω (closed), and the tetrahedron
// holding it.
std::optional<std::pair<int, int>> sub_knot_inside(const KnotPartLocators& locator, const KnotClouds& clouds,
                                                   int vertex) {
  for (int l = 1; l <= clouds.degree; ++l) {
    const int t = locator.locate(vertex, clouds.cloud(vertex)[l]);
    if (t >= 0) return std::pair{l, t};
  }
  return std::nullopt;
}

InvalidInput outside_error(const KnotClouds& clouds, const BoundaryVertex& b, int l, int holder) {
  const auto& f = b.face.vertices;
  return InvalidInput("its boundary face (" + std::to_string(f[0]) + ", " + std::to_string(f[1]) + ", " +
                          std::to_string(f[2]) + ") has the knot t_" + std::to_string(l) + " = " +
                          point_text(clouds.cloud(b.vertex)[l]) + " of point " + std::to_string(b.vertex) +
                          " inside Ω (in " + tetrahedron_name(holder) +
                          "); §3.2 needs the knots of boundary faces outside Ω",
                      tetrahedron_name(b.face.tetrahedron));
}

void check_degree(int degree) {
  if (degree < 0 || degree > kMaxKnotCloudDegree) {
    throw InvalidInput("degree " + std::to_string(degree) + " is outside 0.." + std::to_string(kMaxKnotCloudDegree),
                       "degree");
  }
}

CloudPoints cloud_points(const KnotClouds& clouds) {
  CloudPoints result{clouds.degree, {}};
  result.points.reserve(clouds.knots.size());
  for (const auto& k : clouds.knots) result.points.push_back(exact::to_cgal(k));
  return result;
}

// The outward pseudo-normal of each boundary vertex: the angle-weighted sum of the unit normals
// of its boundary faces (Thürmer–Wüthrich), the direction that points out of Ω at smooth points
// and into the exterior cone at convex edges and corners.
std::vector<Eigen::Vector3d> pseudo_normals(const TetrahedralMesh& domain, const std::vector<BoundaryFace>& faces) {
  std::vector<Eigen::Vector3d> normal(domain.points.size(), Eigen::Vector3d::Zero());
  for (const BoundaryFace& f : faces) {
    const Eigen::Vector3d& a = domain.points[f.vertices[0]];
    const Eigen::Vector3d& b = domain.points[f.vertices[1]];
    const Eigen::Vector3d& c = domain.points[f.vertices[2]];
    const Eigen::Vector3d n = (b - a).cross(c - a).normalized();
    const std::array<const Eigen::Vector3d*, 3> corner{&a, &b, &c};
    for (int k = 0; k < 3; ++k) {
      const Eigen::Vector3d u = *corner[(k + 1) % 3] - *corner[k];
      const Eigen::Vector3d w = *corner[(k + 2) % 3] - *corner[k];
      const double angle = std::atan2(u.cross(w).norm(), u.dot(w));
      normal[f.vertices[k]] += angle * n;
    }
  }
  return normal;
}

}  // namespace

std::vector<std::array<int, 4>> knot_tetrahedron_indices(int degree) {
  if (degree < 0) throw InvalidInput("degree " + std::to_string(degree) + " is negative", "degree");
  std::vector<std::array<int, 4>> result;
  for (int i = 0; i <= degree; ++i)
    for (int j = 0; i + j <= degree; ++j)
      for (int k = 0; i + j + k <= degree; ++k)
        for (int l = 0; i + j + k + l <= degree; ++l) result.push_back({i, j, k, l});
  return result;
}

KnotClouds generate_knot_clouds(const TetrahedralMesh& domain, int degree, const KnotCloudOptions& options) {
  check_degree(degree);
  if (!(options.spread > 0 && options.spread < 0.5)) {
    throw InvalidInput("spread " + format_double(options.spread) + " is outside (0, 0.5)", "spread");
  }
  if (!(options.lean >= 0 && options.lean <= 1)) throw InvalidInput("lean " + format_double(options.lean) + " is outside [0, 1]", "lean");
  validate_tetrahedral_mesh(domain);
  const int n = degree;
  const std::size_t num_points = domain.points.size();
  KnotClouds clouds;
  clouds.degree = n;
  clouds.knots.assign(num_points * (n + 1), Eigen::Vector3d::Zero());
  for (std::size_t v = 0; v < num_points; ++v) clouds.knots[v * (n + 1)] = domain.points[v];
  if (n == 0) return clouds;

  std::vector<double> shortest_edge(num_points, std::numeric_limits<double>::infinity());
  std::vector<std::vector<int>> incident(num_points);
  for (std::size_t t = 0; t < domain.tetrahedra.size(); ++t) {
    const auto& tet = domain.tetrahedra[t];
    for (int a = 0; a < 4; ++a) {
      incident[tet[a]].push_back(static_cast<int>(t));
      for (int b = a + 1; b < 4; ++b) {
        const double e = (domain.points[tet[a]] - domain.points[tet[b]]).norm();
        shortest_edge[tet[a]] = std::min(shortest_edge[tet[a]], e);
        shortest_edge[tet[b]] = std::min(shortest_edge[tet[b]], e);
      }
    }
  }
  const std::vector<BoundaryFace> faces = boundary_faces(domain);
  const std::vector<BoundaryVertex> boundary = boundary_vertex_faces(domain, faces);
  std::vector<int> boundary_slot(num_points, -1);
  for (std::size_t b = 0; b < boundary.size(); ++b) boundary_slot[boundary[b].vertex] = static_cast<int>(b);
  const std::vector<Eigen::Vector3d> normals = pseudo_normals(domain, faces);
  const std::vector<Eigen::Vector3d> directions = spread_directions(n);

  std::vector<int> halvings(num_points, 0);
  // Sub-knot l at distance spread * e * (n + l) / (2n): distinct distances, so no two sub-knots
  // of a cloud are images of each other under the cloud's symmetry. A boundary vertex's
  // sub-knots lean from the outward pseudo-normal N by tan(angle) = options.lean / 2^halvings
  // around it, so they stay in the exterior cone of edges and corners of up to about 53°
  // between N and the faces, and leave N as the cone narrows with each halving.
  const auto place = [&](int v) {
    const double scale = std::ldexp(options.spread * shortest_edge[v], -halvings[v]);
    const Eigen::Vector3d& p = domain.points[v];
    const Eigen::Matrix3d rotation = vertex_rotation(v);
    Eigen::Vector3d normal = normals[v];
    const bool on_boundary = boundary_slot[v] >= 0;
    if (on_boundary && !(normal.norm() > 0)) {
      // Angles summing to a zero vector: a non-manifold boundary vertex. The direction away
      // from the centroid of its tetrahedra is tried instead (the checks decide).
      Eigen::Vector3d centre = Eigen::Vector3d::Zero();
      for (int t : incident[v])
        for (int c : domain.tetrahedra[t]) centre += domain.points[c];
      normal = p - centre / (4.0 * incident[v].size());
    }
    normal.normalize();
    const double lean = std::ldexp(options.lean, -halvings[v]);
    for (int l = 1; l <= n; ++l) {
      const double distance = scale * (n + l) / (2.0 * n);
      Eigen::Vector3d d;
      if (on_boundary) {
        const Eigen::Vector3d around = rotation * directions[l - 1];
        Eigen::Vector3d tangential = around - around.dot(normal) * normal;
        if (tangential.norm() > 0) tangential.normalize();
        d = (normal + lean * tangential).normalized();
      } else {
        d = rotation * directions[l - 1];
      }
      clouds.knots[static_cast<std::size_t>(v) * (n + 1) + l] = p + distance * d;
    }
  };
  for (std::size_t v = 0; v < num_points; ++v) place(static_cast<int>(v));

  const KnotPartLocators locator(domain);
  const auto subs = knot_tetrahedron_indices(n);
  const auto spaces = half_spaces(n);
  std::vector<int> dirty_tetrahedra(domain.tetrahedra.size());
  for (std::size_t t = 0; t < dirty_tetrahedra.size(); ++t) dirty_tetrahedra[t] = static_cast<int>(t);
  std::vector<int> dirty_boundary;
  for (const auto& b : boundary) dirty_boundary.push_back(b.vertex);
  std::vector<char> marked(num_points, 0);
  std::vector<char> tetrahedron_marked(domain.tetrahedra.size(), 0);
  while (!dirty_tetrahedra.empty() || !dirty_boundary.empty()) {
    CloudPoints points = cloud_points(clouds);
    std::vector<int> to_halve;
    const auto mark = [&](int v) {
      if (!marked[v]) {
        marked[v] = 1;
        to_halve.push_back(v);
      }
    };
    const auto can_halve = [&](int v) { return halvings[v] < kMaxKnotCloudHalvings; };
    for (int t : dirty_tetrahedra) {
      const auto& tet = domain.tetrahedra[t];
      // The centroid certificate only: shrinking drives every knot tetrahedron towards I, which
      // holds its centroid, so clouds built here are certified without the linear programme.
      const TetrahedronCheck check = check_tetrahedron(points, tet, subs, spaces, false);
      if (check.violation == Violation::kNone) continue;
      // The corners that can still shrink do; when none can, the tetrahedron is beyond repair.
      if (std::none_of(tet.begin(), tet.end(), can_halve)) throw tetrahedron_error(clouds, domain, t, check);
      for (int v : tet) {
        if (can_halve(v)) mark(v);
      }
    }
    for (int v : dirty_boundary) {
      if (const auto inside = sub_knot_inside(locator, clouds, v)) {
        if (!can_halve(v)) throw outside_error(clouds, boundary[boundary_slot[v]], inside->first, inside->second);
        mark(v);
      }
    }
    dirty_tetrahedra.clear();
    dirty_boundary.clear();
    for (int v : to_halve) {
      marked[v] = 0;
      ++halvings[v];
      place(v);
      if (boundary_slot[v] >= 0) dirty_boundary.push_back(v);
      for (int t : incident[v]) {
        if (!tetrahedron_marked[t]) {
          tetrahedron_marked[t] = 1;
          dirty_tetrahedra.push_back(t);
        }
      }
    }
    std::sort(dirty_tetrahedra.begin(), dirty_tetrahedra.end());
    for (int t : dirty_tetrahedra) tetrahedron_marked[t] = 0;
  }
  return clouds;
}

void validate_knot_clouds(const TetrahedralMesh& domain, const KnotClouds& clouds) {
  check_degree(clouds.degree);
  const int n = clouds.degree;
  if (clouds.knots.size() != domain.points.size() * static_cast<std::size_t>(n + 1)) {
    throw InvalidInput("expected " + std::to_string(n + 1) + " knots for each of the " +
                           std::to_string(domain.points.size()) + " points (degree " + std::to_string(n) + "), got " +
                           std::to_string(clouds.knots.size()),
                       "knots");
  }
  validate_tetrahedral_mesh(domain);
  for (std::size_t i = 0; i < clouds.knots.size(); ++i) {
    const std::size_t v = i / (n + 1);
    if (!clouds.knots[i].allFinite()) throw InvalidInput("knot is not finite", "knots[" + std::to_string(i) + "]");
    if (i % (n + 1) == 0 && clouds.knots[i] != domain.points[v]) {
      throw InvalidInput("t_0 of the cloud of point " + std::to_string(v) + " is " + point_text(clouds.knots[i]) +
                             ", not the point " + point_text(domain.points[v]),
                         "knots[" + std::to_string(i) + "]");
    }
  }
  const CloudPoints points = cloud_points(clouds);
  const auto subs = knot_tetrahedron_indices(n);
  const auto spaces = half_spaces(n);
  for (std::size_t t = 0; t < domain.tetrahedra.size(); ++t) {
    const TetrahedronCheck check = check_tetrahedron(points, domain.tetrahedra[t], subs, spaces, true);
    if (check.violation != Violation::kNone) throw tetrahedron_error(clouds, domain, t, check);
  }
  if (n == 0) return;
  const KnotPartLocators locator(domain);
  for (const BoundaryVertex& b : boundary_vertex_faces(domain, boundary_faces(domain))) {
    if (const auto inside = sub_knot_inside(locator, clouds, b.vertex)) {
      throw outside_error(clouds, b, inside->first, inside->second);
    }
  }
}

}  // namespace volspline
