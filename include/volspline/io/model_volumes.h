#pragma once
// The volume objects of a model (bspline_volume and bezier_volume), visited in file order with
// every error located at the object's place in the file ("model.json: objects[2]"), as the
// model readers locate theirs. Whatever works on solids one volume at a time (faces, boundary,
// Jacobian certificates, views) loops through here.
#include <cstddef>
#include <functional>
#include <string>

#include "volspline/io/model_file.h"

namespace volspline {

/// "SOURCE: objects[INDEX]", or "objects[INDEX]" for an empty `source_name`: where an error
/// about one object of a model read from `source_name` is (the style of parse_model's messages).
std::string object_location(const std::string& source_name, std::size_t index);

/// The number of volume objects of `model`.
std::size_t count_volumes(const Model& model);

/// Calls `visit(index, object, volume)` for every volume object of `model`, in order. Curves,
/// surfaces, hypervolumes and swept solids are skipped.
/// \return the number of volumes visited (at least 1).
/// \throw InvalidInput located at `source_name` if the model has no volume objects (before any
/// call); an InvalidInput from `visit`, rethrown located at object_location(source_name, index);
/// anything else `visit` throws, unchanged.
std::size_t for_each_volume(const Model& model, const std::string& source_name,
                            const std::function<void(std::size_t index, const ModelObject& object, const BSplineVolume& volume)>& visit);

}  // namespace volspline
