// The volume loop: volumes only, in order, errors located at the object in the file.
#include <gtest/gtest.h>

#include <vector>

#include "volspline/construct/primitives.h"
#include "volspline/core/error.h"
#include "volspline/io/model_volumes.h"

namespace volspline {
namespace {

Model mixed_model() {
  Model model;
  const BSplineCurve curve(std::array<KnotVector, 1>{KnotVector::bezier(1)}, 3, {0, 0, 0, 1, 0, 0});
  model.objects.push_back({"curve", false, curve, nullptr});
  model.objects.push_back({"box", true, box(Eigen::Vector3d(1, 2, 3)), nullptr});
  model.objects.push_back({"ball", false, ball(1.0), nullptr});
  return model;
}

TEST(ModelVolumes, VisitsTheVolumesInOrder) {
  const Model model = mixed_model();
  EXPECT_EQ(count_volumes(model), 2u);
  std::vector<std::size_t> seen;
  const std::size_t visited = for_each_volume(model, "m.json", [&](std::size_t i, const ModelObject& object, const BSplineVolume& volume) {
    EXPECT_EQ(&std::get<BSplineVolume>(object.spline), &volume);
    EXPECT_EQ(&model.objects[i], &object);
    seen.push_back(i);
  });
  EXPECT_EQ(visited, 2u);
  EXPECT_EQ(seen, (std::vector<std::size_t>{1, 2}));
}

TEST(ModelVolumes, LocatesErrorsAtTheObject) {
  const Model model = mixed_model();
  try {
    for_each_volume(model, "m.json", [](std::size_t i, const ModelObject&, const BSplineVolume&) {
      if (i == 2) throw InvalidInput("too round", "control_points[3]");
    });
    FAIL() << "expected InvalidInput";
  } catch (const InvalidInput& e) {
    EXPECT_EQ(e.where(), "m.json: objects[2].control_points[3]");
    EXPECT_EQ(e.message(), "too round");
  }
  try {
    for_each_volume(model, "", [](std::size_t, const ModelObject&, const BSplineVolume&) { throw InvalidInput("no"); });
    FAIL() << "expected InvalidInput";
  } catch (const InvalidInput& e) {
    EXPECT_EQ(e.where(), "objects[1]");
  }
  EXPECT_THROW(for_each_volume(model, "m.json", [](std::size_t, const ModelObject&, const BSplineVolume&) { throw IoError("disk"); }),
               IoError);
}

TEST(ModelVolumes, AModelWithoutVolumesIsAnError) {
  Model model = mixed_model();
  model.objects.erase(model.objects.begin() + 1, model.objects.end());
  EXPECT_EQ(count_volumes(model), 0u);
  bool called = false;
  try {
    for_each_volume(model, "m.json", [&](std::size_t, const ModelObject&, const BSplineVolume&) { called = true; });
    FAIL() << "expected InvalidInput";
  } catch (const InvalidInput& e) {
    EXPECT_EQ(e.where(), "m.json");
    EXPECT_NE(e.message().find("no volume objects"), std::string::npos);
  }
  EXPECT_FALSE(called);
  EXPECT_EQ(object_location("a.xml", 7), "a.xml: objects[7]");
}

}  // namespace
}  // namespace volspline
