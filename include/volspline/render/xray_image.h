#pragma once
// X-ray (absorption) pictures of an attribute of a DMS spline volume (Hua–He–Qin §6.1):
// I = exp(−k ∫ f dt) along each ray, where ∫ f = Σ g_β^I ∫ N_β^I is summed from the line
// integrals of the basis functions, computed analytically (eqs. 13–16, with the boundary terms
// of a chord that ends inside a support; simplex/dms_tetrahedron_basis.h), never by sampling.
// The spline is zero outside Ω, so each ray integrates over its chords inside Ω only; a
// constant attribute 1 gives the length of the chords.
//
// Incremental update (eq. 12): after one control coefficient changes by Δg, only the pixels whose
// rays cross the supports of its basis functions change, each by ∫ f += Δg ∫ N (so
// I_new = I_old exp(−k Δg ∫ N)).
#include <memory>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "volspline/render/image.h"
#include "volspline/simplex/dms_spline_volume.h"

namespace volspline {

struct XrayOptions {
  int width = 512;
  int height = 512;
  /// The attribute integrated along the rays; empty: the first attribute, or the constant 1 (the
  /// chord length through Ω) for a volume without attributes.
  std::string attribute;
  /// The direction the camera looks in; the camera is fitted to the supports' bounding sphere.
  Eigen::Vector3d view_direction{-1.0, -1.3, -0.8};
  Eigen::Vector3d up{0.0, 0.0, 1.0};
  /// Angle of view across the shorter side; 0 is an orthographic (parallel) projection.
  double field_of_view_deg = 0;
  /// The absorption coefficient k; NaN (the default) picks k so that the largest line integral
  /// absorbs 1 − e^{-2} ≈ 86 % of the light.
  double absorption = std::numeric_limits<double>::quiet_NaN();
  /// Subtracted from the attribute before it is integrated: the picture shows f − baseline (say
  /// a temperature above the ambient one, which would otherwise absorb alike everywhere). The
  /// integral of the constant is the baseline times the chord length through Ω.
  double baseline = 0;
};

/// Per-pixel line integrals and what they look like.
struct XrayPicture {
  int width = 0, height = 0;
  /// ∫ f dt along each pixel's ray through Ω, rows top to bottom.
  std::vector<double> line_integrals;
  /// The absorption coefficient used.
  double absorption = 1;
  /// Seconds spent, and how many basis-function line-integral evaluations (one per tetrahedron
  /// and chord) the picture took.
  double seconds = 0;
  long long tetrahedron_integrals = 0;
};

/// Renders and incrementally updates X-ray pictures of one attribute of one volume. The volume
/// must outlive the renderer; its domain and knots must not change.
class XrayRenderer {
 public:
  /// \throw InvalidInput for a size outside 1..8192, an unknown attribute, a zero view direction
  /// or an up direction parallel to it.
  XrayRenderer(const DmsSplineVolume& volume, const XrayOptions& options);
  ~XrayRenderer();
  XrayRenderer(const XrayRenderer&) = delete;
  XrayRenderer& operator=(const XrayRenderer&) = delete;

  /// The line integrals of the current control coefficients (computed by the constructor).
  const XrayPicture& picture() const { return picture_; }
  /// Applies eq. 12 after control_vectors()(row, column of the attribute) changed by `delta`
  /// (the caller changes the volume; this updates the picture): only the pixels whose rays meet
  /// the supports of that row's basis functions are touched. Returns how many were.
  /// \throw InvalidInput for a row out of range.
  int update_coefficient(int row, double delta);
  /// Recomputes every pixel from the current control coefficients.
  void render();
  /// The ray of a pixel centre: origin and unit direction; the chord parameters are distances.
  void pixel_ray(int x, int y, Eigen::Vector3d& origin, Eigen::Vector3d& direction) const;
  /// The picture as grey levels: black where nothing absorbs, white where everything does
  /// (1 − exp(−k ∫ f), clamped to [0, 1]).
  Image image() const;

 private:
  struct State;
  const DmsSplineVolume* volume_;
  XrayOptions options_;
  XrayPicture picture_;
  std::unique_ptr<State> state_;
};

}  // namespace volspline
