#include "extract/triangle_buckets.h"

#include <gtest/gtest.h>

#include <random>
#include <set>

#include "volspline/core/error.h"

namespace volspline {
namespace {

using BucketPoint = CGAL::Exact_predicates_inexact_constructions_kernel::Point_3;

// Triangles of every size against the cubes (many inside one cube, some across dozens), and
// query boxes inside, across and outside the triangles' box: each query's answers are the brute
// force's over all triangles, each triangle once.
TEST(TriangleBuckets, QueriesGiveTheBruteForceAnswersEachTriangleOnce) {
  std::mt19937 rng(21);
  std::uniform_real_distribution<double> at(-1.0, 1.0), scale(0.0, 1.0);
  std::vector<BucketTriangle> triangles;
  for (int t = 0; t < 3000; ++t) {
    const double size = t % 100 == 0 ? 1.5 : 0.08 * scale(rng);
    const BucketPoint a(at(rng), at(rng), at(rng));
    auto near = [&] { return BucketPoint(a.x() + size * at(rng), a.y() + size * at(rng), a.z() + size * at(rng)); };
    triangles.emplace_back(a, near(), near());
  }
  triangles.emplace_back(BucketPoint(0.3, 0.3, 0.3), BucketPoint(0.3, 0.3, 0.3), BucketPoint(0.4, 0.3, 0.3));  // collapsed
  const TriangleBuckets buckets(triangles, 0.1);
  for (int q = 0; q < 400; ++q) {
    const double half = q % 10 == 0 ? 0.6 * scale(rng) : 0.05 * scale(rng);
    const double cx = 1.6 * at(rng), cy = 1.6 * at(rng), cz = 1.6 * at(rng);  // a third beyond the triangles' box
    const CGAL::Bbox_3 box(cx - half, cy - half, cz - half, cx + half, cy + half, cz + half);
    std::set<std::size_t> meeting, overlapping;
    for (std::size_t t = 0; t < triangles.size(); ++t) {
      if (CGAL::do_overlap(box, triangles[t].bbox())) overlapping.insert(t);
      if (!triangles[t].is_degenerate() && CGAL::do_intersect(triangles[t], box)) meeting.insert(t);
    }
    std::multiset<std::size_t> visited, candidates;
    buckets.visit_meeting(box, [&](std::size_t t) {
      if (!triangles[t].is_degenerate()) visited.insert(t);
      return true;
    });
    buckets.visit_candidates(box, [&](std::size_t t) {
      candidates.insert(t);
      return true;
    });
    EXPECT_EQ(std::set<std::size_t>(visited.begin(), visited.end()), meeting) << "query " << q;
    EXPECT_EQ(visited.size(), meeting.size()) << "a triangle visited twice, query " << q;
    const std::set<std::size_t> distinct(candidates.begin(), candidates.end());
    EXPECT_EQ(candidates.size(), distinct.size()) << "a candidate visited twice, query " << q;
    for (const std::size_t t : meeting) EXPECT_TRUE(distinct.count(t)) << "query " << q << " missed triangle " << t;
    for (const std::size_t t : distinct) EXPECT_TRUE(overlapping.count(t)) << "query " << q << ": triangle " << t << " is no candidate";
    int visits = 0;
    buckets.visit_candidates(box, [&](std::size_t) { return ++visits < 1; });
    EXPECT_EQ(visits, distinct.empty() ? 0 : 1) << "the visit goes on after its callback said stop";
  }
}

TEST(TriangleBuckets, AnyMeetsAndSegmentCandidatesAgreeWithTheBruteForce) {
  std::mt19937 rng(22);
  std::uniform_real_distribution<double> at(0.0, 10.0), step(-0.3, 0.3);
  std::vector<BucketTriangle> triangles;
  for (int t = 0; t < 2000; ++t) {
    const BucketPoint a(at(rng), at(rng), 0.1 * at(rng));
    triangles.emplace_back(a, BucketPoint(a.x() + step(rng), a.y() + step(rng), a.z()),
                           BucketPoint(a.x() + step(rng), a.y() + step(rng), a.z() + step(rng)));
  }
  const TriangleBuckets buckets(triangles, 0.4);
  for (int q = 0; q < 300; ++q) {
    const BucketPoint a(at(rng), at(rng), 0.1 * at(rng));
    const BucketPoint b(a.x() + step(rng), a.y() + step(rng), a.z() + step(rng));
    const CGAL::Epick::Segment_3 segment(a, b);
    std::set<std::size_t> crossed, found;
    bool any = false;
    for (std::size_t t = 0; t < triangles.size(); ++t) {
      if (CGAL::do_intersect(segment, triangles[t])) crossed.insert(t);
      any = any || CGAL::do_intersect(triangles[t], segment.bbox());
    }
    buckets.visit_candidates(segment.bbox(), [&](std::size_t t) {
      if (CGAL::do_intersect(segment, triangles[t])) found.insert(t);
      return true;
    });
    EXPECT_EQ(found, crossed) << "segment " << q;
    EXPECT_EQ(buckets.any_meets(segment.bbox()), any) << "segment " << q;
  }
}

// A large oblique triangle is entered into the cubes it meets, not every cube of its box: about
// its area in cubes (a 4 x 4 x 4 box of 40^3 cubes holds a triangle of area about 14, some 1,400
// cube faces' worth), and its queries still find it wherever it is.
TEST(TriangleBuckets, ALargeObliqueTriangleTakesTheCubesItMeetsNotItsBox) {
  const std::vector<BucketTriangle> triangles{BucketTriangle(BucketPoint(0, 0, 0), BucketPoint(4, 0, 4), BucketPoint(0, 4, 4))};
  const TriangleBuckets buckets(triangles, 0.1);
  EXPECT_LT(buckets.entries(), std::size_t{10000});
  EXPECT_GT(buckets.entries(), std::size_t{1000});
  std::mt19937 rng(23);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  for (int q = 0; q < 500; ++q) {
    double a = unit(rng), b = unit(rng);
    if (a + b > 1) {
      a = 1 - a;
      b = 1 - b;
    }
    // A point of the triangle, and a tiny box around it.
    const double x = 4 * a, y = 4 * b, z = 4 * (a + b), r = 1e-7;
    EXPECT_TRUE(buckets.any_meets(CGAL::Bbox_3(x - r, y - r, z - r, x + r, y + r, z + r))) << x << " " << y << " " << z;
  }
  EXPECT_FALSE(buckets.any_meets(CGAL::Bbox_3(3.5, 3.5, 0.0, 3.9, 3.9, 0.5)));  // inside the box, far from the triangle
}

TEST(TriangleBuckets, RefusesACubeSizeThatIsNotPositiveAndFinite) {
  const std::vector<BucketTriangle> none;
  EXPECT_THROW(TriangleBuckets(none, 0.0), InvalidInput);
  EXPECT_THROW(TriangleBuckets(none, std::numeric_limits<double>::quiet_NaN()), InvalidInput);
  const TriangleBuckets empty(none, 1.0);
  EXPECT_FALSE(empty.any_meets(CGAL::Bbox_3(0, 0, 0, 1, 1, 1)));
}

}  // namespace
}  // namespace volspline
