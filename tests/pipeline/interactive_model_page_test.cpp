// The probes of a model's page (pipeline/interactive_model_page.h), checked against the spline:
// every vertex of the u-probe at position i has u = values[i] and lies at V of its parameters,
// the probe point is V(u_i, v_j, w_k), and every slice vertex lies in its plane.
#include "volspline/pipeline/interactive_model_page.h"

#include <gtest/gtest.h>

#include "volspline/construct/example_solids.h"
#include "volspline/core/error.h"

namespace volspline {
namespace {

TEST(ModelProbes, IsoparametricSurfacesAndThePointLieWhereTheSplineSays) {
  const BSplineVolume volume = bent_tricubic_volume();
  Model model;
  model.objects.push_back({"bent", false, volume, nullptr});
  InteractivePage page;
  ModelProbeOptions options;
  options.levels = 5;
  options.slice_normal = Eigen::Vector3d(1, 1, 0);
  add_model_probes(page, model, options, "bent.json");
  ASSERT_EQ(page.probes.size(), 4u);
  for (int d = 0; d < 3; ++d) {
    const PageProbe& probe = page.probes[static_cast<std::size_t>(d)];
    EXPECT_EQ(probe.name, std::string(1, "uvw"[d]));
    ASSERT_EQ(probe.values.size(), 5u);
    EXPECT_EQ(probe.initial, 2);
    EXPECT_EQ(probe.values.front(), volume.knot_vector(d).domain_min());
    EXPECT_EQ(probe.values.back(), volume.knot_vector(d).domain_max());
    for (std::size_t i = 0; i < 5; ++i) {
      const TriangleMesh& m = probe.meshes[i];
      ASSERT_GT(m.num_triangles(), 0u);
      for (const int part : m.parts) EXPECT_EQ(part, part_number(isoparametric_part(d)));
      for (std::size_t v = 0; v < m.num_vertices(); v += 7) {
        EXPECT_EQ(m.parameters[v][d], probe.values[i]);
        const Eigen::Vector3d p = volume.evaluate({m.parameters[v][0], m.parameters[v][1], m.parameters[v][2]});
        EXPECT_LT((p - m.positions[v]).norm(), 1e-12);
      }
    }
  }
  ASSERT_TRUE(page.probe_point.has_value());
  ASSERT_EQ(page.probe_point->points.size(), 125u);
  const std::size_t i = 1, j = 4, k = 2;
  const Eigen::Vector3d expected = volume.evaluate({page.probes[0].values[i], page.probes[1].values[j], page.probes[2].values[k]});
  EXPECT_LT((page.probe_point->points[i + 5 * (j + 5 * k)] - expected).norm(), 1e-12);
  const PageProbe& slice = page.probes[3];
  EXPECT_EQ(slice.name, "slice");
  EXPECT_FALSE(slice.shown);
  const Eigen::Vector3d n = Eigen::Vector3d(1, 1, 0).normalized();
  for (std::size_t s = 0; s < slice.meshes.size(); ++s) {
    EXPECT_GT(slice.meshes[s].num_triangles(), 0u) << s;  // the middles of the slabs cut the solid
    for (const Eigen::Vector3d& p : slice.meshes[s].positions) EXPECT_NEAR(n.dot(p), slice.values[s], 1e-9);
  }
  // The page accepts what the pipeline made.
  if (interactive_pages_available()) {
    EXPECT_NO_THROW(interactive_page_html(page));
  }
}

TEST(ModelProbes, SeveralVolumesMoveTogetherWithoutAPointAndBadOptionsAreRefused) {
  Model model;
  model.objects.push_back({"a", false, bent_tricubic_volume(), nullptr});
  model.objects.push_back({"b", false, twisted_volume(0.25), nullptr});
  InteractivePage page;
  ModelProbeOptions options;
  options.levels = 3;
  options.slices = false;
  add_model_probes(page, model, options);
  ASSERT_EQ(page.probes.size(), 3u);
  EXPECT_FALSE(page.probe_point.has_value());
  InteractivePage one;
  add_model_probes(one, Model{{model.objects[0]}, nullptr}, options);
  // Each position holds the surfaces of both volumes.
  EXPECT_GT(page.probes[0].meshes[1].num_triangles(), one.probes[0].meshes[1].num_triangles());
  options.levels = 1;
  EXPECT_THROW(add_model_probes(page, model, options), InvalidInput);
  options.levels = 3;
  options.slice_normal = Eigen::Vector3d::Zero();
  EXPECT_THROW(add_model_probes(page, model, options), InvalidInput);
  // A model without volumes gets no probes.
  InteractivePage none;
  add_model_probes(none, Model{}, {});
  EXPECT_TRUE(none.probes.empty());
}

}  // namespace
}  // namespace volspline
