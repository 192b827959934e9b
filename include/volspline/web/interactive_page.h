#pragma once
// One self-contained HTML page that shows meshes in a browser (docs/web-pages.md): the meshes as
// binary glTF (mesh/mesh_writer.h glb_bytes, base64) and the viewer — three.js with orbit
// controls and its glTF loader, bundled with volspline's own viewer script (web/src/viewer.js)
// into one minified script at build time — inline, so the page opens from a file:// URL without
// a network. The page lists the parts of the mesh by name and colour (mesh/parts.h) with a switch
// each, has a clipping plane with a slider, wireframe on/off, the colour bar of a scalar field,
// a slider per probe that moves precomputed surfaces through the solid (Lasser 1994 Fig. 10:
// the three isoparametric surfaces through V(u, v, w) and the point itself), and the model's
// description beside the view.
//
// Nothing here knows splines: pipeline/interactive_model_page.h makes the probes of a model.
#include <array>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include <Eigen/Core>
#include <nlohmann/json.hpp>

#include "volspline/mesh/triangle_mesh.h"
#include "volspline/render/color_bar.h"

namespace volspline {

/// A slider through precomputed meshes: at each position the page shows meshes[position] alone.
struct PageProbe {
  /// Names the slider for the page's scripts and tests ("u", "v", "w", "slice").
  std::string name;
  /// Shown beside the value ("u", "z offset").
  std::string label;
  /// The value at each position of the slider, one per mesh, ascending.
  std::vector<double> values;
  std::vector<TriangleMesh> meshes;
  /// The position shown when the page opens.
  int initial = 0;
  /// Whether the probe is switched on when the page opens.
  bool shown = true;
  /// The colour of its entry in the list (the meshes carry their own part colours).
  Eigen::Vector3d srgb{0.5, 0.5, 0.5};
};

/// The point through which three probes pass (Lasser Fig. 10's moving point): points[i + n0 (j +
/// n1 k)] is where the surfaces of probes[0] at position i, probes[1] at j and probes[2] at k
/// meet, for probes named here with n0, n1, n2 positions. The page marks it with a small sphere
/// while all three are shown.
struct PageProbePoint {
  std::array<std::string, 3> probes;
  std::vector<Eigen::Vector3d> points;
};

struct InteractivePage {
  /// The page's title and heading.
  std::string title;
  /// The result: its triangles are grouped by part (TriangleMesh::parts), one switch per part.
  TriangleMesh mesh;
  /// sRGB colours in [0, 1], one per vertex of `mesh`, where it is coloured by a field (then
  /// `color_bar` is its key); empty for part colours.
  std::vector<Eigen::Vector3d> vertex_colors;
  /// Or one value per vertex, coloured by `color_bar`'s map over its range.
  std::vector<double> vertex_scalars;
  /// The key to the colours; required with vertex_scalars.
  std::optional<ColorBar> color_bar;
  std::vector<PageProbe> probes;
  std::optional<PageProbePoint> probe_point;
  /// What is shown beside the view as nested lists: the model's description, the command's
  /// figures and verdicts.
  nlohmann::json info = nlohmann::json::object();
  /// The command line that wrote the page, shown under the description; empty for none.
  std::string command;
  /// A result with more triangles is shown reduced to at most this many by vertex clustering
  /// (mesh/vertex_clustering.h; colours averaged like positions), so that the page stays small
  /// and quick to open; the page says so. Probe meshes are shown as they are.
  std::size_t max_triangles = 80000;
};

/// Whether this build of volspline carries the viewer script (three.js was installed when it was
/// built: scripts/install-web-deps); interactive_page_html throws otherwise.
bool interactive_pages_available();

/// Why interactive_pages_available() is false, as a sentence for an error message; empty when
/// it is true.
std::string_view interactive_pages_unavailable_reason();

/// The page, as UTF-8 text.
/// \throw InvalidInput if this build has no viewer (interactive_pages_unavailable_reason), the
/// mesh or a probe mesh is malformed, the colours or scalars are not one per vertex (colours in
/// [0, 1]; scalars with a colour bar), both are given, a probe has
/// no meshes, not one value per mesh or an initial position outside them, or the probe point
/// names probes the page lacks or has not one point per combination of their positions.
std::string interactive_page_html(const InteractivePage& page);

}  // namespace volspline
