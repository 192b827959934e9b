#include "volspline/render/mesh_renderer.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <limits>
#include <mutex>
#include <numbers>
#include <string>
#include <unordered_map>
#include <vector>

#include <Eigen/Geometry>
#include <embree3/rtcore.h>
#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include "volspline/core/error.h"
#include "volspline/mesh/mesh_checks.h"
#include "volspline/render/color_bar.h"

namespace volspline {

namespace {

using Vec3f = Eigen::Vector3f;

// Share of the frame the mesh spans along its limiting direction; the rest is breathing room.
constexpr double kFill = 0.9;
constexpr int kMaxImageSide = 16384;

// ----- colour -------------------------------------------------------------------------------
// Light adds up linearly, so shading and the averaging of supersamples happen in linear RGB and
// only the final pixel is encoded as sRGB; otherwise edges and gradients look too dark.

float srgb_to_linear(double c) {
  c = std::clamp(c, 0.0, 1.0);
  return static_cast<float>(c <= 0.04045 ? c / 12.92 : std::pow((c + 0.055) / 1.055, 2.4));
}

std::uint8_t linear_to_srgb_byte(float c) {
  const double x = std::clamp(static_cast<double>(c), 0.0, 1.0);
  const double s = x <= 0.0031308 ? 12.92 * x : 1.055 * std::pow(x, 1 / 2.4) - 0.055;
  return static_cast<std::uint8_t>(std::lround(255 * s));
}

Vec3f srgb_to_linear(const Eigen::Vector3d& c) {
  return {srgb_to_linear(c.x()), srgb_to_linear(c.y()), srgb_to_linear(c.z())};
}

// ----- Embree handles -----------------------------------------------------------------------

// Embree reports details only through its error callback; keep the first message so the
// exception can say more than an error code.
struct EmbreeErrors {
  std::mutex mutex;
  std::string first_message;
};

void record_embree_error(void* user, RTCError, const char* message) {
  auto& errors = *static_cast<EmbreeErrors*>(user);
  const std::lock_guard lock(errors.mutex);
  if (errors.first_message.empty() && message != nullptr) errors.first_message = message;
}

const char* error_name(RTCError code) {
  switch (code) {
    case RTC_ERROR_NONE:
      return "no error";
    case RTC_ERROR_INVALID_ARGUMENT:
      return "invalid argument";
    case RTC_ERROR_INVALID_OPERATION:
      return "invalid operation";
    case RTC_ERROR_OUT_OF_MEMORY:
      return "out of memory";
    case RTC_ERROR_UNSUPPORTED_CPU:
      return "unsupported CPU";
    case RTC_ERROR_CANCELLED:
      return "cancelled";
    default:
      return "unknown error";
  }
}

void check_embree(RTCDevice device, EmbreeErrors& errors, const char* doing) {
  const RTCError code = rtcGetDeviceError(device);
  if (code == RTC_ERROR_NONE) return;
  std::string message = std::string("Embree failed while ") + doing + ": " + error_name(code);
  const std::lock_guard lock(errors.mutex);
  if (!errors.first_message.empty()) message += " (" + errors.first_message + ")";
  throw Error(message);
}

// A device and a scene holding one triangle geometry, built from coordinates relative to
// `centre`: Embree works in single precision, and moving the origin to the mesh keeps the float
// coordinates small, so a mesh far from the origin is not rendered with visible jitter.
class EmbreeScene {
 public:
  EmbreeScene(const TriangleMesh& mesh, const Eigen::Vector3d& centre) {
    device_ = rtcNewDevice(nullptr);
    if (device_ == nullptr) {
      throw Error(std::string("Embree device creation failed: ") +
                  error_name(rtcGetDeviceError(nullptr)));
    }
    rtcSetDeviceErrorFunction(device_, record_embree_error, &errors_);
    try {
      build(mesh, centre);
    } catch (...) {
      release();
      throw;
    }
  }
  ~EmbreeScene() { release(); }
  EmbreeScene(const EmbreeScene&) = delete;  // Embree holds a pointer to errors_
  EmbreeScene& operator=(const EmbreeScene&) = delete;

  RTCScene scene() const { return scene_; }
  /// \throw Error if Embree reported a failure since the last check.
  void check(const char* doing) { check_embree(device_, errors_, doing); }

 private:
  void build(const TriangleMesh& mesh, const Eigen::Vector3d& centre) {
    scene_ = rtcNewScene(device_);
    check("creating the scene");
    RTCGeometry geometry = rtcNewGeometry(device_, RTC_GEOMETRY_TYPE_TRIANGLE);
    check("creating the triangle geometry");
    auto* vertices = static_cast<float*>(
        rtcSetNewGeometryBuffer(geometry, RTC_BUFFER_TYPE_VERTEX, 0, RTC_FORMAT_FLOAT3,
                                3 * sizeof(float), mesh.num_vertices()));
    auto* indices = static_cast<unsigned*>(
        rtcSetNewGeometryBuffer(geometry, RTC_BUFFER_TYPE_INDEX, 0, RTC_FORMAT_UINT3,
                                3 * sizeof(unsigned), mesh.num_triangles()));
    if (vertices == nullptr || indices == nullptr) {
      rtcReleaseGeometry(geometry);
      check("allocating the mesh buffers");
      throw Error("Embree could not allocate the mesh buffers");
    }
    for (std::size_t v = 0; v < mesh.num_vertices(); ++v) {
      const Eigen::Vector3f p = (mesh.positions[v] - centre).cast<float>();
      std::copy(p.data(), p.data() + 3, vertices + 3 * v);
    }
    for (std::size_t t = 0; t < mesh.num_triangles(); ++t) {
      for (int i = 0; i < 3; ++i) indices[3 * t + i] = static_cast<unsigned>(mesh.triangles[t][i]);
    }
    rtcCommitGeometry(geometry);
    rtcAttachGeometry(scene_, geometry);
    rtcReleaseGeometry(geometry);  // the scene holds its own reference
    rtcCommitScene(scene_);
    check("building the scene");
  }

  void release() {
    if (scene_ != nullptr) rtcReleaseScene(scene_);
    if (device_ != nullptr) rtcReleaseDevice(device_);
    scene_ = nullptr;
    device_ = nullptr;
  }

  EmbreeErrors errors_;
  RTCDevice device_ = nullptr;
  RTCScene scene_ = nullptr;
};

// ----- options ------------------------------------------------------------------------------

void validate_options(const RenderOptions& o) {
  const auto fail = [](const std::string& message) {
    throw InvalidInput(message, "render options");
  };
  if (o.width < 1 || o.height < 1 || o.width > kMaxImageSide || o.height > kMaxImageSide) {
    fail("image size " + std::to_string(o.width) + " x " + std::to_string(o.height) +
         " is not within 1 .. " + std::to_string(kMaxImageSide) + " per side");
  }
  if (!(o.field_of_view_deg > 0 && o.field_of_view_deg < 170)) {
    fail("field of view must be in (0, 170) degrees");
  }
  if (!o.view_direction.allFinite() || o.view_direction.norm() == 0) {
    fail("view direction must be a finite nonzero vector");
  }
  if (!o.up.allFinite() || o.up.norm() == 0) fail("up must be a finite nonzero vector");
  if (!(o.crease_angle_deg >= 0 && o.crease_angle_deg <= 180)) {
    fail("crease angle must be in [0, 180] degrees");
  }
  if (!o.single_color.allFinite() || o.single_color.minCoeff() < 0 ||
      o.single_color.maxCoeff() > 1) {
    fail("single colour components must be in [0, 1]");
  }
  if (o.color == ColorMode::Scalar) {
    for (std::size_t i = 0; i < o.vertex_scalars.size(); ++i)
      if (!std::isfinite(o.vertex_scalars[i])) fail("vertex scalar " + std::to_string(i) + " is not finite");
    if (std::isinf(o.scalar_min) || std::isinf(o.scalar_max) ||
        (!std::isnan(o.scalar_min) && !std::isnan(o.scalar_max) && !(o.scalar_min < o.scalar_max)))
      fail("the scalar range must be finite with min < max");
  }
}

// ----- camera -------------------------------------------------------------------------------

// Coordinates are relative to the centre of the mesh's bounding box (see render_mesh).
struct Camera {
  Eigen::Vector3d position, forward, right, up;
  // The visible window on the image plane at unit distance in front of the camera: its centre
  // (off the optical axis, so the mesh is centred even though perspective makes its near side
  // look larger) and half extents.
  double centre_x = 0, centre_y = 0, half_width = 1, half_height = 1;

  Eigen::Vector3d ray_direction(double px, double py, int width, int height) const {
    const double x = centre_x + (2 * px / width - 1) * half_width;
    const double y = centre_y + (1 - 2 * py / height) * half_height;
    return (forward + x * right + y * up).normalized();
  }
  // Size of one pixel on the image plane at unit distance, to turn distances into pixels.
  double pixel_size(int height) const { return 2 * half_height / height; }
};

Camera fit_camera(const std::vector<Eigen::Vector3d>& points, double extent,
                  const RenderOptions& o) {
  Camera camera;
  camera.forward = o.view_direction.normalized();
  Eigen::Vector3d up_hint = o.up.normalized();
  if (camera.forward.cross(up_hint).norm() < 1e-6) {
    // Looking straight along `up`: any perpendicular will do; take the least aligned axis.
    Eigen::Index axis;
    camera.forward.cwiseAbs().minCoeff(&axis);
    up_hint = Eigen::Vector3d::Unit(axis);
  }
  camera.right = camera.forward.cross(up_hint).normalized();
  camera.up = camera.right.cross(camera.forward);

  const double tan_half = std::tan(o.field_of_view_deg * std::numbers::pi / 360);
  const double shorter = std::min(o.width, o.height);
  const double tan_half_x = tan_half * o.width / shorter;
  const double tan_half_y = tan_half * o.height / shorter;

  // The nearest distance along -forward at which every point projects inside kFill of the
  // frame, and lies in front of the camera.
  double distance = 0;
  for (const auto& q : points) {
    const double depth = q.dot(camera.forward);
    const double lateral = std::max(std::abs(q.dot(camera.right)) / (kFill * tan_half_x),
                                    std::abs(q.dot(camera.up)) / (kFill * tan_half_y));
    distance = std::max({distance, lateral - depth, 0.01 * extent - depth});
  }
  camera.position = -distance * camera.forward;

  // Centre the projected mesh and zoom so it spans kFill of the frame along its limiting axis.
  double x_lo = std::numeric_limits<double>::infinity(), x_hi = -x_lo;
  double y_lo = x_lo, y_hi = -x_lo;
  for (const auto& q : points) {
    const double depth = distance + q.dot(camera.forward);
    const double x = q.dot(camera.right) / depth, y = q.dot(camera.up) / depth;
    x_lo = std::min(x_lo, x);
    x_hi = std::max(x_hi, x);
    y_lo = std::min(y_lo, y);
    y_hi = std::max(y_hi, y);
  }
  camera.centre_x = 0.5 * (x_lo + x_hi);
  camera.centre_y = 0.5 * (y_lo + y_hi);
  const double half_x = 0.5 * (x_hi - x_lo), half_y = 0.5 * (y_hi - y_lo);
  double zoom = std::numeric_limits<double>::infinity();
  if (half_x > 0) zoom = std::min(zoom, kFill * tan_half_x / half_x);
  if (half_y > 0) zoom = std::min(zoom, kFill * tan_half_y / half_y);
  if (!std::isfinite(zoom)) zoom = 1;  // the mesh projects to a point: nothing to fit
  camera.half_width = tan_half_x / zoom;
  camera.half_height = tan_half_y / zoom;
  return camera;
}

// ----- shading ------------------------------------------------------------------------------

struct TriangleShading {
  Vec3f face_normal;                    // unit, or zero for a degenerate triangle
  std::array<Vec3f, 3> corner_normals;  // unit normals to interpolate across the triangle
  Vec3f heights;                        // distance of each corner from the opposite edge
  Vec3f color;                          // linear RGB
  Vec3f corner_t;                       // ColorMode::Scalar: corner values mapped to [0, 1]
  std::uint8_t outline = 0;             // bit i: the edge opposite corner i is a mesh border
};

// A vertex shared by more triangles than this is a pole or a fan; smoothing there would cost
// the square of its valence, and flat shading looks as good.
constexpr std::size_t kMaxSmoothedValence = 64;

std::vector<TriangleShading> shading_data(const TriangleMesh& mesh, const RenderOptions& o,
                                         const std::pair<double, double>& range) {
  const std::size_t n = mesh.num_triangles();
  std::vector<Eigen::Vector3d> face(n);  // cross products: normals weighted by twice the area
  std::vector<Eigen::Vector3d> unit(n);
  for (std::size_t t = 0; t < n; ++t) {
    const auto& tri = mesh.triangles[t];
    const Eigen::Vector3d& a = mesh.positions[tri[0]];
    face[t] = (mesh.positions[tri[1]] - a).cross(mesh.positions[tri[2]] - a);
    const double length = face[t].norm();
    unit[t] = length > 0 ? Eigen::Vector3d(face[t] / length) : Eigen::Vector3d::Zero();
  }

  // Triangles around each vertex, in compressed rows.
  std::vector<std::size_t> first(mesh.num_vertices() + 1, 0);
  std::vector<std::size_t> around;
  if (o.smooth_normals) {
    for (const auto& tri : mesh.triangles) {
      for (const int v : tri) ++first[v + 1];
    }
    for (std::size_t v = 0; v < mesh.num_vertices(); ++v) first[v + 1] += first[v];
    around.resize(3 * n);
    std::vector<std::size_t> next(first.begin(), first.end() - 1);
    for (std::size_t t = 0; t < n; ++t) {
      for (const int v : mesh.triangles[t]) around[next[v]++] = t;
    }
  }

  // Border edges (used by one triangle) of open surfaces — slices, isoparametric surfaces,
  // the Jacobian-zero sheet — are outlined, so that overlapping flat pieces stay apart.
  std::unordered_map<std::uint64_t, int> edge_uses;
  const auto edge_key = [](int a, int b) {
    return (std::uint64_t(std::uint32_t(std::min(a, b))) << 32) | std::uint32_t(std::max(a, b));
  };
  // Edges are compared by position, not by vertex index, so the seam of a periodic
  // parameterisation (a torus's v = 0 and v = 1) is not taken for a border.
  std::vector<int> same;
  if (o.outline_borders) {
    const auto [lo, hi] = mesh.bounding_box();
    same = coincident_vertices(mesh, 1e-9 * (hi - lo).norm());
    edge_uses.reserve(3 * n);
    for (const auto& tri : mesh.triangles)
      for (int i = 0; i < 3; ++i) ++edge_uses[edge_key(same[tri[(i + 1) % 3]], same[tri[(i + 2) % 3]])];
  }
  const double cos_crease = std::cos(o.crease_angle_deg * std::numbers::pi / 180);
  const Vec3f single = srgb_to_linear(o.single_color);
  std::vector<TriangleShading> data(n);
  for (std::size_t t = 0; t < n; ++t) {
    const auto& tri = mesh.triangles[t];
    TriangleShading& s = data[t];
    const double twice_area = face[t].norm();
    s.face_normal = unit[t].cast<float>();
    for (int i = 0; i < 3; ++i) {
      Eigen::Vector3d corner = unit[t];
      const std::size_t v = static_cast<std::size_t>(tri[i]);
      if (o.smooth_normals && twice_area > 0 && first[v + 1] - first[v] <= kMaxSmoothedValence) {
        // Average only over the neighbours on this side of a crease: a plain vertex normal at
        // the corner of a box belongs to none of its faces and would shade them with false
        // gradients, while the faces of a curved surface still blend into each other.
        Eigen::Vector3d sum = Eigen::Vector3d::Zero();
        for (std::size_t k = first[v]; k < first[v + 1]; ++k) {
          if (unit[around[k]].dot(unit[t]) >= cos_crease) sum += face[around[k]];
        }
        if (sum.squaredNorm() > 0) corner = sum.normalized();
      }
      s.corner_normals[i] = corner.cast<float>();
      const double edge =
          (mesh.positions[tri[(i + 2) % 3]] - mesh.positions[tri[(i + 1) % 3]]).norm();
      s.heights[i] = edge > 0 ? static_cast<float>(twice_area / edge) : 0.0f;
    }
    s.color = o.color == ColorMode::ByPart ? srgb_to_linear(part_color(mesh.parts[t])) : single;
    if (o.outline_borders) {
      for (int i = 0; i < 3; ++i)
        if (edge_uses[edge_key(same[tri[(i + 1) % 3]], same[tri[(i + 2) % 3]])] == 1) s.outline |= std::uint8_t(1u << i);
    }
    if (o.color == ColorMode::Scalar) {
      for (int i = 0; i < 3; ++i) {
        const double value = o.vertex_scalars[static_cast<std::size_t>(tri[i])];
        s.corner_t[i] = static_cast<float>((value - range.first) / (range.second - range.first));
      }
    }
  }
  return data;
}

struct Light {
  Vec3f direction;  // towards the light
  float intensity;
};

class Shader {
 public:
  Shader(const Camera& camera, std::vector<TriangleShading> triangles, const RenderOptions& o)
      : triangles_(std::move(triangles)),
        edges_(o.edges),
        scalar_(o.color == ColorMode::Scalar),
        colormap_(o.colormap),
        pixel_size_(static_cast<float>(camera.pixel_size(o.height))) {
    // Lights hang relative to the camera so every view direction is lit the same way: a key
    // light above-left in front, a weaker fill from the right, and a rim light from behind that
    // separates silhouettes from the background.
    const Vec3f r = camera.right.cast<float>(), u = camera.up.cast<float>(),
                f = camera.forward.cast<float>();
    lights_ = {Light{(-0.45f * r + 0.75f * u - 0.50f * f).normalized(), 0.80f},
               Light{(0.80f * r - 0.10f * u - 0.45f * f).normalized(), 0.30f},
               Light{(0.20f * r + 0.50f * u + 0.85f * f).normalized(), 0.35f}};
  }

  // Linear RGB of the surface point (u, v) of triangle `t`, hit at `distance` along the unit
  // direction `ray`.
  Vec3f shade(unsigned t, float u, float v, float distance, const Vec3f& ray) const {
    const TriangleShading& s = triangles_[t];
    const Vec3f to_eye = -ray;
    const float w = 1 - u - v;
    Vec3f face = s.face_normal;
    if (face.squaredNorm() == 0) face = to_eye;
    Vec3f normal = w * s.corner_normals[0] + u * s.corner_normals[1] + v * s.corner_normals[2];
    normal = normal.squaredNorm() > 1e-12f ? normal.normalized() : face;
    // Two-sided: a back face is shaded as if it faced the viewer, so open meshes and inner
    // surfaces (such as det J = 0) are not black.
    if (face.dot(to_eye) < 0) {
      face = -face;
      normal = -normal;
    }
    if (normal.dot(to_eye) < 0) normal = face;

    float diffuse = 0.20f;  // ambient
    for (const Light& light : lights_) {
      diffuse += light.intensity * std::max(0.0f, normal.dot(light.direction));
    }
    const Vec3f half = (lights_[0].direction + to_eye).normalized();
    const float specular = 0.22f * std::pow(std::max(0.0f, normal.dot(half)), 48.0f);
    const Vec3f base =
        scalar_ ? srgb_to_linear(colormap_color(colormap_, w * s.corner_t[0] + u * s.corner_t[1] + v * s.corner_t[2]))
                : s.color;
    Vec3f color = diffuse * base + Vec3f::Constant(specular);

    if (s.outline) {
      // A border line about two pixels wide, drawn wholly by the one triangle at the border.
      const float pixel = distance * pixel_size_;
      const float bary[3] = {w, u, v};
      float to_border = std::numeric_limits<float>::infinity();
      for (int i = 0; i < 3; ++i)
        if (s.outline & (1u << i)) to_border = std::min(to_border, bary[i] * s.heights[i]);
      const float line = std::clamp((1.6f * pixel - to_border) / (0.6f * pixel), 0.0f, 1.0f);
      color = (1 - 0.8f * line) * color + 0.8f * line * Vec3f(0.10f, 0.09f, 0.08f);
    }
    if (edges_) {
      const float to_edge = std::min({w * s.heights[0], u * s.heights[1], v * s.heights[2]});
      const float pixel = distance * pixel_size_;
      // Fully dark within 0.3 pixel of an edge, fading out by 0.7 pixel; each of the two
      // triangles at an edge draws its half, giving a line about 1.4 pixels wide.
      const float line = std::clamp((0.7f * pixel - to_edge) / (0.4f * pixel), 0.0f, 1.0f);
      color = (1 - 0.85f * line) * color + 0.85f * line * Vec3f(0.02f, 0.02f, 0.03f);
    }
    return color;
  }

 private:
  std::vector<TriangleShading> triangles_;
  bool edges_;
  bool scalar_;
  Colormap colormap_;
  float pixel_size_;
  std::array<Light, 3> lights_;
};

// Light grey at the bottom to near white at the top, like a studio backdrop.
Vec3f background(double row_fraction) {
  const Eigen::Vector3d top(0.98, 0.98, 0.99), bottom(0.80, 0.82, 0.85);
  return srgb_to_linear(top + row_fraction * (bottom - top));
}

Image background_image(const RenderOptions& o) {
  Image image(o.width, o.height);
  if (o.transparent_background) return image;
  for (int y = 0; y < o.height; ++y) {
    const Vec3f c = background((y + 0.5) / o.height);
    for (int x = 0; x < o.width; ++x) {
      std::uint8_t* p = image.pixel(x, y);
      for (int i = 0; i < 3; ++i) p[i] = linear_to_srgb_byte(c[i]);
      p[3] = 255;
    }
  }
  return image;
}

// Traces and resolves one image row at a time; rows are independent, so they run in parallel.
class RowRenderer {
 public:
  RowRenderer(const EmbreeScene& scene, const Camera& camera, const Shader& shader,
              const RenderOptions& options)
      : scene_(scene.scene()),
        camera_(camera),
        shader_(shader),
        options_(options),
        samples_(options.supersample ? 4 : 1),
        eye_(camera.position.cast<float>()) {}

  void render(int y, Image& image) const {
    const int count = options_.width * samples_;
    std::vector<Vec3f> color(count);
    std::vector<float> alpha(count);
    const Vec3f backdrop = background((y + 0.5) / options_.height);
    for (int first = 0; first < count; first += 4) {
      trace_packet(y, first, count, backdrop, color, alpha);
    }
    for (int x = 0; x < options_.width; ++x) {
      // Average premultiplied colours, then un-premultiply: a pixel half covered by the mesh
      // over a transparent background keeps the mesh's colour at half opacity.
      Vec3f sum = Vec3f::Zero();
      float coverage = 0;
      for (int k = x * samples_; k < (x + 1) * samples_; ++k) {
        sum += alpha[k] * color[k];
        coverage += alpha[k];
      }
      std::uint8_t* p = image.pixel(x, y);
      const Vec3f straight = coverage > 0 ? Vec3f(sum / coverage) : Vec3f::Zero();
      for (int i = 0; i < 3; ++i) p[i] = linear_to_srgb_byte(straight[i]);
      p[3] = static_cast<std::uint8_t>(std::lround(255.0f * coverage / samples_));
    }
  }

 private:
  // Samples first .. first + 3 of row y (sample k is sub-sample k % samples of pixel
  // k / samples). With supersampling the four are one pixel's 2 x 2 grid: coherent rays, which
  // is what packets of four are fast for.
  void trace_packet(int y, int first, int count, const Vec3f& backdrop, std::vector<Vec3f>& color,
                    std::vector<float>& alpha) const {
    static constexpr double kOffsets[4][2] = {
        {0.25, 0.25}, {0.75, 0.25}, {0.25, 0.75}, {0.75, 0.75}};
    RTCRayHit4 packet;
    alignas(16) int valid[4];
    Vec3f directions[4];
    for (int lane = 0; lane < 4; ++lane) {
      const int k = std::min(first + lane, count - 1);  // spare lanes repeat the last sample
      valid[lane] = first + lane < count ? -1 : 0;
      const int x = k / samples_, s = k % samples_;
      const double px = x + (samples_ == 4 ? kOffsets[s][0] : 0.5);
      const double py = y + (samples_ == 4 ? kOffsets[s][1] : 0.5);
      directions[lane] =
          camera_.ray_direction(px, py, options_.width, options_.height).cast<float>();
      packet.ray.org_x[lane] = eye_.x();
      packet.ray.org_y[lane] = eye_.y();
      packet.ray.org_z[lane] = eye_.z();
      packet.ray.dir_x[lane] = directions[lane].x();
      packet.ray.dir_y[lane] = directions[lane].y();
      packet.ray.dir_z[lane] = directions[lane].z();
      packet.ray.tnear[lane] = 0.0f;
      packet.ray.tfar[lane] = std::numeric_limits<float>::infinity();
      packet.ray.time[lane] = 0.0f;
      packet.ray.mask[lane] = 0xFFFFFFFFu;
      packet.ray.id[lane] = static_cast<unsigned>(lane);
      packet.ray.flags[lane] = 0;
      packet.hit.geomID[lane] = RTC_INVALID_GEOMETRY_ID;
      packet.hit.instID[0][lane] = RTC_INVALID_GEOMETRY_ID;
    }
    RTCIntersectContext context;
    rtcInitIntersectContext(&context);
    context.flags = RTC_INTERSECT_CONTEXT_FLAG_COHERENT;
    rtcIntersect4(valid, scene_, &context, &packet);
    for (int lane = 0; lane < 4 && first + lane < count; ++lane) {
      const int k = first + lane;
      if (packet.hit.geomID[lane] == RTC_INVALID_GEOMETRY_ID) {
        color[k] = options_.transparent_background ? Vec3f::Zero() : backdrop;
        alpha[k] = options_.transparent_background ? 0.0f : 1.0f;
      } else {
        color[k] = shader_.shade(packet.hit.primID[lane], packet.hit.u[lane], packet.hit.v[lane],
                                 packet.ray.tfar[lane], directions[lane]);
        alpha[k] = 1.0f;
      }
    }
  }

  RTCScene scene_;
  const Camera& camera_;
  const Shader& shader_;
  const RenderOptions& options_;
  int samples_;
  Vec3f eye_;
};

}  // namespace

std::pair<double, double> scalar_range(const TriangleMesh& mesh, const RenderOptions& options) {
  double lo = options.scalar_min, hi = options.scalar_max;
  if (std::isnan(lo) || std::isnan(hi)) {
    double data_lo = std::numeric_limits<double>::infinity(), data_hi = -data_lo;
    for (const auto& t : mesh.triangles)
      for (const int v : t) {
        if (static_cast<std::size_t>(v) >= options.vertex_scalars.size()) continue;
        data_lo = std::min(data_lo, options.vertex_scalars[static_cast<std::size_t>(v)]);
        data_hi = std::max(data_hi, options.vertex_scalars[static_cast<std::size_t>(v)]);
      }
    if (!(data_lo <= data_hi)) data_lo = data_hi = 0;
    if (std::isnan(lo) && std::isnan(hi)) {
      // From the data alone: suggested_coloring's range (a field constant up to rounding is
      // constant), so `view` of a simplex slice and of a spline solid agree.
      const ScalarColoring data = suggested_coloring({data_lo, data_hi}, false);
      return {data.min, data.max};
    }
    if (std::isnan(lo)) lo = std::min(data_lo, hi);
    if (std::isnan(hi)) hi = std::max(data_hi, lo);
  }
  // A constant field: centred, so it shows the middle colour and the bar still reads.
  return widened_range(lo, hi);
}

Image render_mesh(const TriangleMesh& mesh, const RenderOptions& options) {
  validate_options(options);
  validate_mesh(mesh);
  if (options.color == ColorMode::Scalar && options.vertex_scalars.size() != mesh.num_vertices()) {
    throw InvalidInput("scalar colouring needs one value per vertex: the mesh has " + std::to_string(mesh.num_vertices()) +
                       " vertices, got " + std::to_string(options.vertex_scalars.size()) + " values");
  }
  if (options.color == ColorMode::Scalar && !options.color_bar_title.empty()) {
    // Frame the mesh in the picture left of the bar, then add the bar on the same backdrop.
    const std::pair<double, double> range = scalar_range(mesh, options);
    const int bar = color_bar_width(options.width, options.height);
    RenderOptions left = options;
    left.width = options.width - bar;
    left.color_bar_title.clear();
    left.scalar_min = range.first;
    left.scalar_max = range.second;
    const Image inner = render_mesh(mesh, left);
    Image image = background_image(options);
    for (int y = 0; y < inner.height; ++y)
      std::copy(inner.rgba.begin() + 4 * std::ptrdiff_t(y) * inner.width, inner.rgba.begin() + 4 * std::ptrdiff_t(y + 1) * inner.width,
                image.rgba.begin() + 4 * std::ptrdiff_t(y) * image.width);
    draw_color_bar(image, {options.colormap, range.first, range.second, options.color_bar_title});
    return image;
  }

  // Only vertices of triangles are seen, so only they decide the framing.
  std::vector<char> used(mesh.num_vertices(), 0);
  for (const auto& t : mesh.triangles) used[t[0]] = used[t[1]] = used[t[2]] = 1;
  Eigen::Vector3d lo = Eigen::Vector3d::Constant(std::numeric_limits<double>::infinity());
  Eigen::Vector3d hi = -lo;
  for (std::size_t v = 0; v < mesh.num_vertices(); ++v) {
    if (!used[v]) continue;
    lo = lo.cwiseMin(mesh.positions[v]);
    hi = hi.cwiseMax(mesh.positions[v]);
  }
  // Halves first: the box of coordinates near ±1.8e308 has no finite edge.
  const double half_extent = mesh.triangles.empty() ? 0.0 : (0.5 * hi - 0.5 * lo).maxCoeff();
  if (!(half_extent > 0)) return background_image(options);  // nothing with an area to see
  // Embree works in single precision (largest 3.4e38, least normal 1.2e-38), and products of
  // coordinates must stay in range too: a mesh much larger or smaller than 1 (models hold sizes
  // from 2^-200 to 2^200, docs/model-format.md) is drawn from a copy moved to the origin and
  // scaled by an exact power of two to a size near 1, which is the same picture.
  int exponent = 0;
  std::frexp(half_extent, &exponent);
  if (exponent > 16 || exponent < -16) {
    const Eigen::Vector3d middle = 0.5 * lo + 0.5 * hi;
    TriangleMesh scaled = mesh;
    for (Eigen::Vector3d& p : scaled.positions)
      for (int c = 0; c < 3; ++c) p[c] = std::ldexp(p[c], -exponent) - std::ldexp(middle[c], -exponent);
    return render_mesh(scaled, options);
  }
  const double extent = (hi - lo).norm();

  const Eigen::Vector3d centre = 0.5 * (lo + hi);
  std::vector<Eigen::Vector3d> points;
  for (std::size_t v = 0; v < mesh.num_vertices(); ++v) {
    if (used[v]) points.push_back(mesh.positions[v] - centre);
  }
  const Camera camera = fit_camera(points, extent, options);
  const Shader shader(camera, shading_data(mesh, options, scalar_range(mesh, options)), options);
  EmbreeScene scene(mesh, centre);
  const RowRenderer rows(scene, camera, shader, options);

  Image image(options.width, options.height);
  tbb::parallel_for(tbb::blocked_range<int>(0, options.height),
                    [&](const tbb::blocked_range<int>& range) {
                      for (int y = range.begin(); y != range.end(); ++y) rows.render(y, image);
                    });
  scene.check("tracing rays");
  return image;
}

}  // namespace volspline
