#include "volspline/io/model_formats.h"

#include <algorithm>
#include <array>
#include <cctype>
#include <cmath>
#include <functional>
#include <type_traits>
#include <vector>

#include "volspline/core/coordinate_range.h"
#include "volspline/core/error.h"
#include "volspline/core/format.h"
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
  try {
    check_coordinate_range(model);  // what no reader would accept is not written
  } catch (const InvalidInput& e) {
    throw InvalidInput(e.message(), path.string() + ": " + e.where());
  }
  write_file_atomically(path, f.text(model));
}

// check_coordinate_range (io/coordinate_range.h) lives here, beside the dispatcher that every
// reader and writer goes through.
namespace {

std::string coordinate_location(const std::string& path, std::size_t i, std::size_t c) {
  return path + "[" + std::to_string(i) + "][" + std::to_string(c) + "]";
}

// `count` points of `dimension` numbers at `points` (point i's coordinates at points + i * stride),
// those with skip(i) true being directions; `path` names the array ("control_points"). The rule
// is core/coordinate_range.h's, located at the number's JSON path.
void check_coordinate_array(const double* points, std::size_t count, std::size_t dimension, std::size_t stride,
                            const std::function<bool(std::size_t)>& skip, const std::string& path) {
  check_point_coordinate_range(
      points, count, dimension, stride, [&](std::size_t i, std::size_t c) { return coordinate_location(path, i, c); }, path,
      "control points", "docs/model-format.md", skip);
}

template <int D>
void check_spline_coordinates(const TensorSpline<D>& spline, const std::string& prefix) {
  const std::vector<double>& w = spline.weights();
  check_coordinate_array(
      spline.points().data(), static_cast<std::size_t>(spline.num_control_points_total()), static_cast<std::size_t>(spline.dimension()),
      static_cast<std::size_t>(spline.dimension()), [&](std::size_t i) { return !w.empty() && w[i] == 0.0; }, prefix + "control_points");
}

}  // namespace

void check_coordinate_range(const Model& model) {
  for (std::size_t o = 0; o < model.objects.size(); ++o) {
    const std::string at = "objects[" + std::to_string(o) + "].";
    std::visit(
        [&](const auto& spline) {
          using T = std::decay_t<decltype(spline)>;
          if constexpr (std::is_same_v<T, SweptSolid>) {
            for (std::size_t g = 0; g < spline.generator.size(); ++g)
              check_spline_coordinates(spline.generator[g], at + "generator[" + std::to_string(g) + "].");
            check_spline_coordinates(spline.path, at + "path.");
            for (std::size_t k = 0; k < 3; ++k) check_spline_coordinates(spline.frame[k], at + "frame.curves[" + std::to_string(k) + "].");
          } else if constexpr (std::is_same_v<T, DmsSplineVolume>) {
            const auto& points = spline.domain().points;
            if (!points.empty())
              check_coordinate_array(points.front().data(), points.size(), 3, 3, [](std::size_t) { return false; }, at + "domain.points");
            // The geometry is the first three entries of each control vector (row-major copy:
            // Eigen stores columns).
            const Eigen::MatrixXd& control = spline.control_vectors();
            std::vector<double> xyz(static_cast<std::size_t>(control.rows()) * 3);
            for (Eigen::Index r = 0; r < control.rows(); ++r)
              for (Eigen::Index c = 0; c < 3 && c < control.cols(); ++c) xyz[static_cast<std::size_t>(r * 3 + c)] = control(r, c);
            check_coordinate_array(xyz.data(), static_cast<std::size_t>(control.rows()), 3, 3, [](std::size_t) { return false; },
                         at + "control_vectors");
          } else {
            check_spline_coordinates(spline, at);
          }
        },
        model.objects[o].spline);
  }
}

}  // namespace volspline
