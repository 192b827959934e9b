#include "volspline/render/xray_image.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <limits>

#include <Eigen/Geometry>
#include <tbb/enumerable_thread_specific.h>
#include <tbb/parallel_for.h>

#include "volspline/core/error.h"
#include "volspline/simplex/dms_tetrahedron_basis.h"

namespace volspline {
namespace {

// Pixels are binned in square tiles; each tile lists the tetrahedra whose projected boxes meet
// it, so that a ray tests only those.
constexpr int kTile = 16;

// A convex polytope given by planes n·x <= h: the parameter interval of the ray inside it.
template <std::size_t N>
bool clip_ray(const std::array<Eigen::Vector4d, N>& planes, const Eigen::Vector3d& o, const Eigen::Vector3d& d, double& t0, double& t1) {
  for (const Eigen::Vector4d& p : planes) {
    const double nd = p.head<3>().dot(d), no = p.head<3>().dot(o);
    if (nd == 0) {
      if (no > p[3]) return false;
    } else {
      const double t = (p[3] - no) / nd;
      if (nd > 0) t1 = std::min(t1, t);
      else t0 = std::max(t0, t);
    }
    if (t0 >= t1) return false;
  }
  return true;
}

// Four planes per tetrahedron, outward normals, offsets lifted to `points` (the corners for the
// domain tetrahedron, all knots for the support's enclosure).
std::array<Eigen::Vector4d, 4> enclosing_planes(const std::array<Eigen::Vector3d, 4>& corner, const std::vector<Eigen::Vector3d>& points) {
  std::array<Eigen::Vector4d, 4> planes;
  for (int f = 0; f < 4; ++f) {
    const Eigen::Vector3d& a = corner[static_cast<std::size_t>((f + 1) % 4)];
    const Eigen::Vector3d& b = corner[static_cast<std::size_t>((f + 2) % 4)];
    const Eigen::Vector3d& c = corner[static_cast<std::size_t>((f + 3) % 4)];
    Eigen::Vector3d n = (b - a).cross(c - a).normalized();
    if (n.dot(corner[static_cast<std::size_t>(f)] - a) > 0) n = -n;
    double h = -std::numeric_limits<double>::infinity();
    for (const Eigen::Vector3d& p : points) h = std::max(h, n.dot(p));
    planes[static_cast<std::size_t>(f)] << n, h;
  }
  return planes;
}

}  // namespace

struct XrayRenderer::State {
  int column = -1;  // -1: the constant 1
  // Camera.
  Eigen::Vector3d centre, forward, right, up;
  double radius = 1, half_extent = 1, tan_half = 0;
  // Geometry of every tetrahedron: the domain tetrahedron's planes, its supports' enclosure, and
  // the boxes in pixels both cover.
  std::vector<std::array<Eigen::Vector4d, 4>> domain_planes, support_planes;
  // The compiled recurrence of each tetrahedron's basis (simplex/dms_tetrahedron_basis.h).
  std::vector<DmsTetrahedronPlan> plans;
  std::vector<std::array<int, 4>> support_pixels;  // x0, y0, x1, y1 (inclusive), or x0 > x1 when off screen
  int tiles_x = 0, tiles_y = 0;
  std::vector<std::vector<int>> tile_domain, tile_support;
  // Per pixel, the chords of its ray inside Ω (merged), as [a, b] pairs: offsets into `chords`.
  std::vector<int> chord_offsets;
  std::vector<Eigen::Vector2d> chords;
};

XrayRenderer::XrayRenderer(const DmsSplineVolume& volume, const XrayOptions& options)
    : volume_(&volume), options_(options), state_(std::make_unique<State>()) {
  if (options.width < 1 || options.height < 1 || options.width > 8192 || options.height > 8192)
    throw InvalidInput("expected an image size from 1 x 1 to 8192 x 8192, got " + std::to_string(options.width) + " x " +
                       std::to_string(options.height));
  if (!std::isfinite(options.baseline)) throw InvalidInput("expected a finite baseline", "baseline");
  if (!(options.view_direction.norm() > 0) || !options.view_direction.allFinite())
    throw InvalidInput("expected a nonzero view direction");
  if (!(options.field_of_view_deg >= 0 && options.field_of_view_deg < 170))
    throw InvalidInput("expected a field of view from 0 (orthographic) to 170 degrees, got " + std::to_string(options.field_of_view_deg));
  State& s = *state_;
  if (!options.attribute.empty()) s.column = volume.attribute_column(options.attribute);
  else if (!volume.attribute_names().empty()) s.column = 3;

  const TetrahedralMesh& domain = volume.domain();
  const int per_cloud = volume.degree() + 1;
  Eigen::AlignedBox3d box;
  for (const Eigen::Vector3d& k : volume.knots().knots) box.extend(k);
  s.centre = box.center();
  s.radius = std::max(0.5 * box.diagonal().norm(), 1e-300);
  s.forward = options.view_direction.normalized();
  s.right = s.forward.cross(options.up);
  if (!(s.right.norm() > 1e-12 * options.up.norm())) throw InvalidInput("expected an up direction that is not parallel to the view direction");
  s.right.normalize();
  s.up = s.right.cross(s.forward);
  s.tan_half = options.field_of_view_deg > 0 ? std::tan(options.field_of_view_deg * M_PI / 360.0) : 0.0;
  s.half_extent = 1.05 * s.radius;

  // Tetrahedra: planes and projected pixel boxes.
  const std::size_t tets = domain.tetrahedra.size();
  s.domain_planes.resize(tets);
  s.support_planes.resize(tets);
  s.support_pixels.resize(tets);
  std::vector<std::array<int, 4>> domain_pixels(tets);
  s.tiles_x = (options.width + kTile - 1) / kTile;
  s.tiles_y = (options.height + kTile - 1) / kTile;
  const int width = options.width, height = options.height;
  const double shorter = std::min(width, height);
  auto to_pixels = [&](const std::vector<Eigen::Vector3d>& points) -> std::array<int, 4> {
    double x0 = std::numeric_limits<double>::infinity(), y0 = x0, x1 = -x0, y1 = -x0;
    for (const Eigen::Vector3d& p : points) {
      const Eigen::Vector3d q = p - s.centre;
      double sx = q.dot(s.right), sy = q.dot(s.up);
      if (s.tan_half > 0) {
        const double depth = q.dot(s.forward) + s.radius / std::sin(std::atan(s.tan_half)) * 1.05;
        if (depth <= 1e-9 * s.radius) return {0, 0, width - 1, height - 1};
        sx /= depth * s.tan_half;
        sy /= depth * s.tan_half;
      } else {
        sx /= s.half_extent;
        sy /= s.half_extent;
      }
      // Normalised coordinates span [-1, 1] across the shorter side.
      const double px = width / 2.0 + sx * shorter / 2.0, py = height / 2.0 - sy * shorter / 2.0;
      x0 = std::min(x0, px), x1 = std::max(x1, px), y0 = std::min(y0, py), y1 = std::max(y1, py);
    }
    // Clamped as doubles first: a far point's pixel coordinate need not fit an int.
    const auto pixel = [](double v, int limit) { return static_cast<int>(std::clamp(v, -1.0, static_cast<double>(limit))); };
    return {std::max(0, pixel(std::floor(x0 - 1), width)), std::max(0, pixel(std::floor(y0 - 1), height)),
            std::min(width - 1, pixel(std::ceil(x1 + 1), width)), std::min(height - 1, pixel(std::ceil(y1 + 1), height))};
  };
  std::vector<Eigen::Vector3d> knots;
  for (std::size_t t = 0; t < tets; ++t) {
    std::array<Eigen::Vector3d, 4> corner;
    knots.clear();
    for (int c = 0; c < 4; ++c) {
      const int v = domain.tetrahedra[t][static_cast<std::size_t>(c)];
      corner[static_cast<std::size_t>(c)] = domain.points[static_cast<std::size_t>(v)];
      for (int m = 0; m < per_cloud; ++m) knots.push_back(volume.knots().cloud(v)[m]);
    }
    s.domain_planes[t] = enclosing_planes(corner, std::vector<Eigen::Vector3d>(corner.begin(), corner.end()));
    s.support_planes[t] = enclosing_planes(corner, knots);
    // Box corners of the support's knots: the projected knots bound the projected hull.
    s.support_pixels[t] = to_pixels(knots);
    domain_pixels[t] = to_pixels(std::vector<Eigen::Vector3d>(corner.begin(), corner.end()));
  }
  s.plans.resize(tets);
  tbb::parallel_for(std::size_t{0}, tets, [&](std::size_t t) {
    const std::array<int, 4>& tet = domain.tetrahedra[t];
    s.plans[t] = DmsTetrahedronPlan(volume.degree(), {volume.knots().cloud(tet[0]), volume.knots().cloud(tet[1]),
                                                      volume.knots().cloud(tet[2]), volume.knots().cloud(tet[3])});
  });
  s.tile_domain.assign(static_cast<std::size_t>(s.tiles_x * s.tiles_y), {});
  s.tile_support.assign(static_cast<std::size_t>(s.tiles_x * s.tiles_y), {});
  auto bin = [&](const std::array<int, 4>& r, int id, std::vector<std::vector<int>>& tiles) {
    if (r[0] > r[2] || r[1] > r[3]) return;
    for (int ty = r[1] / kTile; ty <= r[3] / kTile; ++ty)
      for (int tx = r[0] / kTile; tx <= r[2] / kTile; ++tx) tiles[static_cast<std::size_t>(ty * s.tiles_x + tx)].push_back(id);
  };
  for (std::size_t t = 0; t < tets; ++t) {
    bin(domain_pixels[t], static_cast<int>(t), s.tile_domain);
    bin(s.support_pixels[t], static_cast<int>(t), s.tile_support);
  }

  // Chords of every ray inside Ω: the domain tetrahedra's chords, merged where they meet (two
  // tetrahedra sharing a face give chords that meet up to rounding).
  const std::size_t pixels = static_cast<std::size_t>(width) * static_cast<std::size_t>(height);
  std::vector<std::vector<Eigen::Vector2d>> per_pixel(pixels);
  const double gap = 1e-9 * s.radius;
  tbb::parallel_for(0, s.tiles_x * s.tiles_y, [&](int tile) {
    const int tx = tile % s.tiles_x, ty = tile / s.tiles_x;
    std::vector<Eigen::Vector2d> pieces;
    for (int y = ty * kTile; y < std::min(height, (ty + 1) * kTile); ++y)
      for (int x = tx * kTile; x < std::min(width, (tx + 1) * kTile); ++x) {
        Eigen::Vector3d o, d;
        pixel_ray(x, y, o, d);
        pieces.clear();
        for (const int t : s.tile_domain[static_cast<std::size_t>(tile)]) {
          double t0 = 0, t1 = std::numeric_limits<double>::infinity();
          if (clip_ray(s.domain_planes[static_cast<std::size_t>(t)], o, d, t0, t1)) pieces.emplace_back(t0, t1);
        }
        std::sort(pieces.begin(), pieces.end(), [](const Eigen::Vector2d& a, const Eigen::Vector2d& b) { return a[0] < b[0]; });
        auto& merged = per_pixel[static_cast<std::size_t>(y) * static_cast<std::size_t>(width) + static_cast<std::size_t>(x)];
        for (const Eigen::Vector2d& p : pieces) {
          if (!merged.empty() && p[0] <= merged.back()[1] + gap) merged.back()[1] = std::max(merged.back()[1], p[1]);
          else merged.push_back(p);
        }
      }
  });
  s.chord_offsets.assign(pixels + 1, 0);
  for (std::size_t p = 0; p < pixels; ++p) s.chord_offsets[p + 1] = s.chord_offsets[p] + static_cast<int>(per_pixel[p].size());
  s.chords.reserve(static_cast<std::size_t>(s.chord_offsets.back()));
  for (const auto& m : per_pixel) s.chords.insert(s.chords.end(), m.begin(), m.end());

  picture_.width = width;
  picture_.height = height;
  render();
}

XrayRenderer::~XrayRenderer() = default;

void XrayRenderer::pixel_ray(int x, int y, Eigen::Vector3d& origin, Eigen::Vector3d& direction) const {
  const State& s = *state_;
  const double shorter = std::min(options_.width, options_.height);
  const double sx = (x + 0.5 - options_.width / 2.0) / (shorter / 2.0), sy = (options_.height / 2.0 - (y + 0.5)) / (shorter / 2.0);
  if (s.tan_half > 0) {
    const double distance = s.radius / std::sin(std::atan(s.tan_half)) * 1.05;
    origin = s.centre - distance * s.forward;
    direction = (s.forward + s.tan_half * (sx * s.right + sy * s.up)).normalized();
  } else {
    origin = s.centre - 2.0 * s.radius * s.forward + s.half_extent * (sx * s.right + sy * s.up);
    direction = s.forward;
  }
}

void XrayRenderer::render() {
  const auto start = std::chrono::steady_clock::now();
  const State& s = *state_;
  const DmsSplineVolume& v = *volume_;
  const int width = options_.width, height = options_.height;
  picture_.line_integrals.assign(static_cast<std::size_t>(width) * static_cast<std::size_t>(height), 0.0);
  struct Local {
    explicit Local(int degree) : basis(degree) {}
    DmsTetrahedronBasis basis;
    std::vector<double> integrals;
    long long count = 0;
  };
  tbb::enumerable_thread_specific<Local> locals([&] { return Local(v.degree()); });
  const Eigen::MatrixXd& control = v.control_vectors();
  // Tetrahedron-major within a tile: each plan (kilobytes) is used for all the tile's rays while
  // it is in the cache, instead of the tile's hundreds of plans for every ray.
  tbb::parallel_for(0, s.tiles_x * s.tiles_y, [&](int tile) {
    Local& local = locals.local();
    const int tx = tile % s.tiles_x, ty = tile / s.tiles_x;
    struct Ray {
      std::size_t pixel;
      Eigen::Vector3d origin, direction;
      int c0, c1;
      double sum;
    };
    std::vector<Ray> rays;
    rays.reserve(kTile * kTile);
    for (int y = ty * kTile; y < std::min(height, (ty + 1) * kTile); ++y)
      for (int x = tx * kTile; x < std::min(width, (tx + 1) * kTile); ++x) {
        const std::size_t p = static_cast<std::size_t>(y) * static_cast<std::size_t>(width) + static_cast<std::size_t>(x);
        const int c0 = s.chord_offsets[p], c1 = s.chord_offsets[p + 1];
        if (c0 == c1) continue;
        Ray ray{p, {}, {}, c0, c1, 0.0};
        pixel_ray(x, y, ray.origin, ray.direction);
        rays.push_back(ray);
      }
    if (rays.empty()) return;
    std::vector<double> weights(static_cast<std::size_t>(v.basis_per_tetrahedron()));
    for (const int t : s.tile_support[static_cast<std::size_t>(tile)]) {
      const DmsTetrahedronPlan& plan = s.plans[static_cast<std::size_t>(t)];
      for (int beta = 0; beta < v.basis_per_tetrahedron(); ++beta)
        weights[static_cast<std::size_t>(beta)] = s.column < 0 ? 1.0 : control(v.control_row(t, beta), s.column);
      for (Ray& ray : rays) {
        double s0 = s.chords[static_cast<std::size_t>(ray.c0)][0], s1 = s.chords[static_cast<std::size_t>(ray.c1 - 1)][1];
        if (!clip_ray(s.support_planes[static_cast<std::size_t>(t)], ray.origin, ray.direction, s0, s1)) continue;
        for (int c = ray.c0; c < ray.c1; ++c) {
          // The chord itself, not its part inside the support's enclosure: the kernel clips to the
          // support's box, and ends outside it need no boundary terms (ends on the enclosure would).
          const double a = s.chords[static_cast<std::size_t>(c)][0], b = s.chords[static_cast<std::size_t>(c)][1];
          if (!(std::max(s0, a) < std::min(s1, b))) continue;
          local.basis.line_integrals(ray.origin, ray.direction, a, b, plan, local.integrals);
          ++local.count;
          for (std::size_t beta = 0; beta < weights.size(); ++beta) ray.sum += weights[beta] * local.integrals[beta];
        }
      }
    }
    for (const Ray& ray : rays) {
      double length = 0;
      for (int c = ray.c0; c < ray.c1; ++c) length += s.chords[static_cast<std::size_t>(c)][1] - s.chords[static_cast<std::size_t>(c)][0];
      picture_.line_integrals[ray.pixel] = ray.sum - options_.baseline * length;
    }
  });
  picture_.tetrahedron_integrals = 0;
  for (const Local& l : locals) picture_.tetrahedron_integrals += l.count;
  double largest = 0;
  for (double value : picture_.line_integrals) largest = std::max(largest, std::abs(value));
  picture_.absorption = std::isnan(options_.absorption) ? (largest > 0 ? 2.0 / largest : 1.0) : options_.absorption;
  picture_.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

int XrayRenderer::update_coefficient(int row, double delta) {
  const DmsSplineVolume& v = *volume_;
  if (row < 0 || row >= v.control_vector_count())
    throw InvalidInput("expected a control row from 0 to " + std::to_string(v.control_vector_count() - 1) + ", got " + std::to_string(row));
  if (state_->column < 0) return 0;  // the constant 1 has no coefficients
  const State& s = *state_;
  DmsTetrahedronBasis basis(v.degree());
  std::vector<double> integrals;
  int touched = 0;
  std::vector<char> seen(static_cast<std::size_t>(options_.width) * static_cast<std::size_t>(options_.height), 0);
  for (const auto& [t, beta] : v.control_row_uses()[static_cast<std::size_t>(row)]) {
    const std::array<int, 4>& r = s.support_pixels[static_cast<std::size_t>(t)];
    const DmsTetrahedronPlan& plan = s.plans[static_cast<std::size_t>(t)];
    for (int y = r[1]; y <= r[3]; ++y)
      for (int x = r[0]; x <= r[2]; ++x) {
        const std::size_t p = static_cast<std::size_t>(y) * static_cast<std::size_t>(options_.width) + static_cast<std::size_t>(x);
        const int c0 = s.chord_offsets[p], c1 = s.chord_offsets[p + 1];
        if (c0 == c1) continue;
        Eigen::Vector3d o, d;
        pixel_ray(x, y, o, d);
        double s0 = s.chords[static_cast<std::size_t>(c0)][0], s1 = s.chords[static_cast<std::size_t>(c1 - 1)][1];
        if (!clip_ray(s.support_planes[static_cast<std::size_t>(t)], o, d, s0, s1)) continue;
        double integral = 0;
        for (int c = c0; c < c1; ++c) {
          const double a = s.chords[static_cast<std::size_t>(c)][0], b = s.chords[static_cast<std::size_t>(c)][1];
          if (!(std::max(s0, a) < std::min(s1, b))) continue;
          basis.line_integrals(o, d, a, b, plan, integrals);
          integral += integrals[static_cast<std::size_t>(beta)];
        }
        picture_.line_integrals[p] += delta * integral;
        if (!seen[p]) ++touched, seen[p] = 1;
      }
  }
  return touched;
}

Image XrayRenderer::image() const {
  Image out(picture_.width, picture_.height, 0, 0, 0, 255);
  for (int y = 0; y < picture_.height; ++y)
    for (int x = 0; x < picture_.width; ++x) {
      const double f = picture_.line_integrals[static_cast<std::size_t>(y) * static_cast<std::size_t>(picture_.width) + static_cast<std::size_t>(x)];
      const double absorbed = std::clamp(1.0 - std::exp(-picture_.absorption * f), 0.0, 1.0);
      // Gamma 1/2.2: the eye sees light on a logarithmic scale, and faint absorption matters.
      const auto level = static_cast<std::uint8_t>(std::lround(255.0 * std::pow(absorbed, 1.0 / 2.2)));
      std::uint8_t* px = out.pixel(x, y);
      px[0] = px[1] = px[2] = level;
    }
  return out;
}

}  // namespace volspline
