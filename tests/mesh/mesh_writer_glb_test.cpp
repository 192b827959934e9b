// Binary glTF: read back with tinygltf's own loader, every triangle corner must have the
// position, the normal and the colour of its part that the mesh says.
#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <string>
#include <Eigen/Geometry>
#include <tiny_gltf.h>

#include "support/temporary_directory.h"
#include "support/test_meshes.h"
#include "volspline/core/error.h"
#include "volspline/mesh/mesh_writer.h"
#include "volspline/mesh/parts.h"

namespace volspline {
namespace {

struct LoadedGlb {
  tinygltf::Model model;
  std::vector<float> positions, normals, colors;
  std::vector<std::uint32_t> indices;
};

template <class T>
std::vector<T> accessor_values(const tinygltf::Model& model, int index, int components) {
  const tinygltf::Accessor& accessor = model.accessors.at(static_cast<std::size_t>(index));
  const tinygltf::BufferView& view = model.bufferViews.at(static_cast<std::size_t>(accessor.bufferView));
  const tinygltf::Buffer& buffer = model.buffers.at(static_cast<std::size_t>(view.buffer));
  std::vector<T> values(accessor.count * static_cast<std::size_t>(components));
  EXPECT_GE(view.byteLength, values.size() * sizeof(T));
  std::memcpy(values.data(), buffer.data.data() + view.byteOffset + accessor.byteOffset, values.size() * sizeof(T));
  return values;
}

LoadedGlb load(const std::string& bytes) {
  LoadedGlb out;
  tinygltf::TinyGLTF loader;
  std::string error, warning;
  const bool ok = loader.LoadBinaryFromMemory(&out.model, &error, &warning, reinterpret_cast<const unsigned char*>(bytes.data()),
                                              static_cast<unsigned>(bytes.size()));
  EXPECT_TRUE(ok) << error;
  EXPECT_TRUE(error.empty()) << error;
  EXPECT_TRUE(warning.empty()) << warning;
  if (!ok) return out;
  EXPECT_EQ(out.model.asset.version, "2.0");
  EXPECT_EQ(out.model.meshes.size(), 1u);
  const tinygltf::Primitive& primitive = out.model.meshes.at(0).primitives.at(0);
  EXPECT_EQ(primitive.mode, TINYGLTF_MODE_TRIANGLES);
  EXPECT_EQ(out.model.accessors.at(static_cast<std::size_t>(primitive.attributes.at("POSITION"))).componentType, TINYGLTF_COMPONENT_TYPE_FLOAT);
  EXPECT_EQ(out.model.accessors.at(static_cast<std::size_t>(primitive.indices)).componentType, TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT);
  out.positions = accessor_values<float>(out.model, primitive.attributes.at("POSITION"), 3);
  out.normals = accessor_values<float>(out.model, primitive.attributes.at("NORMAL"), 3);
  out.colors = accessor_values<float>(out.model, primitive.attributes.at("COLOR_0"), 3);
  out.indices = accessor_values<std::uint32_t>(out.model, primitive.indices, 1);
  return out;
}

double linear(double srgb) { return srgb <= 0.04045 ? srgb / 12.92 : std::pow((srgb + 0.055) / 1.055, 2.4); }

/// Every corner of every triangle: position as float, unit normal, part colour; and for a mesh
/// whose parts are planar, the normal of the plane.
void expect_round_trip(const TriangleMesh& mesh, bool planar_parts) {
  const LoadedGlb glb = load(glb_bytes(mesh));
  ASSERT_EQ(glb.indices.size(), 3 * mesh.num_triangles());
  const std::size_t n = glb.positions.size() / 3;
  ASSERT_EQ(glb.normals.size(), 3 * n);
  ASSERT_EQ(glb.colors.size(), 3 * n);
  for (std::size_t t = 0; t < mesh.num_triangles(); ++t) {
    const auto& tri = mesh.triangles[t];
    const Eigen::Vector3d face = (mesh.positions[tri[1]] - mesh.positions[tri[0]]).cross(mesh.positions[tri[2]] - mesh.positions[tri[0]]).normalized();
    const Eigen::Vector3d color = part_color(mesh.parts[t]);
    for (int c = 0; c < 3; ++c) {
      const std::uint32_t g = glb.indices[3 * t + static_cast<std::size_t>(c)];
      ASSERT_LT(g, n);
      const Eigen::Vector3d normal(glb.normals[3 * g], glb.normals[3 * g + 1], glb.normals[3 * g + 2]);
      for (int i = 0; i < 3; ++i) {
        EXPECT_EQ(glb.positions[3 * g + static_cast<std::size_t>(i)], static_cast<float>(mesh.positions[tri[c]][i]));
        EXPECT_NEAR(glb.colors[3 * g + static_cast<std::size_t>(i)], linear(color[i]), 1e-6);
      }
      EXPECT_NEAR(normal.norm(), 1.0, 1e-6);
      if (planar_parts) {
        EXPECT_NEAR((normal - face).norm(), 0.0, 1e-6) << "triangle " << t;
      }
    }
  }
}

TEST(Glb, CubeRoundTripsThroughTinygltfWithFaceNormalsAndPartColours) {
  // The cube shares its 8 vertices between parts: the writer must split them so that every
  // face keeps its own colour and flat normal.
  expect_round_trip(test_support::unit_cube(), true);
  expect_round_trip(test_support::unit_cube_as_separate_quads(), true);
}

TEST(Glb, CurvedMeshNormalsPointOutwardAndColoursFollowParts) {
  const TriangleMesh sphere = test_support::icosphere(2);
  expect_round_trip(sphere, false);
  const LoadedGlb glb = load(glb_bytes(sphere));
  // Smooth normals of a sphere centred at the origin point along the position vector.
  for (std::size_t g = 0; g < glb.positions.size() / 3; ++g) {
    const Eigen::Vector3d p(glb.positions[3 * g], glb.positions[3 * g + 1], glb.positions[3 * g + 2]);
    const Eigen::Vector3d normal(glb.normals[3 * g], glb.normals[3 * g + 1], glb.normals[3 * g + 2]);
    EXPECT_GT(normal.dot(p.normalized()), 0.95);
  }
}

TEST(Glb, IsChosenByExtensionAndWrittenAtomically) {
  EXPECT_EQ(mesh_format_from_path("solid.GLB"), MeshFormat::Glb);
  const test_support::TemporaryDirectory dir;
  write_mesh(test_support::unit_tetrahedron(), dir / "t.glb");
  EXPECT_EQ(dir.entries(), 1u);
  const LoadedGlb glb = load(glb_bytes(test_support::unit_tetrahedron()));
  EXPECT_EQ(glb.indices.size(), 12u);
}

TEST(Glb, MalformedMeshIsRejected) {
  TriangleMesh mesh = test_support::unit_tetrahedron();
  mesh.triangles[0][1] = 17;
  EXPECT_THROW(glb_bytes(mesh), InvalidInput);
}

}  // namespace
}  // namespace volspline
