// libFuzzer target for the VTK .vtu reader: any bytes either parse or throw a volspline::Error;
// anything else (a crash, another exception, a sanitizer report, a hang, unbounded memory) is a
// bug. A file that parses is written and parsed again, and written again: the second text must
// equal the first (the writer keeps every number, the reader reads every number back).
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <string>
#include <string_view>

#include "volspline/core/error.h"
#include "volspline/io/vtk_xml.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string_view text(reinterpret_cast<const char*>(data), size);
  volspline::Model model;
  try {
    model = volspline::parse_vtu(text, "fuzz");
  } catch (const volspline::Error&) {
    return 0;
  }
  std::string written;
  try {
    written = volspline::vtu_text(model);
  } catch (const volspline::InvalidInput&) {
    return 0;  // a model the format cannot hold (an attribute name that clashes, ...)
  }
  const std::string again = volspline::vtu_text(volspline::parse_vtu(written, "written"));
  if (again != written) {
    std::fprintf(stderr, "vtu_reader_fuzz: writing what was read changed the text\n");
    std::abort();
  }
  return 0;
}
