#pragma once
// Export of boundary meshes to the formats other tools read: PLY keeps everything volspline
// knows (positions, parameters, parts), OBJ and STL trade information for reach, binary glTF
// (.glb) carries normals and colours for viewers on the web and in game engines. Every writer
// also has a `*_bytes` form returning the file contents, which is what the path form writes
// (atomically, see io/atomic_file.h).
#include <filesystem>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "volspline/mesh/triangle_mesh.h"

namespace volspline {

enum class MeshFormat { Ply, Obj, Stl, Glb };

/// The format named by the extension of `path` (.ply, .obj, .stl or .glb, any letter case).
/// \throw InvalidInput naming the path and the accepted extensions otherwise.
MeshFormat mesh_format_from_path(const std::filesystem::path& path);

/// One more PLY vertex property: a name and one value per vertex, written as `double`, or as
/// `int` when `integer` (the values are then rounded).
struct PlyVertexProperty {
  std::string name;
  std::vector<double> values;
  bool integer = false;
};

struct MeshWriteOptions {
  /// Text instead of binary, for PLY and STL; OBJ is always text.
  bool ascii = false;
  /// PLY: one value per vertex, written as one more vertex property (double) named
  /// `scalar_name` — the field a picture was coloured by. Ignored by the other formats.
  std::vector<double> vertex_scalars{};
  std::string scalar_name = "scalar";
  /// PLY: more vertex properties, after the scalar (a swept envelope's t and patch).
  std::vector<PlyVertexProperty> vertex_properties{};
  /// glTF: one sRGB colour (components in [0, 1]) per vertex for COLOR_0 instead of the part
  /// colours, so a file coloured by a field looks like its picture.
  std::vector<Eigen::Vector3d> vertex_colors{};
};

/// True if `name` can name a PLY property: nonempty, letters, digits, '_', '-' or '.'.
bool is_ply_property_name(const std::string& name);

/// PLY 1.0, binary_little_endian unless `ascii`: vertices with double x, y, z, u, v, w (position
/// and parameters) and faces with `list uchar int vertex_indices` and `int part` (the part
/// number, mesh/parts.h; a header comment lists the table).
/// With `scalars` (one per vertex) a further vertex property `double scalar_name` follows w.
/// \throw InvalidInput if the mesh is malformed, the scalars are not one per vertex or the name
/// is not a plain identifier.
std::string ply_bytes(const TriangleMesh& mesh, bool ascii = false, const std::vector<double>& scalars = {},
                      const std::string& scalar_name = "scalar");
/// The same with any number of further vertex properties after w, in order. \throw InvalidInput
/// also for two properties of one name (x .. w included).
std::string ply_bytes(const TriangleMesh& mesh, bool ascii, const std::vector<PlyVertexProperty>& properties);

/// Wavefront OBJ: `v` lines and 1-based `f` lines grouped as `g part_N`, parts ascending.
/// Parameters are not written.
std::string obj_bytes(const TriangleMesh& mesh);

/// STL: binary (80-byte header, then 50 bytes per triangle) unless `ascii` (`solid volspline`).
/// Coordinates are single precision in binary STL; parameters and parts are not written.
std::string stl_bytes(const TriangleMesh& mesh, bool ascii = false);

/// Binary glTF 2.0 (.glb, written with tinygltf): one mesh of indexed triangles with POSITION,
/// NORMAL and COLOR_0 (single precision). Every triangle's corners carry the colour of its part
/// (part_color of mesh/parts.h, converted from sRGB to glTF's linear colour space), so
/// a vertex shared by two parts is written once per part; normals are area-weighted averages
/// over the triangles of the same part around a vertex, so the seams between parts stay sharp.
/// Parameters are not written. With `vertex_colors` (sRGB, one per vertex) the corners carry
/// those colours instead of the parts'.
/// \throw InvalidInput if the mesh is malformed or the colours are not one per vertex in [0, 1],
/// Error if tinygltf fails.
std::string glb_bytes(const TriangleMesh& mesh, const std::vector<Eigen::Vector3d>& vertex_colors = {});

/// The bytes of `mesh` in `format`.
std::string mesh_bytes(const TriangleMesh& mesh, MeshFormat format,
                       const MeshWriteOptions& options = {});

/// Each writes the corresponding `*_bytes` to `path` atomically.
/// \throw InvalidInput if the mesh is malformed (see validate_mesh), IoError if it cannot be
/// written.
void write_ply(const TriangleMesh& mesh, const std::filesystem::path& path, bool ascii = false);
void write_obj(const TriangleMesh& mesh, const std::filesystem::path& path);
void write_stl(const TriangleMesh& mesh, const std::filesystem::path& path, bool ascii = false);
void write_glb(const TriangleMesh& mesh, const std::filesystem::path& path);

/// Writes `mesh` in the format named by the extension of `path` (mesh_format_from_path).
/// \throw InvalidInput for an unknown extension or a malformed mesh, IoError if it cannot be
/// written.
void write_mesh(const TriangleMesh& mesh, const std::filesystem::path& path,
                const MeshWriteOptions& options = {});

}  // namespace volspline
