#include "volspline/pipeline/model_summary.h"

#include <algorithm>
#include <variant>

#include "volspline/mesh/tetrahedral_mesh.h"
#include "volspline/spline/affine_map.h"

namespace volspline {

namespace {

template <int D>
nlohmann::json summary_of(const TensorSpline<D>& s) {
  nlohmann::json j;
  const auto [lo, hi] = bounding_box(s, 2);  // Bézier pieces halved twice: tight to about 1e-2 of a cell
  for (int d = 0; d < D; ++d) {
    const auto& kv = s.knot_vector(d);
    j["degree"].push_back(kv.degree());
    j["control_points"].push_back(s.num_control_points()[static_cast<std::size_t>(d)]);
    j["knot_spans"].push_back(kv.num_spans());
    j["domain"].push_back({kv.domain_min(), kv.domain_max()});
    j["clamped"].push_back(kv.is_clamped());
  }
  j["dimension"] = s.dimension();
  j["rational"] = s.is_rational();
  j["points_at_infinity"] = std::count(s.weights().begin(), s.weights().end(), 0.0);
  j["bounding_box"] = {{"min", std::vector<double>(lo.data(), lo.data() + lo.size())},
                       {"max", std::vector<double>(hi.data(), hi.data() + hi.size())}};
  return j;
}

// A swept solid: its generator, path and frame (the hypervolume patches are made on demand).
nlohmann::json summary_of(const SweptSolid& s) {
  nlohmann::json j;
  j["generator_patches"] = s.generator.size();
  j["path"] = summary_of(s.path);
  j["frame"] = s.frame_name;
  j["frame_fit_error"] = s.frame_fit_error;
  return j;
}

// A simplex spline volume (Hua–He–Qin): its domain, knot clouds, control vectors and attributes.
nlohmann::json summary_of(const DmsSplineVolume& s) {
  nlohmann::json j;
  j["degree"] = s.degree();
  j["domain_points"] = s.domain().points.size();
  j["tetrahedra"] = s.domain().tetrahedra.size();
  j["knots"] = s.knots().knots.size();
  j["domain_volume"] = tetrahedral_mesh_volume(s.domain());
  j["control"] = s.sharing() == DmsControlSharing::Shared ? "shared" : "per_tetrahedron";
  j["control_points"] = s.control_vector_count();
  j["attributes"] = s.attribute_names();
  const Eigen::MatrixXd& c = s.control_vectors();
  const Eigen::Vector3d lo = c.leftCols<3>().colwise().minCoeff().transpose(), hi = c.leftCols<3>().colwise().maxCoeff().transpose();
  j["control_box"] = {{"min", {lo.x(), lo.y(), lo.z()}}, {"max", {hi.x(), hi.y(), hi.z()}}};
  for (std::size_t a = 0; a < s.attribute_names().size(); ++a) {
    const auto column = c.col(static_cast<Eigen::Index>(3 + a));
    j["attribute_ranges"][s.attribute_names()[a]] = {column.minCoeff(), column.maxCoeff()};
  }
  return j;
}

}  // namespace

nlohmann::json model_object_summaries(const Model& model) {
  nlohmann::json objects = nlohmann::json::array();
  for (std::size_t i = 0; i < model.objects.size(); ++i) {
    const ModelObject& object = model.objects[i];
    nlohmann::json j = std::visit([](const auto& s) { return summary_of(s); }, object.spline);
    j["index"] = i;
    j["type"] = object_type_name(object);
    if (!object.name.empty()) j["name"] = object.name;
    objects.push_back(std::move(j));
  }
  return objects;
}

}  // namespace volspline
