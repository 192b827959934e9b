// The part table: numbers that mesh files have always carried stay, every part has its own name,
// parts drawn together can be told apart, and the blend's primitives are grey.
#include "volspline/mesh/parts.h"

#include <gtest/gtest.h>

#include <set>
#include <string>

namespace volspline {
namespace {

TEST(Parts, KeepTheNumbersOfEveryMeshFileWritten) {
  // Faces 0..5 in the order of core/conventions.h, J = 0 is 6, isoparametric 7..9, slices 10.
  for (int d = 0; d < 3; ++d) {
    EXPECT_EQ(part_number(face_part(d, false)), 2 * d);
    EXPECT_EQ(part_number(face_part(d, true)), 2 * d + 1);
    EXPECT_EQ(part_number(isoparametric_part(d)), 7 + d);
  }
  EXPECT_EQ(face_part(0, false), Part::UMin);
  EXPECT_EQ(face_part(2, true), Part::WMax);
  EXPECT_EQ(part_number(Part::JacobianZero), 6);
  EXPECT_EQ(part_number(Part::Slice), 10);
  EXPECT_EQ(part_number(Part::BlendSpline), 11);
  EXPECT_EQ(part_number(Part::BlendPrimitive), 12);
  EXPECT_EQ(part_number(Part::SweepCap), 13);
  EXPECT_EQ(part_number(Part::SweepFace), 14);
  EXPECT_EQ(part_number(Part::SweepRankDeficient), 15);
}

TEST(Parts, HaveOneRowEachWithItsOwnNameAndColour) {
  std::set<std::string> names;
  std::set<std::array<double, 3>> colours;
  for (std::size_t n = 0; n < kParts.size(); ++n) {
    const PartInfo* info = part_info(static_cast<int>(n));
    ASSERT_NE(info, nullptr);
    EXPECT_EQ(part_number(info->part), static_cast<int>(n));
    EXPECT_EQ(part_name(static_cast<int>(n)), std::string(info->name));
    names.insert(std::string(info->name));
    for (double c : info->srgb) {
      EXPECT_GE(c, 0.0);
      EXPECT_LE(c, 1.0);
    }
    const Eigen::Vector3d colour = part_color(info->part);
    EXPECT_EQ(colour, part_color(static_cast<int>(n)));
    // The blend's spline surface is the one part that shares a colour (with J = 0: the surface
    // one looks for, in meshes that never meet).
    if (info->part != Part::BlendSpline) colours.insert(info->srgb);
  }
  EXPECT_EQ(names.size(), kParts.size());
  EXPECT_EQ(colours.size(), kParts.size() - 1);
  EXPECT_EQ(part_info(-1), nullptr);
  EXPECT_EQ(part_info(static_cast<int>(kParts.size())), nullptr);
  EXPECT_EQ(part_name(42), "part_42");
}

TEST(Parts, DrawTheBlendPrimitivesGreyAndTheSplineOrange) {
  // README and `volspline blend --help`: spline part orange, primitives outside the box grey.
  const Eigen::Vector3d primitive = part_color(Part::BlendPrimitive), spline = part_color(Part::BlendSpline);
  EXPECT_EQ(primitive[0], primitive[1]);
  EXPECT_EQ(primitive[1], primitive[2]);
  EXPECT_GT(spline[0], spline[1] + 0.3);
  EXPECT_GT(spline[1], spline[2]);
  // A number no table row has (a mesh file may carry any) is grey too.
  EXPECT_EQ(part_color(99), Eigen::Vector3d(kUnknownPartSrgb[0], kUnknownPartSrgb[1], kUnknownPartSrgb[2]));
  EXPECT_EQ(part_color(-3), part_color(99));
}

}  // namespace
}  // namespace volspline
