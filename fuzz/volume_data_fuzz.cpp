// libFuzzer target for the text parsing of volume data: the same bytes as CSV, as an INRIMAGE
// header with data, and as PLY either parse or throw a volspline::Error. Parsed data must be
// valid (finite, consistent sizes), and CSV written back from parsed CSV must parse to the same
// values bit for bit.
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <optional>
#include <sstream>
#include <string>
#include <string_view>

#include "volspline/core/error.h"
#include "volspline/io/volume_data.h"

namespace {

void check_valid(const volspline::VolumeData& data, const char* what) {
  try {
    volspline::validate_volume_data(data, what);
  } catch (const volspline::Error& e) {
    std::fprintf(stderr, "volume_data_fuzz: %s parsed to invalid data: %s\n", what, e.what());
    std::abort();
  }
}

std::string as_csv(const volspline::VolumeData& data) {
  std::ostringstream out;
  out.precision(17);
  out << "x,y,z";
  for (const auto& name : data.attribute_names) out << "," << name;
  out << "\n";
  for (std::size_t i = 0; i < data.size(); ++i) {
    out << data.points[i].x() << "," << data.points[i].y() << "," << data.points[i].z();
    for (Eigen::Index a = 0; a < data.attributes.cols(); ++a) out << "," << data.attributes(static_cast<Eigen::Index>(i), a);
    out << "\n";
  }
  return out.str();
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* bytes, std::size_t size) {
  const std::string_view text(reinterpret_cast<const char*>(bytes), size);
  std::optional<volspline::VolumeData> csv;
  try {
    csv.emplace(volspline::parse_volume_csv(text, "fuzz.csv"));
  } catch (const volspline::Error&) {
  }
  if (csv) {
    check_valid(*csv, "CSV");
    bool names_survive = true;  // names with commas, quotes or leading '#' do not survive a plain writer
    for (const auto& name : csv->attribute_names)
      names_survive = names_survive && name.find_first_of(",\"#\n\r \t") == std::string::npos;
    if (names_survive) {
      const std::string written = as_csv(*csv);
      try {
        const volspline::VolumeData again = volspline::parse_volume_csv(written, "written.csv");
        if (again.points != csv->points || again.attributes != csv->attributes || again.attribute_names != csv->attribute_names) {
          std::fprintf(stderr, "volume_data_fuzz: CSV round trip changed the data\n%s\n", written.c_str());
          std::abort();
        }
      } catch (const volspline::Error& e) {
        std::fprintf(stderr, "volume_data_fuzz: written CSV does not parse: %s\n%s\n", e.what(), written.c_str());
        std::abort();
      }
    }
  }
  for (int format = 0; format < 2; ++format) {
    try {
      const volspline::VolumeData data =
          format == 0 ? volspline::parse_inrimage(text, "fuzz.inr") : volspline::parse_volume_ply(text, "fuzz.ply");
      check_valid(data, format == 0 ? "INR" : "PLY");
    } catch (const volspline::Error&) {
    }
  }
  return 0;
}
