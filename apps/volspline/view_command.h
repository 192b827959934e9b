#pragma once
// The arguments of `volspline view`, shared with `demo`, whose gallery shows the command line
// that reproduces each picture: the demo runs exactly the command it prints.
#include <ostream>
#include <string>
#include <vector>

namespace volspline {
class Progress;
}

namespace volspline::cli {

struct ViewArguments {
  std::string model, input_format, image, mesh, color, range, camera, size = "800,600", through, core;
  /// --html: the interactive page of what is shown (docs/web-pages.md); empty for none.
  std::string html;
  std::vector<std::string> iso, slices, planes, paddlewheels;
  /// Isosurfaces ATTRIBUTE:VALUE of a simplex spline volume (repeatable).
  std::vector<std::string> iso_attribute;
  /// Their sampling: the longest edge after local longest-edge bisection (domain units; 0: the
  /// library's default), or k³ sub-tetrahedra per domain tetrahedron alike (0: local bisection).
  double iso_edge = 0;
  int iso_subdivisions = 0;
  /// Cells per tetrahedron edge of a simplex spline volume shown shrunken (0: none).
  int cells = 0;
  int resolution = 32;
  bool faces = false, cutaway = false, edges = false, transparent = false, ascii = false;
};

/// Does what `volspline view` does with these arguments, reporting to `out` and, unless null,
/// its phases (reading, surfaces, rendering, writing) to `progress`.
/// \throw InvalidInput / IoError as the command reports them.
void run_view(const ViewArguments& arguments, std::ostream& out, Progress* progress = nullptr);

/// The `volspline view ...` command line for these arguments (paths as given).
std::string view_command_line(const ViewArguments& arguments);

}  // namespace volspline::cli
