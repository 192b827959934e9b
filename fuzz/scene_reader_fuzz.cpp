// libFuzzer target for scene files: every input either parses or raises volspline::Error, and a
// parsed scene survives a write/read round trip with the same tree shape. Nothing is meshed
// (that would measure the mesher, not the parser).
#include <cstddef>
#include <cstdint>
#include <string>
#include <string_view>

#include "volspline/boxspline/scene_file.h"
#include "volspline/core/error.h"

namespace {

bool same_shape(const volspline::SceneNode& a, const volspline::SceneNode& b) {
  if (a.operation != b.operation || a.children.size() != b.children.size()) return false;
  if (a.operation == volspline::SceneOperation::Primitive && a.primitive.kind != b.primitive.kind) return false;
  for (std::size_t i = 0; i < a.children.size(); ++i)
    if (!same_shape(a.children[i], b.children[i])) return false;
  return true;
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string_view text(reinterpret_cast<const char*>(data), size);
  volspline::Scene scene;
  try {
    scene = volspline::parse_scene(text, "fuzz.json");
  } catch (const volspline::Error&) {
    return 0;
  }
  const volspline::Scene again = volspline::parse_scene(volspline::scene_to_json(scene), "round-trip.json");
  if (!same_shape(scene.root, again.root)) __builtin_trap();
  return 0;
}
