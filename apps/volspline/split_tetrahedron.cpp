// volspline split-tetrahedron MODEL --tetrahedron I [--at X,Y,Z] -o OUT.json: local refinement of
// a simplex spline volume (Hua–He–Qin §4, §5.4; simplex/local_refinement.h): the tetrahedron split
// 1 → 4 at a new primary knot (its centroid by default), the spline re-fitted, the error printed.
#include <iostream>
#include <memory>
#include <string>

#include "cli_support.h"
#include "commands.h"
#include "volspline/core/error.h"
#include "volspline/core/format.h"
#include "volspline/io/model_file.h"
#include "volspline/simplex/local_refinement.h"

namespace volspline::cli {

void add_split_tetrahedron_command(CLI::App& app) {
  auto tetrahedron = std::make_shared<int>(-1);
  auto at = std::make_shared<std::string>();
  auto out = std::make_shared<std::string>();
  auto* cmd = app.add_subcommand("split-tetrahedron", "Refine a simplex spline volume: split one domain tetrahedron 1 -> 4 at a new "
                                                      "knot and re-fit the spline (prints the re-fit error)");
  const auto input = add_model_input(cmd);
  cmd->add_option("--tetrahedron", *tetrahedron, "index of the domain tetrahedron to split")->required();
  cmd->add_option("--at", *at, "X,Y,Z of the new knot, strictly inside (default: the centroid)");
  cmd->add_option("-o,--output", *out, "output model file (.json)")->required();
  cmd->callback([=] {
    Model model = input->read();
    for (std::size_t i = 0; i < model.objects.size(); ++i) {
      auto* volume = std::get_if<DmsSplineVolume>(&model.objects[i].spline);
      if (volume == nullptr) continue;
      const auto& tets = volume->domain().tetrahedra;
      if (*tetrahedron < 0 || static_cast<std::size_t>(*tetrahedron) >= tets.size())
        throw InvalidInput("expected a tetrahedron from 0 to " + std::to_string(tets.size() - 1) + ", got " + std::to_string(*tetrahedron),
                           "--tetrahedron");
      Eigen::Vector3d point = Eigen::Vector3d::Zero();
      if (at->empty()) {
        for (int c = 0; c < 4; ++c) point += volume->domain().points[static_cast<std::size_t>(tets[static_cast<std::size_t>(*tetrahedron)][static_cast<std::size_t>(c)])] / 4;
      } else {
        const auto p = parse_numbers(*at, 3, "--at");
        point = Eigen::Vector3d(p[0], p[1], p[2]);
      }
      LocalRefinementReport report;
      DmsSplineVolume refined = [&] {
        try {
          return refine_tetrahedron(*volume, *tetrahedron, point, &report);
        } catch (const InvalidInput& e) {
          throw InvalidInput(e.message(), "--at");
        }
      }();
      model.objects[i].spline = std::move(refined);
      write_model(model, *out);
      std::cout << "wrote " << *out << ": tetrahedron " << *tetrahedron << " split at (" << format_double(point.x()) << ", "
                << format_double(point.y()) << ", " << format_double(point.z()) << "), knot clouds "
                << (report.clouds_kept ? "kept" : "regenerated") << "; re-fit error max " << format_double(report.max_error) << ", rms "
                << format_double(report.rms_error) << " over " << report.samples << " samples\n";
      return;
    }
    throw InvalidInput(input->path + " has no simplex_spline_volume object", "MODEL");
  });
}

}  // namespace volspline::cli
