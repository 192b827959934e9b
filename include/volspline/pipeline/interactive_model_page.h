#pragma once
// The probes of an interactive page (web/interactive_page.h) for the volumes of a model: Lasser
// 1994 Fig. 10's moving point — sliders for u, v and w that move the three isoparametric surfaces
// through V(u, v, w), and the point itself — and a slice plane whose offset a fourth slider moves
// (Lasser §IV, Figs. 11-13). A page is static, so every surface is computed here at `levels`
// positions per slider (docs/web-pages.md, "Probes").
//
// A pipeline: it joins extract/ (the surfaces), spline/ (the point) and web/ (the page).
#include <string>

#include <Eigen/Core>

#include "volspline/io/model_file.h"
#include "volspline/web/interactive_page.h"

namespace volspline {

struct ModelProbeOptions {
  /// Positions per slider: u, v and w at isoparametric_values(knots, levels) of each volume's
  /// domain (both ends included, so the end positions are boundary faces), the slice at the
  /// middles of `levels` equal slabs of the solids' extent along the normal.
  int levels = 9;
  /// Segments across the domain of each isoparametric surface, plus every knot.
  int iso_resolution = 12;
  /// Sample grid of the slices (planar_slices' resolution).
  int slice_resolution = 16;
  /// The slice planes' normal (any length but zero).
  Eigen::Vector3d slice_normal = Eigen::Vector3d::UnitZ();
  /// Whether to add the slice probe.
  bool slices = true;
};

/// Appends to `page` the probes "u", "v", "w" (parts iso_u, iso_v, iso_w; at position i the
/// surfaces of every volume at its i-th value) and, with options.slices, "slice" (part slice;
/// switched off when the page opens); for a model with exactly one volume also the probe point
/// V(u_i, v_j, w_k) at every combination of positions. The sliders open in the middle. Objects that
/// are not trivariate volumes in R^3 are skipped; a model without any gets no probes.
/// \throw InvalidInput if levels < 2 or above 64, a resolution is < 1 or the normal is zero or not
/// finite; located at `source_name` and the object as the extraction functions throw.
void add_model_probes(InteractivePage& page, const Model& model, const ModelProbeOptions& options = {},
                      const std::string& source_name = "");

/// The model's description for a page's `info`: {"file": source_name, "objects":
/// model_object_summaries(model)}.
nlohmann::json model_page_info(const Model& model, const std::string& source_name);

}  // namespace volspline
