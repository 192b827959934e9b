// `volspline make` end to end: every kind writes a model that evaluates on its analytic surface;
// bad input exits with 2, names the option and leaves no output behind.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <sys/wait.h>

#include "support/cli_runner.h"
#include "support/temporary_directory.h"
#include "volspline/io/model_file.h"

namespace volspline {
namespace {

using Result = test_support::CliResult;

class MakeCli : public ::testing::Test {
 protected:
  test_support::TemporaryDirectory tmp;
  std::string path(const std::string& name) const { return (tmp.path() / name).string(); }

  Result run(const std::string& args) const {
    return test_support::run_cli(args, tmp.path());
  }

  template <int D>
  std::string write_object(const std::string& name, const TensorSpline<D>& s) const {
    Model m;
    m.objects.push_back({name, false, s, nullptr});
    write_model(m, path(name));
    return path(name);
  }

  // Runs `make ARGS -o OUT.json`, expects success and returns the volume written.
  BSplineVolume make(const std::string& args) const {
    const auto out = path("out.json");
    std::filesystem::remove(out);
    const auto r = run("make " + args + " -o " + out);
    EXPECT_EQ(r.code, 0) << args << "\n" << r.err;
    EXPECT_NE(r.out.find("wrote"), std::string::npos);
    const Model m = read_model(out);
    EXPECT_EQ(m.objects.size(), 1u);
    return std::get<BSplineVolume>(m.objects.at(0).spline);
  }

  // Expects exit code 2, a message naming `option`, and no output file.
  void expect_bad(const std::string& args, const std::string& option) const {
    const auto out = path("bad.json");
    const auto r = run("make " + args + " -o " + out);
    EXPECT_EQ(r.code, 2) << args;
    EXPECT_NE(r.err.find(option), std::string::npos) << args << "\n" << r.err;
    EXPECT_FALSE(std::filesystem::exists(out)) << args;
  }
};

// Largest |f(p)| over a grid on the face `face` (u=min, u=max, v=min, ...).
template <class F>
double on_face(const BSplineVolume& v, int face, F f, int n = 24) {
  const int d = face / 2, d1 = (d + 1) % 3, d2 = (d + 2) % 3;
  double worst = 0;
  for (int a = 0; a <= n; ++a)
    for (int b = 0; b <= n; ++b) {
      std::array<double, 3> t{};
      t[static_cast<std::size_t>(d)] = face % 2 ? v.domain_max(d) : v.domain_min(d);
      t[static_cast<std::size_t>(d1)] = v.domain_min(d1) + (v.domain_max(d1) - v.domain_min(d1)) * a / n;
      t[static_cast<std::size_t>(d2)] = v.domain_min(d2) + (v.domain_max(d2) - v.domain_min(d2)) * b / n;
      worst = std::max(worst, std::abs(f(v.evaluate(t))));
    }
  return worst;
}

// A rectangle in the x-z half plane: x in [1, 2], z in [0, 1].
BSplineSurface rectangle(double z0 = 0.0) {
  const KnotVector k = KnotVector::bezier(1);
  return BSplineSurface({k, k}, 3, {1, 0, z0, 2, 0, z0, 1, 0, z0 + 1, 2, 0, z0 + 1});
}

TEST_F(MakeCli, HelpOnMakeAndEveryKind) {
  for (const char* kind : {"", "box", "ball", "cylinder", "cone", "torus", "half-torus", "hyperboloid", "half-cylinder-sweep", "revolve",
                           "extrude", "ruled", "loft", "sweep", "swept-patch", "twisted-loft", "curved-loft"}) {
    const auto r = run(std::string("make ") + kind + " --help");
    EXPECT_EQ(r.code, 0) << kind;
    EXPECT_NE(r.out.find("Usage"), std::string::npos) << kind;
  }
  EXPECT_EQ(run("make").code, 2);  // a kind is required
  EXPECT_EQ(run("make sphere -o x.json").code, 2);
}

TEST_F(MakeCli, PrimitivesLieOnTheirSurfaces) {
  const Eigen::Vector3d c(1, 2, 3);
  auto rho = [&](const Eigen::Vector3d& p) { return std::hypot(p.x() - c.x(), p.y() - c.y()); };
  {
    const auto v = make("ball --radius 2 --center 1,2,3");
    EXPECT_LE(on_face(v, 1, [&](const Eigen::Vector3d& p) { return (p - c).norm() - 2; }), 1e-12 * 2);
  }
  {
    const auto v = make("cylinder --radius 2 --height 4 --inner 0.5 --center 1,2,3");
    EXPECT_LE(on_face(v, 0, [&](const Eigen::Vector3d& p) { return rho(p) - 0.5; }), 1e-12 * 2);
    EXPECT_LE(on_face(v, 1, [&](const Eigen::Vector3d& p) { return rho(p) - 2; }), 1e-12 * 2);
    EXPECT_LE(on_face(v, 3, [&](const Eigen::Vector3d& p) { return p.z() - 5; }), 1e-12 * 5);
  }
  {
    const auto v = make("cone --radius1 2 --radius2 0 --height 4 --center 1,2,3");
    EXPECT_LE(on_face(v, 1, [&](const Eigen::Vector3d& p) { return rho(p) - 2 * (5 - p.z()) / 4; }), 1e-12 * 5);
  }
  {
    const auto v = make("torus --major 3 --minor 1 --angle 270 --center 1,2,3");
    EXPECT_LE(on_face(v, 1, [&](const Eigen::Vector3d& p) { return std::hypot(rho(p) - 3, p.z() - 3) - 1; }), 1e-12 * 4);
    EXPECT_LE(on_face(v, 5, [&](const Eigen::Vector3d& p) { return p.x() - c.x(); }), 1e-12 * 4);  // the end face at 270 degrees
  }
  {
    const auto v = make("box --size 1,2,3 --center 1,2,3");
    EXPECT_LE(on_face(v, 5, [&](const Eigen::Vector3d& p) { return p.z() - 4.5; }), 1e-15);
  }
  {
    const auto v = make("half-torus");
    int zero = 0;
    for (double w : v.weights()) zero += w == 0.0;
    EXPECT_GT(zero, 0);
    EXPECT_LE(on_face(v, 0, [&](const Eigen::Vector3d& p) { return std::hypot(std::hypot(p.x(), p.y()) - 2, p.z()) - 1; }), 1e-12 * 3);
  }
  {
    const auto v = make("hyperboloid --throat-radius 0.5 --half-height 2");
    EXPECT_LE(on_face(v, 1, [&](const Eigen::Vector3d& p) { return std::hypot(p.x(), p.y()) - std::hypot(0.5, p.z()); }), 1e-12 * 3);
  }
  {
    const auto v = make("half-cylinder-sweep");
    EXPECT_LE(on_face(v, 5, [&](const Eigen::Vector3d& p) { return std::hypot(p.x() - 3, p.y()) - 1; }), 1e-12 * 4);
  }
}

TEST_F(MakeCli, RevolveExtrudeRuledLoft) {
  const auto profile = write_object("profile.json", rectangle());
  {
    const auto v = make("revolve --profile " + profile + " --axis-point 0,0,0 --axis-direction 0,0,1 --angle 360");
    EXPECT_LE(on_face(v, 1, [](const Eigen::Vector3d& p) { return std::hypot(p.x(), p.y()) - 2; }), 1e-12 * 2);
    EXPECT_LT((v.evaluate({0.3, 0.6, 0.0}) - v.evaluate({0.3, 0.6, 1.0})).norm(), 1e-13);
  }
  {
    const auto v = make("revolve --profile " + profile + " --axis-point 0,0,0 --axis-direction 0,0,1 --angle 180 --single-segment");
    EXPECT_TRUE(v.knot_vector(2).is_bezier());
    EXPECT_EQ(v.weights()[4], 0.0);
  }
  {
    const auto v = make("extrude --profile " + profile + " --vector 0,3,0");
    EXPECT_LT((v.evaluate({0.5, 0.5, 1.0}) - Eigen::Vector3d(1.5, 3, 0.5)).norm(), 1e-14);
  }
  {
    const BSplineCurve line({KnotVector::bezier(2)}, 3, {5, 5, 5, 5, 6, 5, 5, 7, 7});
    const auto curve = write_object("curve.json", line);
    const auto v = make("extrude --profile " + profile + " --along " + curve);
    // moved along the translate of the curve that starts at F(0, 0) = (1, 0, 0)
    EXPECT_LT((v.evaluate({0.0, 0.0, 1.0}) - Eigen::Vector3d(1, 2, 2)).norm(), 1e-14);
  }
  const auto top = write_object("top.json", rectangle(3.0));
  const auto middle = write_object("middle.json", rectangle(1.0));
  {
    const auto v = make("ruled --from " + profile + " --to " + top);
    EXPECT_LT((v.evaluate({0.0, 0.0, 0.5}) - Eigen::Vector3d(1, 0, 1.5)).norm(), 1e-14);
  }
  {
    const auto v = make("loft --through " + profile + " " + middle + " " + top + " --degree 2");
    EXPECT_EQ(v.degrees()[2], 2);
    EXPECT_LT((v.evaluate({1.0, 1.0, 1.0}) - Eigen::Vector3d(2, 0, 4)).norm(), 1e-13);
  }
}

TEST_F(MakeCli, SweepsAndPaperExamples) {
  const auto profile = write_object("profile.json", rectangle());
  const BSplineCurve straight({KnotVector::bezier(1)}, 3, {0, 0, 0, 0, 0, 5});
  const auto curve = write_object("path.json", straight);
  {
    const auto v = make("sweep --profile " + profile + " --path " + curve + " --frame fixed");
    EXPECT_LT((v.evaluate({0.0, 0.0, v.domain_min(2)}) - Eigen::Vector3d(1, 0, 0)).norm(), 1e-12);
    EXPECT_LT((v.evaluate({0.0, 0.0, v.domain_max(2)}) - Eigen::Vector3d(1, 0, 5)).norm(), 1e-12);
  }
  {
    // the identity frame as three constant curves
    Model frame;
    for (int c = 0; c < 3; ++c) {
      std::vector<double> p(6, 0.0);
      p[static_cast<std::size_t>(c)] = p[static_cast<std::size_t>(3 + c)] = 1.0;
      frame.objects.push_back({"", false, BSplineCurve({KnotVector::bezier(1)}, 3, p), nullptr});
    }
    write_model(frame, path("frame.json"));
    const auto v = make("sweep --profile " + profile + " --path " + curve + " --frame " + path("frame.json"));
    EXPECT_LT((v.evaluate({1.0, 1.0, v.domain_max(2)}) - Eigen::Vector3d(2, 0, 6)).norm(), 1e-12);
    frame.objects.pop_back();
    write_model(frame, path("frame2.json"));
    expect_bad("sweep --profile " + profile + " --path " + curve + " --frame " + path("frame2.json"), "--frame");
  }
  for (const char* kind : {"swept-patch", "twisted-loft", "curved-loft"}) {
    const auto v = make(kind);
    EXPECT_EQ(v.dimension(), 3) << kind;
  }
}

TEST_F(MakeCli, BadInputNamesTheOption) {
  const auto profile = write_object("profile.json", rectangle());
  const BSplineCurve curve({KnotVector::bezier(1)}, 3, {0, 0, 0, 1, 1, 1});
  const auto curve_file = write_object("curve.json", curve);
  expect_bad("ball --radius -1", "--radius");
  expect_bad("ball --radius 0", "--radius");
  expect_bad("ball --radius x", "--radius");
  expect_bad("ball --radius 1 --center 1,2", "--center");
  expect_bad("box --size 1,0,1", "--size");
  expect_bad("cylinder --radius 2 --height 1 --inner 2", "--inner");
  expect_bad("cylinder --radius 2 --height -1", "--height");
  expect_bad("cone --radius1 -1 --radius2 1 --height 1", "--radius1");
  expect_bad("torus --major 1 --minor 2", "--major");
  expect_bad("torus --major 3 --minor 1 --angle 400", "--angle");
  expect_bad("torus --major 3 --minor 1 --angle 0", "--angle");
  expect_bad("revolve --profile " + profile + " --axis-point 0,0,0 --axis-direction 0,0,0 --angle 90", "--axis-direction");
  expect_bad("revolve --profile " + profile + " --axis-point 0,0,0 --axis-direction 0,0,1 --angle 361", "--angle");
  expect_bad("revolve --profile " + profile + " --axis-point 0,0,0 --axis-direction 0,0,1 --angle 270 --single-segment", "--angle");
  expect_bad("revolve --profile " + curve_file + " --axis-point 0,0,0 --axis-direction 0,0,1 --angle 90", "--profile");
  expect_bad("revolve --profile " + path("missing.json") + " --axis-point 0,0,0 --axis-direction 0,0,1 --angle 90", "missing.json");
  expect_bad("extrude --profile " + profile, "--vector");
  expect_bad("extrude --profile " + profile + " --vector 0,0,0", "--vector");
  expect_bad("extrude --profile " + profile + " --along " + profile, "--along");
  expect_bad("loft --through " + profile, "--through");
  expect_bad("loft --through " + profile + " " + profile, "--through");
  expect_bad("loft --through " + profile + " " + curve_file, "--through[1]");
  expect_bad("ruled --from " + profile + " --to " + curve_file, "--to");
  const auto r = run("make revolve --profile " + curve_file + " --axis-point 0,0,0 --axis-direction 0,0,1 --angle 90 -o " + path("x.json"));
  EXPECT_NE(r.err.find("no surface"), std::string::npos) << r.err;
}

}  // namespace
}  // namespace volspline
