#pragma once
// G+Smo XML files (the <xml> documents of github.com/gismo/gismo): B-spline and NURBS curves
// (BSpline, Nurbs), surfaces (TensorBSpline2, TensorNurbs2) and volumes (TensorBSpline3,
// TensorNurbs3), and the patch topology of multipatch files (<MultiPatch>). Conventions, what is
// kept and what is lost: docs/formats.md.
//
// G+Smo's conventions, which this reader follows:
// * coefficients are listed one control point per row, first parameter direction fastest (the
//   same order as volspline's, core/conventions.h);
// * NURBS coefficients are Cartesian, the weights sit in the rational basis, and the geometry is
//   sum_i R_i(t) c_i with R_i = w_i N_i / sum_j w_j N_j. A weight-0 coefficient therefore has no
//   influence at all (volspline would read it as a point at infinity), so the reader zeroes its
//   coordinates, and the writer refuses volspline points at infinity with nonzero direction.
#include <filesystem>
#include <string>
#include <string_view>

#include "volspline/io/model_file.h"

namespace volspline {

/// Parses a G+Smo XML document. Every direct <Geometry> child of the root <xml> element becomes
/// one object, in document order; its `id` attribute is kept as object metadata {"gismo": {"id":
/// N}}. Each <MultiPatch> is kept as model metadata {"gismo": {"multipatch": [{"id", "parDim",
/// "patches": [ids], "interfaces": [[...], ...], "boundary": [[patch, side], ...]}]}} with
/// G+Smo's numbers unchanged (sides 1..6 = u min, u max, v min, v max, w min, w max).
/// \throw InvalidInput "SOURCE: line L, /xml/Geometry[2]/coefs: what was expected, got what" for
/// malformed XML, a missing or malformed knot vector, a wrong number of coefficients or weights,
/// an unsupported geometry type, or a multipatch naming a patch id that no geometry has.
Model parse_gismo_xml(std::string_view text, const std::string& source_name);

/// Reads and parses a G+Smo XML file. \throw IoError if it cannot be read, InvalidInput as
/// parse_gismo_xml.
Model read_gismo_xml(const std::filesystem::path& path);

/// The G+Smo XML text of `model`: one <Geometry> per object (id from the object's "gismo"
/// metadata, else its index), and the <MultiPatch> elements kept in the model's "gismo"
/// metadata. Numbers have 17 significant digits, so reading the text gives back every double.
/// Names, other metadata and attributes are not written (G+Smo has no place for them).
/// \throw InvalidInput for a point at infinity with nonzero direction (G+Smo cannot hold it) or
/// malformed "gismo" metadata.
std::string gismo_xml_text(const Model& model);

/// Writes gismo_xml_text(model) atomically. \throw IoError, InvalidInput as gismo_xml_text.
void write_gismo_xml(const Model& model, const std::filesystem::path& path);

}  // namespace volspline
