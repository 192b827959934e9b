#pragma once
#include "demo_gallery.h"

namespace volspline::cli {

/// Writes the Peters-Wittman figures 1a .. 4c (mesh .ply and picture .png each) that `demo`
/// wants, and adds them to its gallery.
void write_blend_demo(DemoRun& demo);

}  // namespace volspline::cli
