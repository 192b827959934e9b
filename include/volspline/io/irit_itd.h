#pragma once
// IRIT data files (.itd, Gershon Elber's IRIT solid modeller): B-spline and Bézier curves
// ([CURVE BSPLINE ...]), surfaces ([SURFACE BSPLINE ...]) and trivariates ([TRIVAR BSPLINE ...]),
// possibly inside [OBJECT NAME ...] lists. Conventions, what is kept and what is lost:
// docs/formats.md.
//
// IRIT's conventions, which this reader follows:
// * the header gives the control-point counts, then the ORDERS (degree + 1) per direction
//   (BSPLINE only; a Bézier's order is its count), then the point type: En (n Cartesian
//   coordinates) or Pn (rational: the weight first, then the n coordinates multiplied by it,
//   i.e. the homogeneous point (w, w x1, ..., w xn));
// * knot vectors follow as [KV t0 t1 ...] with count + order knots each ([KVP ...], periodic, is
//   not supported);
// * control points follow one per [...], the first direction fastest.
#include <cstddef>
#include <filesystem>
#include <string>
#include <string_view>

#include "volspline/io/model_file.h"

namespace volspline {

/// [OBJECT ...] lists may nest at most this deep (as JSON nests at most kMaxJsonDepth): the
/// reader recurses into them, and a file of thousands of nested OBJECTs must be refused rather
/// than exhaust the stack. IRIT's own files nest a few levels.
inline constexpr std::size_t kMaxIritObjectDepth = 64;

/// Parses the text of an IRIT data file. Every curve, surface and trivariate becomes one object,
/// in file order, named after the innermost [OBJECT NAME ...] around it ("NONE" reads as no name).
/// \throw InvalidInput "SOURCE: line L: what was expected, got what" for a bad token, a wrong count
/// of knots or control points, an unsupported object ([POLYGON ...], periodic knots), a missing
/// bracket, OBJECTs nested deeper than kMaxIritObjectDepth or an invalid spline.
Model parse_irit_itd(std::string_view text, const std::string& source_name);

/// Reads and parses an IRIT data file. \throw IoError, InvalidInput as parse_irit_itd.
Model read_irit_itd(const std::filesystem::path& path);

/// The IRIT text of `model`: one [OBJECT NAME [CURVE|SURFACE|TRIVAR BSPLINE ...]] per object,
/// numbers with 17 significant digits (homogeneous coefficients for rational objects, so reading
/// the text gives back every coefficient bit for bit). Names are reduced to letters, digits and
/// '_' (an empty name is written NONE); metadata and attributes are not written.
/// \throw InvalidInput for a spline of more than 9 coordinates (IRIT's point types stop at E9/P9).
std::string irit_itd_text(const Model& model);

/// Writes irit_itd_text(model) atomically. \throw IoError, InvalidInput as irit_itd_text.
void write_irit_itd(const Model& model, const std::filesystem::path& path);

}  // namespace volspline
