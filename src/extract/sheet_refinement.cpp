#include "volspline/extract/sheet_refinement.h"

#include <algorithm>
#include <array>
#include <atomic>
#include <cmath>
#include <iterator>
#include <memory>
#include <string>
#include <unordered_map>
#include <unordered_set>

#include <Eigen/LU>
#include <tbb/blocked_range.h>
#include <tbb/concurrent_unordered_map.h>
#include <tbb/parallel_for.h>
#include <tbb/parallel_sort.h>

#include "volspline/core/bucket_sort.h"
#include "volspline/core/error.h"
#include "volspline/core/exact_hash.h"
#include "volspline/mesh/mesh_checks.h"

namespace volspline {

namespace {

std::uint64_t refinement_edge_key(int p, int q) {
  return (static_cast<std::uint64_t>(std::min(p, q)) << 32) | static_cast<std::uint32_t>(std::max(p, q));
}

struct EdgeSplit {
  std::uint64_t key = 0;
  bool found = false;
  double distance = 0;
  Eigen::Vector3d position = Eigen::Vector3d::Zero();
  SheetVertex vertex;
};

// The sheets two vertices share: both on the same two (a crease edge), on one common sheet, or
// on two sheets that meet smoothly (a seam): the kind and, per end, the sheet point to use.
enum class EdgeKind { None, Crease, Sheet, Seam, Across };

bool same_sheet_point(const SheetPoint& a, const SheetPoint& b) {
  return a.sheet == b.sheet && a.triangle == b.triangle && a.parameters == b.parameters && a.normal == b.normal;
}

bool same_sheet_vertex(const SheetVertex& a, const SheetVertex& b) {
  return a.source == b.source && a.frozen == b.frozen && same_sheet_point(a.on[0], b.on[0]) && same_sheet_point(a.on[1], b.on[1]);
}

}  // namespace

// Not anonymous: SheetRefinementMemory::State holds these types.
namespace sheet_refinement_detail {

// An edge's ends by their positions, in the order of their vertex numbers (+ 0.0 makes -0 and +0
// one key).
using RefinementEdgeEnds = std::array<double, 6>;

}  // namespace sheet_refinement_detail

struct SheetRefinementMemory::State {
  struct Entry {
    SheetVertex p, q;
    bool found = false;
    double distance = 0;
    Eigen::Vector3d position = Eigen::Vector3d::Zero();
    SheetVertex vertex;
  };
  tbb::concurrent_unordered_map<sheet_refinement_detail::RefinementEdgeEnds, Entry, ExactDoublesHash> splits;
  std::atomic<std::size_t> reused{0};
};

SheetRefinementMemory::SheetRefinementMemory() : state_(std::make_unique<State>()) {}
SheetRefinementMemory::~SheetRefinementMemory() = default;
// A moved-from memory has no state; refine_to_sheets gives it an empty one.
SheetRefinementMemory::SheetRefinementMemory(SheetRefinementMemory&&) noexcept = default;
SheetRefinementMemory& SheetRefinementMemory::operator=(SheetRefinementMemory&&) noexcept = default;
std::size_t SheetRefinementMemory::size() const { return state_ ? state_->splits.size() : 0; }
std::size_t SheetRefinementMemory::reused() const { return state_ ? state_->reused.load() : 0; }

std::optional<Eigen::Vector3d> sheet_crease_point(const SheetCrossingFrom& crossing, SheetPoint& a, SheetPoint& b, const Eigen::Vector3d& x0,
                                                  const Eigen::Vector3d& direction, double reach) {
  if (!crossing || !(direction.norm() > 0) || !(reach > 0)) return std::nullopt;
  const Eigen::Vector3d d = direction.normalized();
  Eigen::Vector3d x = x0;
  for (int step = 0; step < 12; ++step) {
    std::array<Eigen::Vector3d, 2> on;
    for (int k = 0; k < 2; ++k) {
      SheetPoint& sheet = k == 0 ? a : b;
      const SheetPoint& other = k == 0 ? b : a;
      // Along the sheet's normal within the plane (the trace's normal there); where that line
      // misses the sheet (a crease along the sheet's own border, e.g. a face's edge swept, and
      // the point beyond it), along the two bisectors of the normals. A point exactly on the
      // plane of a sheet that ends at the crease, beyond its end, is crossed by no line within
      // the sheet: then the same from points a hundredth of the reach off it, one of which lies
      // within both sheets' ends (the annulus at 16 × tolerance: 440 crease cells unsnapped
      // without, 168 with).
      std::optional<SheetCrossing> c;
      Eigen::Vector3d from, to;
      const Eigen::Vector3d na = sheet.normal.normalized(), nb = other.normal.normalized();
      for (const Eigen::Vector3d& offset : {Eigen::Vector3d(Eigen::Vector3d::Zero()), Eigen::Vector3d(na + nb), Eigen::Vector3d(na - nb),
                                            Eigen::Vector3d(-na + nb), Eigen::Vector3d(-na - nb)}) {
        const Eigen::Vector3d centre = x + 0.01 * reach * offset;
        for (const Eigen::Vector3d& along : {Eigen::Vector3d(sheet.normal), Eigen::Vector3d(na - nb), Eigen::Vector3d(na + nb)}) {
          Eigen::Vector3d g = along - along.dot(d) * d;
          if (!(g.norm() > 1e-9)) continue;
          g.normalize();
          from = centre - reach * g;
          to = centre + reach * g;
          c = crossing(sheet.triangle, sheet.parameters, 0.5, from, to);
          if (c && c->lambda >= 0 && c->lambda <= 1 && !c->normal.isZero()) break;
          c.reset();
        }
        if (c) break;
      }
      if (!c) return std::nullopt;
      on[static_cast<std::size_t>(k)] = from + c->lambda * (to - from);
      sheet.parameters << c->parameters, c->extra;
      sheet.normal = c->normal.normalized();
    }
    // The two tangent planes and the plane of the section meet in one point.
    Eigen::Matrix3d m;
    m.row(0) = a.normal.transpose();
    m.row(1) = b.normal.transpose();
    m.row(2) = d.transpose();
    const Eigen::Vector3d r(a.normal.dot(on[0]), b.normal.dot(on[1]), d.dot(x0));
    const Eigen::FullPivLU<Eigen::Matrix3d> lu(m);
    if (!lu.isInvertible() || std::abs(a.normal.dot(b.normal)) > 0.999) return std::nullopt;
    const Eigen::Vector3d next = lu.solve(r);
    const double moved = (next - x).norm();
    x = next;
    if ((x - x0).norm() > 2 * reach) return std::nullopt;
    if (moved <= 1e-9 * reach && (on[0] - on[1]).norm() <= 1e-6 * reach) return x;
  }
  return std::nullopt;
}

SheetRefinementStats refine_to_sheets(TriangleMesh& mesh, std::vector<SheetVertex>& vertices, const SheetCrossingFrom& crossing,
                                      const SheetRefinementOptions& options, std::vector<std::size_t>* face_origin) {
  if (vertices.size() != mesh.num_vertices())
    throw InvalidInput("expected one sheet vertex per mesh vertex (" + std::to_string(mesh.num_vertices()) + "), got " +
                           std::to_string(vertices.size()),
                       "vertices");
  if (!(options.tolerance > 0) || !std::isfinite(options.tolerance)) throw InvalidInput("expected a positive tolerance", "tolerance");
  if (!(options.shortest_edge >= 0)) throw InvalidInput("expected shortest_edge >= 0", "shortest_edge");
  if (options.max_rounds < 0 || options.max_rounds > 60) throw InvalidInput("expected 0 to 60 rounds", "max_rounds");
  if (!(options.branch_angle_degrees >= 0 && options.branch_angle_degrees <= 90))
    throw InvalidInput("expected a branch angle of 0 to 90 degrees", "branch_angle_degrees");
  validate_mesh(mesh);
  if (options.inside && !(options.check_distance > 0))
    throw InvalidInput("expected a positive check_distance with a membership test", "check_distance");
  SheetRefinementStats stats;
  std::vector<std::size_t> origin(mesh.num_triangles());
  for (std::size_t f = 0; f < origin.size(); ++f) origin[f] = f;
  auto finish = [&] {
    if (face_origin) *face_origin = std::move(origin);
    return stats;
  };
  if (!crossing) return finish();
  if (options.memory && !options.memory->state_) options.memory->state_ = std::make_unique<SheetRefinementMemory::State>();
  // Edges found within the tolerance (or whose sheet point was not found) are not tried again:
  // their ends do not move, so neither does the answer.
  // Sorted; the edges settled in the current round are collected in `newly_settled` and merged
  // in before the next round looks.
  std::vector<std::uint64_t> settled, newly_settled, merged;
  const double seam_cos = std::cos(options.seam_angle_degrees * 3.14159265358979323846 / 180);
  const double checked_seam_cos = std::cos(80 * 3.14159265358979323846 / 180);
  struct Shared {
    EdgeKind kind = EdgeKind::None;
    SheetPoint p, q;
  };
  // Two points of one sheet lie on one branch of it unless their normals differ by more than
  // the branch angle: a sheet that crosses itself (a face sweep's fold folding over, Fig. 5's
  // ridge) makes a crease between two of its own branches, whose parameters are far apart.
  const double branch_cos = options.branch_angle_degrees > 0 ? std::cos(options.branch_angle_degrees * 3.14159265358979323846 / 180) : -1.0;
  // (A point without a normal is on every branch of its sheet.)
  const auto same_branch = [&](const SheetPoint& a, const SheetPoint& b) {
    return a.sheet >= 0 && a.sheet == b.sheet &&
           (a.normal.isZero() || b.normal.isZero() || std::abs(a.normal.normalized().dot(b.normal.normalized())) >= branch_cos);
  };
  // Two crease points on the same two sheets; where the two are one sheet's two branches, the
  // normals say which branch is which.
  const auto same_crease = [&](const SheetPoint& a0, const SheetPoint& a1, const SheetPoint& b0, const SheetPoint& b1) {
    return a0.sheet == b0.sheet && a1.sheet == b1.sheet && (a0.sheet != a1.sheet || (same_branch(a0, b0) && same_branch(a1, b1)));
  };
  auto edge_kind = [&](const SheetVertex& vp, const SheetVertex& vq) {
    Shared shared;
    const auto crease = [](const SheetVertex& v) { return v.on[0].sheet >= 0 && v.on[1].sheet >= 0; };
    if (crease(vp) && crease(vq) &&
        (same_crease(vp.on[0], vp.on[1], vq.on[0], vq.on[1]) || same_crease(vp.on[0], vp.on[1], vq.on[1], vq.on[0]))) {
      shared.kind = EdgeKind::Crease;
      return shared;
    }
    // On one branch of a common sheet: the pair whose normals agree best.
    double best = -1;
    for (const SheetPoint& a : vp.on)
      for (const SheetPoint& b : vq.on)
        if (same_branch(a, b)) {
          const double c = std::abs(a.normal.normalized().dot(b.normal.normalized()));
          if (c > best) {
            best = c;
            shared.kind = EdgeKind::Sheet;
            shared.p = a;
            shared.q = b;
          }
        }
    if (shared.kind == EdgeKind::None && !crease(vp) && !crease(vq) && vp.on[0].sheet >= 0 && vq.on[0].sheet >= 0 &&
        std::abs(vp.on[0].normal.normalized().dot(vq.on[0].normal.normalized())) >= (options.inside ? checked_seam_cos : seam_cos)) {
      shared.kind = EdgeKind::Seam;
      shared.p = vp.on[0];
      shared.q = vq.on[0];
    }
    // Across a crease that no crease point resolves (a chamfer): split where the two sheets
    // meet, checked on the boundary by the membership test.
    if (shared.kind == EdgeKind::None && options.inside && options.split_across_creases) {
      double smallest = 2;
      for (const SheetPoint& a : vp.on)
        for (const SheetPoint& b : vq.on) {
          if (a.sheet < 0 || b.sheet < 0 || same_branch(a, b)) continue;
          const double c = std::abs(a.normal.normalized().dot(b.normal.normalized()));
          if (c < smallest) {
            smallest = c;
            shared.kind = EdgeKind::Across;
            shared.p = a;
            shared.q = b;
          }
        }
    }
    return shared;
  };
  // A circular arc of chord L whose end normals differ by the angle θ stands L θ / 8 above its
  // chord.
  auto arc_deviation = [&](int p, int q, const Eigen::Vector3d& np, const Eigen::Vector3d& nq) {
    const double length = (mesh.positions[static_cast<std::size_t>(p)] - mesh.positions[static_cast<std::size_t>(q)]).norm();
    if (np.isZero() || nq.isZero()) return length;
    return length * std::acos(std::clamp(std::abs(np.normalized().dot(nq.normalized())), 0.0, 1.0)) / 8;
  };
  // A circular arc of chord L whose end normals differ by the angle θ stands L θ / 8 above its
  // chord. Edges along a sheet (or a seam) estimated at a quarter of the tolerance or less are
  // not solved for (most of a smooth boundary); the estimate misses S-shaped edges, whose
  // deviation is of third order in L.
  auto within_estimate = [&](int p, int q, const Shared& shared) {
    if (shared.kind != EdgeKind::Sheet && shared.kind != EdgeKind::Seam) return false;
    Eigen::Vector3d normal = shared.p.normal + (shared.p.normal.dot(shared.q.normal) < 0 ? -shared.q.normal : shared.q.normal);
    if (!(normal.norm() > 1e-12)) normal = shared.p.normal;
    if (!(normal.norm() > 1e-12)) return false;
    const double length = (mesh.positions[static_cast<std::size_t>(p)] - mesh.positions[static_cast<std::size_t>(q)]).norm();
    const double angle = std::acos(std::clamp(std::abs(shared.p.normal.normalized().dot(shared.q.normal.normalized())), 0.0, 1.0));
    return length * angle / 8 <= 0.25 * options.tolerance;
  };
  // Faces made in the last round (all at first): every other edge is settled, so only theirs
  // are candidates.
  std::vector<char> fresh(mesh.num_triangles(), 1);
  // Buffers of the rounds, kept (with their memory) from round to round.
  std::vector<EdgeSplit> candidates;
  std::vector<std::uint64_t> keys;
  std::vector<char> verdicts;
  std::vector<char> at_split;
  std::unordered_map<std::uint64_t, std::size_t> wanted;
  std::vector<Eigen::Vector3d> added;
  std::unordered_map<std::uint64_t, int> split_at;
  std::vector<std::array<int, 3>> triangles;
  std::vector<int> parts;
  std::vector<std::size_t> parent_face, new_origin;
  std::vector<char> split_face;
  std::unordered_set<std::uint64_t> refused;
  for (int round = 0;; ++round) {
    candidates.clear();
    {
      // The fresh faces' edges not settled yet, in key order, each classified (in parallel:
      // on the first round that is every edge of the mesh) and then counted in that order.
      keys.clear();
      for (std::size_t f = 0; f < mesh.triangles.size(); ++f) {
        if (!fresh[f]) continue;
        const auto& t = mesh.triangles[f];
        for (int j = 0; j < 3; ++j) keys.push_back(refinement_edge_key(t[static_cast<std::size_t>(j)], t[static_cast<std::size_t>((j + 1) % 3)]));
      }
      sort_keys_by_high_bits(keys, 32, mesh.num_vertices());
      keys.erase(std::unique(keys.begin(), keys.end()), keys.end());
      if (!newly_settled.empty()) {
        tbb::parallel_sort(newly_settled.begin(), newly_settled.end());
        merged.resize(settled.size() + newly_settled.size());
        std::merge(settled.begin(), settled.end(), newly_settled.begin(), newly_settled.end(), merged.begin());
        settled.swap(merged);
        newly_settled.clear();
      }
      if (!settled.empty()) {
        merged.clear();
        std::set_difference(keys.begin(), keys.end(), settled.begin(), settled.end(), std::back_inserter(merged));
        keys.swap(merged);
      }
      enum : char { kFrozen, kUnshared, kUnsharedUnresolved, kShort, kWithinEstimate, kCandidate };
      verdicts.resize(keys.size());
      tbb::parallel_for(tbb::blocked_range<std::size_t>(0, keys.size(), 1024), [&](const tbb::blocked_range<std::size_t>& range) {
        for (std::size_t i = range.begin(); i != range.end(); ++i) {
          const auto p = static_cast<int>(keys[i] >> 32), q = static_cast<int>(keys[i] & 0xffffffffu);
          const SheetVertex &vp = vertices[static_cast<std::size_t>(p)], &vq = vertices[static_cast<std::size_t>(q)];
          char& verdict = verdicts[i];
          if (vp.frozen || vq.frozen) {
            verdict = kFrozen;
            continue;
          }
          const Shared shared = edge_kind(vp, vq);
          if (shared.kind == EdgeKind::None) {
            // Across a crease that no crease point resolves (a chamfer): counted where a chord
            // of that length between those normals may stand off the boundary by more than the
            // tolerance.
            verdict = vp.on[0].sheet >= 0 && vq.on[0].sheet >= 0 && arc_deviation(p, q, vp.on[0].normal, vq.on[0].normal) > options.tolerance
                          ? kUnsharedUnresolved
                          : kUnshared;
          } else if ((mesh.positions[static_cast<std::size_t>(p)] - mesh.positions[static_cast<std::size_t>(q)]).norm() <= options.shortest_edge) {
            verdict = kShort;
          } else {
            verdict = within_estimate(p, q, shared) ? kWithinEstimate : kCandidate;
          }
        }
      });
      for (std::size_t i = 0; i < keys.size(); ++i) {
        const std::uint64_t key = keys[i];
        const char verdict = verdicts[i];
        if (verdict == kCandidate) {
          EdgeSplit e;
          e.key = key;
          candidates.push_back(e);
          continue;
        }
        newly_settled.push_back(key);
        if (verdict == kWithinEstimate) continue;
        stats.unverified_edges.push_back({static_cast<int>(key >> 32), static_cast<int>(key & 0xffffffffu)});
        if (verdict == kUnsharedUnresolved) ++stats.unresolved_edges;
      }
    }
    // The split point of candidate e, if any (e.found, e.position, e.distance, e.vertex).
    const auto split_edge = [&](EdgeSplit& e) {
      const auto p = static_cast<int>(e.key >> 32), q = static_cast<int>(e.key & 0xffffffffu);
      const SheetVertex &vp = vertices[static_cast<std::size_t>(p)], &vq = vertices[static_cast<std::size_t>(q)];
      const Eigen::Vector3d &xp = mesh.positions[static_cast<std::size_t>(p)], &xq = mesh.positions[static_cast<std::size_t>(q)];
      const double length = (xq - xp).norm();
      const Eigen::Vector3d middle = 0.5 * (xp + xq);
      const Shared shared = edge_kind(vp, vq);
      if (shared.kind == EdgeKind::Crease) {
        SheetVertex v = vp;
        const std::optional<Eigen::Vector3d> x = sheet_crease_point(crossing, v.on[0], v.on[1], middle, xq - xp, 0.5 * length);
        if (!x) return;
        e.found = true;
        e.position = *x;
        e.distance = (*x - middle).norm();
        e.vertex = v;
        return;
      }
      // The point where the ends' two sheets meet, in the plane across their crease through the
      // midpoint, if it is on the boundary (membership differs on the two sides of it along
      // one of the bisectors of the normals).
      auto split_at_crease = [&](SheetPoint a, SheetPoint b) {
        const Eigen::Vector3d across = a.normal.normalized().cross(b.normal.normalized());
        if (!(across.norm() > 1e-3)) return false;
        const std::optional<Eigen::Vector3d> x = sheet_crease_point(crossing, a, b, middle, across, 0.5 * length);
        if (!x) return false;
        bool on_boundary = false;
        for (const Eigen::Vector3d& bisector : {Eigen::Vector3d(a.normal.normalized() + b.normal.normalized()),
                                                Eigen::Vector3d(a.normal.normalized() - b.normal.normalized())}) {
          if (on_boundary || !(bisector.norm() > 1e-9)) continue;
          const Eigen::Vector3d step = options.check_distance * bisector.normalized();
          const std::optional<bool> plus = options.inside(*x + step), minus = options.inside(*x - step);
          on_boundary = plus && minus && *plus != *minus;
        }
        if (!on_boundary) return false;
        e.found = true;
        e.position = *x;
        e.distance = (*x - middle).norm();
        e.vertex.on[0] = a;
        e.vertex.on[1] = b;
        e.vertex.source = vp.source;
        return true;
      };
      if (shared.kind == EdgeKind::Across) {
        split_at_crease(shared.p, shared.q);
        return;
      }
      const SheetPoint &sp = shared.p, &sq = shared.q;
      Eigen::Vector3d normal = sp.normal + (sp.normal.dot(sq.normal) < 0 ? -sq.normal : sq.normal);
      if (!(normal.norm() > 1e-12)) normal = sp.normal;
      if (!(normal.norm() > 1e-12)) return;
      normal.normalize();
      const Eigen::Vector3d a = middle - 0.5 * length * normal, b = middle + 0.5 * length * normal;
      // One sheet: Newton from the mean of the ends' parameters. A seam between two sheets
      // that meet smoothly (patches of one surface): each end's sheet from that end.
      std::optional<SheetCrossing> c;
      SheetPoint on = sp;
      // Where the mean fails (a sheet closed on itself: a tube's seam w = 0 ~ 1, where the
      // mean lies on the far side), from each end's own parameters.
      if (shared.kind == EdgeKind::Sheet) c = crossing(sp.triangle, 0.5 * (sp.parameters + sq.parameters), 0.5, a, b);
      for (int end = 0; end < 2 && !(c && c->lambda >= 0 && c->lambda <= 1); ++end) {
        on = end == 0 ? sp : sq;
        c = crossing(on.triangle, on.parameters, 0.5, a, b);
      }
      if (!c || !(c->lambda >= 0 && c->lambda <= 1)) return;
      const Eigen::Vector3d position = a + c->lambda * (b - a);
      if (shared.kind == EdgeKind::Seam && std::abs(sp.normal.normalized().dot(sq.normal.normalized())) < seam_cos) {
        // A seam or a crease: the point must be on the boundary, not on a sheet's interior
        // part. (Checking every split alike, for sheets that run on inside the solid past
        // where another cuts them off, cost 94,000 more membership queries on Fig. 4, mostly
        // outside proofs: 7.4 s instead of 0.15 s; those edges are caught by the verification
        // of extract/image_contouring.h instead.)
        const Eigen::Vector3d step = options.check_distance * c->normal.normalized();
        const std::optional<bool> plus = options.inside(position + step), minus = options.inside(position - step);
        if (!plus || !minus || *plus == *minus) {
          if (options.split_across_creases) split_at_crease(sp, sq);
          return;
        }
      }
      e.found = true;
      e.position = position;
      on.parameters << c->parameters, c->extra;
      on.normal = c->normal;
      e.vertex.on[0] = on;
      e.vertex.source = vp.source;
      e.distance = (e.position - middle).norm();
    };
    SheetRefinementMemory::State* memory = options.memory ? options.memory->state_.get() : nullptr;
    tbb::parallel_for(tbb::blocked_range<std::size_t>(0, candidates.size(), 4), [&](const tbb::blocked_range<std::size_t>& range) {
      for (std::size_t i = range.begin(); i != range.end(); ++i) {
        EdgeSplit& e = candidates[i];
        if (!memory) {
          split_edge(e);
          continue;
        }
        const auto p = static_cast<std::size_t>(e.key >> 32), q = static_cast<std::size_t>(e.key & 0xffffffffu);
        const Eigen::Vector3d &xp = mesh.positions[p], &xq = mesh.positions[q];
        const sheet_refinement_detail::RefinementEdgeEnds ends{xp.x() + 0.0, xp.y() + 0.0, xp.z() + 0.0, xq.x() + 0.0, xq.y() + 0.0, xq.z() + 0.0};
        if (const auto it = memory->splits.find(ends);
            it != memory->splits.end() && same_sheet_vertex(it->second.p, vertices[p]) && same_sheet_vertex(it->second.q, vertices[q])) {
          e.found = it->second.found;
          e.distance = it->second.distance;
          e.position = it->second.position;
          e.vertex = it->second.vertex;
          ++memory->reused;
          continue;
        }
        split_edge(e);
        memory->splits.emplace(ends, SheetRefinementMemory::State::Entry{vertices[p], vertices[q], e.found, e.distance, e.position, e.vertex});
      }
    });
    // A split must not turn a face over: each face next to the edge, split at the new point
    // alone, gives two faces facing its way (else the split is refused, the edge unresolved).
    // (Faces with two corners at the ends of wanted splits are looked at only.)
    at_split.assign(mesh.num_vertices(), 0);
    {
      wanted.clear();
      for (std::size_t c = 0; c < candidates.size(); ++c) {
        const EdgeSplit& e = candidates[c];
        if (!e.found || e.distance <= options.tolerance) continue;
        wanted.emplace(e.key, c);
        at_split[static_cast<std::size_t>(e.key >> 32)] = at_split[static_cast<std::size_t>(e.key & 0xffffffffu)] = 1;
      }
      auto position = [&](int v) -> const Eigen::Vector3d& { return mesh.positions[static_cast<std::size_t>(v)]; };
      for (const auto& t : mesh.triangles) {
        if (at_split[static_cast<std::size_t>(t[0])] + at_split[static_cast<std::size_t>(t[1])] + at_split[static_cast<std::size_t>(t[2])] < 2)
          continue;
        for (int j = 0; j < 3; ++j) {
          const int u = t[static_cast<std::size_t>(j)], v = t[static_cast<std::size_t>((j + 1) % 3)], r = t[static_cast<std::size_t>((j + 2) % 3)];
          const auto it = wanted.find(refinement_edge_key(u, v));
          if (it == wanted.end()) continue;
          EdgeSplit& e = candidates[it->second];
          const Eigen::Vector3d parent = (position(v) - position(u)).cross(position(r) - position(u));
          const Eigen::Vector3d first = (e.position - position(u)).cross(position(r) - position(u));
          const Eigen::Vector3d second = (position(v) - e.position).cross(position(r) - e.position);
          if (!(first.dot(parent) > 0 && second.dot(parent) > 0)) e.found = false;
        }
      }
    }
    // Faces split by their split edges (`at`: edge key -> new vertex), orientation kept; `pos`
    // gives the positions, also of vertices not added yet.
    const auto base = static_cast<int>(mesh.num_vertices());
    added.clear();
    auto pos = [&](int v) -> const Eigen::Vector3d& {
      return v < base ? mesh.positions[static_cast<std::size_t>(v)] : added[static_cast<std::size_t>(v - base)];
    };
    split_at.clear();
    auto split_faces = [&] {
      triangles.clear();
      parts.clear();
      parent_face.clear();
      split_face.clear();
      std::size_t parent = 0;
      bool parent_split = false;
      auto emit = [&](int a, int b, int c, int part) {
        triangles.push_back({a, b, c});
        parts.push_back(part);
        parent_face.push_back(parent);
        split_face.push_back(parent_split ? 1 : 0);
      };
      auto midpoint_of = [&](int p, int q) {
        if (!at_split[static_cast<std::size_t>(p)] || !at_split[static_cast<std::size_t>(q)]) return -1;
        const auto it = split_at.find(refinement_edge_key(p, q));
        return it == split_at.end() ? -1 : it->second;
      };
      for (std::size_t f = 0; f < mesh.triangles.size(); ++f) {
        std::array<int, 3> t = mesh.triangles[f];
        const int part = mesh.parts[f];
        parent = f;
        std::array<int, 3> m{midpoint_of(t[0], t[1]), midpoint_of(t[1], t[2]), midpoint_of(t[2], t[0])};
        const int splits = static_cast<int>(std::count_if(m.begin(), m.end(), [](int v) { return v >= 0; }));
        parent_split = splits > 0;
        if (splits == 0) {
          emit(t[0], t[1], t[2], part);
        } else if (splits == 3) {
          emit(t[0], m[0], m[2], part);
          emit(m[0], t[1], m[1], part);
          emit(m[2], m[1], t[2], part);
          emit(m[0], m[1], m[2], part);
        } else if (splits == 1) {
          while (m[0] < 0) {
            std::rotate(t.begin(), t.begin() + 1, t.end());
            std::rotate(m.begin(), m.begin() + 1, m.end());
          }
          emit(t[0], m[0], t[2], part);
          emit(m[0], t[1], t[2], part);
        } else {
          // The unsplit edge last: (t2, t0).
          while (m[2] >= 0) {
            std::rotate(t.begin(), t.begin() + 1, t.end());
            std::rotate(m.begin(), m.begin() + 1, m.end());
          }
          emit(m[0], t[1], m[1], part);
          if ((pos(t[0]) - pos(m[1])).squaredNorm() <= (pos(m[0]) - pos(t[2])).squaredNorm()) {
            emit(t[0], m[0], m[1], part);
            emit(t[0], m[1], t[2], part);
          } else {
            emit(t[0], m[0], t[2], part);
            emit(m[0], m[1], t[2], part);
          }
        }
      }
    };
    // Faces split at two or three edges must not turn over either: the splits of a face with a
    // child facing against it are refused, until none is left (each refusal removes splits).
    auto normal_of = [&](const std::array<int, 3>& t) { return Eigen::Vector3d((pos(t[1]) - pos(t[0])).cross(pos(t[2]) - pos(t[0]))); };
    bool faces_checked = false;  // `triangles` holds the faces split by exactly the splits left
    for (int attempt = 0; attempt < 16; ++attempt) {
      faces_checked = false;
      split_at.clear();
      added.clear();
      for (const EdgeSplit& e : candidates)
        if (e.found && e.distance > options.tolerance) {
          split_at.emplace(e.key, base + static_cast<int>(added.size()));
          added.push_back(e.position);
        }
      if (split_at.empty()) break;
      split_faces();
      refused.clear();
      for (std::size_t c = 0; c < triangles.size(); ++c) {
        if (!split_face[c]) continue;
        const std::array<int, 3>& parent = mesh.triangles[parent_face[c]];
        if (normal_of(triangles[c]).dot(normal_of(parent)) > 0) continue;
        for (int j = 0; j < 3; ++j) {
          const std::uint64_t key = refinement_edge_key(parent[static_cast<std::size_t>(j)], parent[static_cast<std::size_t>((j + 1) % 3)]);
          if (split_at.count(key)) refused.insert(key);
        }
      }
      if (refused.empty()) {
        faces_checked = true;
        break;
      }
      for (EdgeSplit& e : candidates)
        if (refused.count(e.key)) e.found = false;
    }
    std::int64_t above = 0;
    double largest = 0;
    for (const EdgeSplit& e : candidates) {
      if (!e.found) {
        ++stats.failed_edges;
        const auto p = static_cast<int>(e.key >> 32), q = static_cast<int>(e.key & 0xffffffffu);
        stats.unverified_edges.push_back({p, q});
        if (arc_deviation(p, q, vertices[static_cast<std::size_t>(p)].on[0].normal, vertices[static_cast<std::size_t>(q)].on[0].normal) >
            options.tolerance)
          ++stats.unresolved_edges;
        newly_settled.push_back(e.key);
        continue;
      }
      if (e.distance <= options.tolerance) {
        newly_settled.push_back(e.key);
        continue;
      }
      ++above;
      largest = std::max(largest, e.distance);
    }
    if (above == 0) break;
    if (round >= options.max_rounds) {
      stats.edges_above_tolerance = above;
      stats.largest_remaining_distance = largest;
      for (const EdgeSplit& e : candidates)
        if (e.found && e.distance > options.tolerance) stats.unverified_edges.push_back({static_cast<int>(e.key >> 32), static_cast<int>(e.key & 0xffffffffu)});
      break;
    }
    stats.rounds = round + 1;
    // The vertices in the order the tentative ids gave them, then the faces as checked.
    for (const EdgeSplit& e : candidates) {
      if (!e.found || e.distance <= options.tolerance) continue;
      mesh.add_vertex(e.position, e.vertex.on[0].parameters.head<3>());
      vertices.push_back(e.vertex);
      ++stats.split_edges;
    }
    if (!faces_checked) split_faces();
    new_origin.resize(parent_face.size());
    for (std::size_t c = 0; c < parent_face.size(); ++c) new_origin[c] = origin[parent_face[c]];
    mesh.triangles.swap(triangles);
    mesh.parts.swap(parts);
    origin.swap(new_origin);
    fresh.swap(split_face);
  }
  return finish();
}

}  // namespace volspline
