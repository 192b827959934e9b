#pragma once
// Import of triangle meshes from the formats mesh_writer.h writes, and from what other tools
// write in them: OBJ (v/f, polygons, negative and v/vt/vn indices), PLY (ascii and binary of
// either byte order, any scalar types, optional u v w parameters and face part) and STL (ascii
// and binary). Every reader also has a form taking the file contents, which is what the path
// form reads and what the fuzz target drives.
//
// Errors are InvalidInput whose where() names the source and the place: "model.obj: line 12"
// for text, "model.ply: byte 1234 (face 17)" for binary data. Declared counts are checked
// against the bytes that are there before anything is allocated, so a hostile header cannot make
// a reader reserve memory the file does not back.
#include <filesystem>
#include <string>
#include <string_view>

#include "volspline/mesh/mesh_writer.h"
#include "volspline/mesh/triangle_mesh.h"

namespace volspline {

/// OBJ: `v x y z` (extra numbers such as w or colours are ignored), `f` with 3 or more vertices
/// (triangulated as a fan from the first), each `i`, `i/t`, `i//n` or `i/t/n`, 1-based or
/// negative (relative to the vertices read so far). `g part_N` sets the part of the following
/// faces to N, as obj_bytes writes it; any other group, and no group, is part
/// kUnnamedPartNumber (mesh/parts.h). Other statements (vt, vn, o, s, usemtl, mtllib, l, p, ...)
/// are ignored. Parameters are (0, 0, 0).
/// \throw InvalidInput naming `source` and the line if the text is not a valid OBJ mesh.
TriangleMesh parse_obj(std::string_view bytes, const std::string& source);

/// PLY 1.0, ascii, binary_little_endian or binary_big_endian. Element "vertex" needs x, y, z
/// and may have u, v, w (the parameters, else 0); element "face" needs a list property
/// vertex_indices (or vertex_index) of 3 or more vertices (fans), and may have an integer
/// property part (else kUnnamedPartNumber). Any scalar type (char/int8 ... double/float64) is
/// accepted for any property; other elements and properties are skipped.
/// \throw InvalidInput naming `source` and where if the bytes are not a valid PLY mesh.
TriangleMesh parse_ply(std::string_view bytes, const std::string& source);

/// STL, binary unless the file starts with "solid" and is not exactly the size a binary file
/// with its declared triangle count would have (some binary writers begin the header with
/// "solid" too). Identical positions are welded into one vertex (STL stores each triangle's
/// corners separately); triangles are kept in file order, parts are kUnnamedPartNumber,
/// parameters (0, 0, 0).
/// \throw InvalidInput naming `source` and where if the bytes are not a valid STL mesh.
TriangleMesh parse_stl(std::string_view bytes, const std::string& source);

/// OFF (Geomview; what CGAL's data files and Debian's mesh packages ship): "OFF", the vertex,
/// face and edge counts, the vertices, then faces "k i_0 .. i_{k-1}" (fans; colours after the
/// indices ignored); '#' comments. Read only (volspline writes PLY, OBJ, STL and glTF); parts are
/// kUnnamedPartNumber, parameters (0, 0, 0).
/// \throw InvalidInput naming `source` and the line if the text is not a valid OFF mesh.
TriangleMesh parse_off(std::string_view bytes, const std::string& source);

/// The parser of `format`. \throw InvalidInput as that parser, or for a format without one.
TriangleMesh parse_mesh(std::string_view bytes, MeshFormat format, const std::string& source);

/// Reads the mesh in `path`, in the format its extension names (mesh_format_from_path, or .off
/// for parse_off); errors
/// name the path as given.
/// \throw IoError if the file cannot be read, InvalidInput if it is not a valid mesh or the
/// extension is unknown.
TriangleMesh read_mesh(const std::filesystem::path& path);

}  // namespace volspline
