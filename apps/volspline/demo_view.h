#pragma once

namespace volspline::cli {

class DemoRun;

/// Writes Lasser 1994 §IV's ways of looking inside a solid (Figs. 8-13, a paddlewheel, colouring
/// by the Jacobian and by a material attribute) as `view-*.png`, each a `volspline view` command
/// run exactly as the gallery prints it (inside the demo folder). The models viewed are those
/// the demo writes (bent-tricubic.json, half-torus.json, twisted-loft.json; written here too
/// when absent, for `demo --only`) and torus-temperature.json, written here.
void write_view_demo(DemoRun& demo);

}  // namespace volspline::cli
