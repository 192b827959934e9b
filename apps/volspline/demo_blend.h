#pragma once
#include "demo_gallery.h"

namespace volspline::cli {

/// Writes the Peters-Wittman figures 1a .. 4c (mesh .ply and picture .png each) that `demo`
/// wants, and adds them to its gallery with the `volspline blend` commands that make them from
/// the figures' scene files (written into the demo folder's examples/scenes).
void write_blend_demo(DemoRun& demo);

}  // namespace volspline::cli
