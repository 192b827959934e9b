// libFuzzer target for the mesh readers: any bytes, read as OBJ, PLY, STL and OFF in turn, either
// parse or throw a volspline::Error. Anything else (a crash, another exception, a sanitizer
// report, a hang, memory out of proportion to the input) is a bug. A mesh that parses must be
// well formed (validate_mesh) and survive a PLY write/read round trip bit for bit.
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <string>
#include <string_view>

#include "volspline/core/error.h"
#include "volspline/mesh/mesh_checks.h"
#include "volspline/mesh/mesh_reader.h"
#include "volspline/mesh/mesh_writer.h"

namespace {

[[noreturn]] void bug(const char* what) {
  std::fprintf(stderr, "mesh_reader_fuzz: %s\n", what);
  std::abort();
}

void check(const volspline::TriangleMesh& mesh) {
  try {
    volspline::validate_mesh(mesh);
  } catch (const volspline::Error& e) {
    std::fprintf(stderr, "%s\n", e.what());
    bug("a parsed mesh is malformed");
  }
  for (const bool ascii : {false, true}) {
    volspline::TriangleMesh again;
    try {
      again = volspline::parse_ply(volspline::ply_bytes(mesh, ascii), "written.ply");
    } catch (const volspline::Error& e) {
      std::fprintf(stderr, "%s\n", e.what());
      bug("a written PLY does not parse");
    }
    if (again.positions != mesh.positions || again.parameters != mesh.parameters || again.triangles != mesh.triangles ||
        again.parts != mesh.parts) {
      bug("the PLY round trip changed the mesh");
    }
  }
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string_view bytes(reinterpret_cast<const char*>(data), size);
  for (const auto format : {volspline::MeshFormat::Obj, volspline::MeshFormat::Ply, volspline::MeshFormat::Stl}) {
    volspline::TriangleMesh mesh;
    try {
      mesh = volspline::parse_mesh(bytes, format, "fuzz");
    } catch (const volspline::Error&) {
      continue;  // rejected: fine, as long as it is a volspline::Error
    }
    check(mesh);
  }
  volspline::TriangleMesh off;
  try {
    off = volspline::parse_off(bytes, "fuzz.off");
  } catch (const volspline::Error&) {
    return 0;
  }
  check(off);
  return 0;
}
