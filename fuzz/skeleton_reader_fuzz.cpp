// libFuzzer target for the skeleton reader: any bytes either parse or throw a volspline::Error.
// A skeleton that parses is evaluated at one point (every element's distance runs), written,
// parsed again and written again: the two texts must be equal and the field values bit for bit.
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <optional>
#include <string>
#include <string_view>

#include "volspline/core/error.h"
#include "volspline/io/skeleton_file.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string_view text(reinterpret_cast<const char*>(data), size);
  std::optional<volspline::SkeletonField> field;
  try {
    field.emplace(volspline::parse_skeleton(text, "fuzz.json"));
  } catch (const volspline::Error&) {
    return 0;  // rejected: fine, as long as it is a volspline::Error
  }
  const Eigen::Vector3d x(0.25, -0.5, 0.125);
  const double value = (*field)(x);
  const std::string written = volspline::skeleton_to_json(*field);
  std::optional<volspline::SkeletonField> again;
  try {
    again.emplace(volspline::parse_skeleton(written, "written.json"));
  } catch (const volspline::Error& e) {
    std::fprintf(stderr, "skeleton_reader_fuzz: written skeleton does not parse: %s\n%s\n", e.what(), written.c_str());
    std::abort();
  }
  const double value_again = (*again)(x);
  if (std::memcmp(&value, &value_again, sizeof value) != 0 && !(value != value && value_again != value_again)) {
    std::fprintf(stderr, "skeleton_reader_fuzz: round trip changed the field value\n");
    std::abort();
  }
  if (volspline::skeleton_to_json(*again) != written) {
    std::fprintf(stderr, "skeleton_reader_fuzz: round trip changed the written text\n");
    std::abort();
  }
  return 0;
}
