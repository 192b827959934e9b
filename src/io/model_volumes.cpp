#include "volspline/io/model_volumes.h"

#include "volspline/core/error.h"

namespace volspline {

std::string object_location(const std::string& source_name, std::size_t index) {
  const std::string object = "objects[" + std::to_string(index) + "]";
  return source_name.empty() ? object : source_name + ": " + object;
}

std::size_t count_volumes(const Model& model) {
  std::size_t count = 0;
  for (const ModelObject& object : model.objects) count += std::holds_alternative<BSplineVolume>(object.spline);
  return count;
}

std::size_t for_each_volume(const Model& model, const std::string& source_name,
                            const std::function<void(std::size_t index, const ModelObject& object, const BSplineVolume& volume)>& visit) {
  if (count_volumes(model) == 0) {
    std::size_t four_variate = 0;
    for (const ModelObject& object : model.objects)
      four_variate += is_swept_solid(object) || std::holds_alternative<BSplineHypervolume>(object.spline);
    throw InvalidInput(std::string("the model has no volume objects (bspline_volume or bezier_volume)") +
                           (four_variate ? "; swept solids and hypervolumes are skipped: they are 4-variate (the swept volume is their envelope)" : ""),
                       source_name);
  }
  std::size_t visited = 0;
  for (std::size_t i = 0; i < model.objects.size(); ++i) {
    const auto* volume = std::get_if<BSplineVolume>(&model.objects[i].spline);
    if (volume == nullptr) continue;
    try {
      visit(i, model.objects[i], *volume);
    } catch (const InvalidInput& e) {
      throw e.located(object_location(source_name, i));
    }
    ++visited;
  }
  return visited;
}

}  // namespace volspline
