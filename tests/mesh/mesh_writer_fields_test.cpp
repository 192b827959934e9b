// A field on a mesh survives export: PLY carries the values as one more vertex property, glTF
// carries the colours they were drawn with.
#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <sstream>
#include <tiny_gltf.h>

#include "support/test_meshes.h"
#include "volspline/core/error.h"
#include "volspline/mesh/mesh_reader.h"
#include "volspline/mesh/mesh_writer.h"

namespace volspline {
namespace {

std::vector<double> field_of(const TriangleMesh& mesh) {
  std::vector<double> f;
  for (const auto& p : mesh.positions) f.push_back(p.x() - 2 * p.y() + 0.125 * p.z());
  return f;
}

TEST(PlyScalar, AsciiAndBinaryCarryTheValuesAfterTheParameters) {
  const TriangleMesh cube = test_support::unit_cube();
  const auto f = field_of(cube);
  const std::string text = ply_bytes(cube, true, f, "jacobian");
  EXPECT_NE(text.find("property double w\nproperty double jacobian\n"), std::string::npos);
  // Every vertex line has seven numbers, the last being the field.
  std::istringstream in(text.substr(text.find("end_header\n") + 11));
  for (std::size_t v = 0; v < cube.num_vertices(); ++v) {
    double values[7];
    for (double& x : values) in >> x;
    EXPECT_EQ(values[6], f[v]);
    EXPECT_EQ(values[0], cube.positions[v].x());
  }
  const std::string binary = ply_bytes(cube, false, f, "jacobian");
  const std::size_t body = binary.find("end_header\n") + 11;
  for (std::size_t v = 0; v < cube.num_vertices(); ++v) {
    double x;
    std::memcpy(&x, binary.data() + body + 56 * v + 48, 8);
    EXPECT_EQ(x, f[v]);
  }
  // Our reader skips the extra property and still reads the geometry.
  for (const std::string& bytes : {text, binary}) {
    const TriangleMesh back = parse_ply(bytes, "test.ply");
    EXPECT_EQ(back.positions, cube.positions);
    EXPECT_EQ(back.triangles, cube.triangles);
  }
  EXPECT_THROW(ply_bytes(cube, true, {1.0, 2.0}, "f"), InvalidInput);
  EXPECT_THROW(ply_bytes(cube, true, f, "two words"), InvalidInput);
}

TEST(GlbVertexColors, CornersCarryTheGivenColoursInLinearSpace) {
  const TriangleMesh cube = test_support::unit_cube();
  std::vector<Eigen::Vector3d> colors;
  for (const auto& p : cube.positions) colors.push_back(0.25 * p + Eigen::Vector3d::Constant(0.5));
  const std::string bytes = glb_bytes(cube, colors);
  tinygltf::Model model;
  tinygltf::TinyGLTF loader;
  std::string error, warning;
  ASSERT_TRUE(loader.LoadBinaryFromMemory(&model, &error, &warning, reinterpret_cast<const unsigned char*>(bytes.data()),
                                          static_cast<unsigned>(bytes.size())))
      << error;
  const auto& primitive = model.meshes.at(0).primitives.at(0);
  auto floats = [&](int accessor_index) {
    const auto& accessor = model.accessors.at(static_cast<std::size_t>(accessor_index));
    const auto& view = model.bufferViews.at(static_cast<std::size_t>(accessor.bufferView));
    std::vector<float> out(3 * accessor.count);
    std::memcpy(out.data(), model.buffers[0].data.data() + view.byteOffset + accessor.byteOffset, out.size() * sizeof(float));
    return out;
  };
  const auto positions = floats(primitive.attributes.at("POSITION"));
  const auto gl_colors = floats(primitive.attributes.at("COLOR_0"));
  auto linear = [](double c) { return c <= 0.04045 ? c / 12.92 : std::pow((c + 0.055) / 1.055, 2.4); };
  ASSERT_EQ(positions.size(), gl_colors.size());
  for (std::size_t k = 0; k < positions.size() / 3; ++k) {
    const Eigen::Vector3d p(positions[3 * k], positions[3 * k + 1], positions[3 * k + 2]);
    const Eigen::Vector3d srgb = 0.25 * p + Eigen::Vector3d::Constant(0.5);
    for (int i = 0; i < 3; ++i) EXPECT_NEAR(gl_colors[3 * k + static_cast<std::size_t>(i)], linear(srgb[i]), 1e-6);
  }
  colors.pop_back();
  EXPECT_THROW(glb_bytes(cube, colors), InvalidInput);
  colors.push_back(Eigen::Vector3d(0, 1.5, 0));
  EXPECT_THROW(glb_bytes(cube, colors), InvalidInput);
}

}  // namespace
}  // namespace volspline
