#pragma once
// Small helpers shared by the subcommands: argument lists, object selection, number printing.
#include <array>
#include <memory>
#include <string>
#include <vector>

#include <nlohmann/json_fwd.hpp>

#include "volspline/core/progress.h"
#include "volspline/io/model_file.h"
#include "volspline/mesh/mesh_writer.h"
#include "volspline/mesh/plane.h"
#include "volspline/render/mesh_renderer.h"
#include "volspline/web/interactive_page.h"

namespace CLI {
class App;
}

namespace volspline::cli {

/// Parses "A,B,C" into exactly `count` finite numbers. \throw InvalidInput naming `option`.
std::vector<double> parse_numbers(const std::string& text, std::size_t count, const std::string& option);
/// Parses "A,B,C" into exactly `count` integers >= minimum. \throw InvalidInput naming `option`.
std::vector<int> parse_integers(const std::string& text, std::size_t count, int minimum, const std::string& option);
/// Parses "DX,DY,DZ", the direction a camera looks in. \throw InvalidInput naming `option` for
/// anything but three finite numbers, or the zero vector.
Eigen::Vector3d parse_view_direction(const std::string& text, const std::string& option);
/// Parses "NX,NY,NZ,D", the plane NX x + NY y + NZ z = D (normal as given, not normalised).
/// \throw InvalidInput naming `option` for anything but four finite numbers, or a zero normal.
Plane parse_plane(const std::string& text, const std::string& option);
/// "u", "v", "w" (or "s" for the 4th) or "0".."3" to a direction index. \throw InvalidInput.
int parse_direction(const std::string& text, const std::string& option);
/// The model a subcommand reads: the positional MODEL (any format of io/model_formats.h, by
/// extension) and --input-format NAME to override the extension.
struct ModelInput {
  std::string path, format;
  /// \throw IoError, InvalidInput as read_model_file.
  Model read() const;
};
std::shared_ptr<ModelInput> add_model_input(CLI::App* cmd);
/// Number of parameters of an object (1, 2 or 3).
int parameter_count(const ModelObject& object);
/// Writes `mesh` to `out` and, unless `png` is empty, its picture (of `shown` where not null, e.g.
/// the mesh cut open) to `png`. Both files are prepared and opened before either is committed, so
/// a failure on one leaves neither behind. `properties`: further PLY vertex properties (ignored
/// by the other formats).
void write_mesh_and_picture(const TriangleMesh& mesh, const std::string& out, MeshFormat format, bool ascii,
                            const std::string& png, const RenderOptions& options, const TriangleMesh* shown = nullptr,
                            const std::vector<PlyVertexProperty>& properties = {});
/// Writes `stats_text` to `stats_path` (unless empty), `mesh` and its picture as
/// write_mesh_and_picture, all prepared before any is committed, and prints what it wrote.
void write_mesh_picture_and_stats(const TriangleMesh& mesh, const std::string& out, MeshFormat format, const std::string& png,
                                  const RenderOptions& options, const std::string& stats_text, const std::string& stats_path,
                                  Progress* progress, const TriangleMesh* shown = nullptr,
                                  const std::vector<PlyVertexProperty>& properties = {});
/// The help of a DATA argument (`fit`, `data`): the volume data formats and generated names.
inline constexpr const char* kVolumeDataHelp =
    "volume data: .csv (header x,y,z,...), .ply, .vtu, .vti, .vtk, .inr, .nii, .nii.gz, or marschner-lobb:N / two-material:N[:TILT]";
/// JSON text for output (stdout, --stats): strings that are not valid UTF-8 (an object name read
/// from an IRIT file) have their invalid bytes replaced by U+FFFD instead of failing.
std::string json_text(const nlohmann::json& value, int indent = 2);
/// An object index given as --object: parsed as a signed number so that -1 is refused as
/// negative rather than wrapped to 18446744073709551615.
/// \throw InvalidInput naming `option` unless 0 <= index < count.
std::size_t object_index(long long index, std::size_t count, const std::string& option);
/// Adds `--html OUT.html` to `cmd`: the interactive page of the result (docs/web-pages.md).
std::shared_ptr<std::string> add_html_option(CLI::App* cmd);
/// Before any work: unless `html` is empty, it ends in .html and this build can write pages.
/// \throw InvalidInput naming --html otherwise.
void check_html_option(const std::string& html);
/// Unless `html` is empty: writes `page` there (atomically, with the command line that runs now
/// as its `command` where the page has none) and prints "wrote HTML".
void write_html_page(const std::string& html, InteractivePage page);
/// The command line of this run, as `volspline ARGS` with arguments quoted for a POSIX shell
/// where they need it: set once by main().
void remember_command_line(int argc, const char* const* argv);
const std::string& remembered_command_line();
/// Formats numbers with 17 significant digits separated by spaces.
std::string join_numbers(const double* values, std::size_t count);

}  // namespace volspline::cli
