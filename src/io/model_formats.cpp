#include "volspline/io/model_formats.h"

#include <algorithm>
#include <array>
#include <cctype>

#include "volspline/core/error.h"
#include "volspline/io/atomic_file.h"
#include "volspline/io/coordinate_range.h"
#include "volspline/io/gismo_xml.h"
#include "volspline/io/irit_itd.h"
#include "volspline/io/vtk_xml.h"

namespace volspline {

namespace {

const std::array<ModelFormat, 4> kFormats{{
    {"json", ".json", "volspline model file (docs/model-format.md)", parse_model, model_to_json},
    {"gismo", ".xml", "G+Smo XML: BSpline, Nurbs, TensorBSpline2/3, TensorNurbs2/3, MultiPatch", parse_gismo_xml,
     gismo_xml_text},
    {"irit", ".itd", "IRIT data file: CURVE, SURFACE, TRIVAR (BSPLINE, BEZIER)", parse_irit_itd, irit_itd_text},
    {"vtu", ".vtu", "VTK XML unstructured grid of rational Bezier cells (ParaView)", parse_vtu, vtu_text},
}};

std::string lowercase(std::string_view text) {
  std::string out(text);
  std::transform(out.begin(), out.end(), out.begin(), [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  return out;
}

std::string list(bool extensions) {
  std::string out;
  for (const ModelFormat& f : kFormats) out += (out.empty() ? "" : ", ") + std::string(extensions ? f.extension : f.name);
  return out;
}

}  // namespace

std::span<const ModelFormat> model_formats() { return kFormats; }

const ModelFormat& model_format_from_path(const std::filesystem::path& path, std::string_view format_option) {
  const std::string extension = lowercase(path.extension().string());
  for (const ModelFormat& f : kFormats) {
    if (extension == f.extension) return f;
  }
  throw InvalidInput("cannot tell the model format of '" + path.string() + "': expected the extension " + list(true) +
                     " (or name the format with " + std::string(format_option) + " " + list(false) + ")");
}

const ModelFormat& model_format_named(std::string_view name) {
  const std::string wanted = lowercase(name);
  for (const ModelFormat& f : kFormats) {
    if (wanted == f.name || wanted == f.extension || wanted == f.extension + 1) return f;
  }
  throw InvalidInput("unknown model format '" + std::string(name) + "': expected one of " + list(false));
}

Model read_model_file(const std::filesystem::path& path, std::string_view format) {
  // Every command that reads a model names its format option --input-format.
  const ModelFormat& f = format.empty() ? model_format_from_path(path, "--input-format") : model_format_named(format);
  return f.parse(read_file(path), path.string());
}

void write_model_file(const Model& model, const std::filesystem::path& path, std::string_view format) {
  const ModelFormat& f = format.empty() ? model_format_from_path(path) : model_format_named(format);
  check_coordinate_range(model);  // what no reader would accept is not written
  write_file_atomically(path, f.text(model));
}

}  // namespace volspline
