#pragma once
// Free-form deformation of a whole model (Lasser 1994 §III.2): every curve and surface composed
// exactly with the lattice's map (deform/ffd.h, compose), as `volspline ffd LATTICE MODEL.json`
// does.
#include <string>

#include "volspline/deform/lattice.h"
#include "volspline/io/model_file.h"

namespace volspline {

/// `model` with every curve and surface replaced by its exact image under `lattice`, each
/// written as a B-spline object (the composition is no longer one Bézier span on [0, 1] in
/// general); names and metadata kept.
/// \throw InvalidInput located at object_location(source_name, i) (io/model_volumes.h) for a
/// volume object ("type": volumes are deformed by composing their control points) or as compose.
Model deform_model(const Lattice& lattice, Model model, const std::string& source_name = {});

}  // namespace volspline
