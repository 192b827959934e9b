// G+Smo XML: the data files of ../shared/data/gismo evaluate as G+Smo defines them (checked
// against formulas evaluated straight from the XML with pugixml), files written by volspline read
// back to the same geometry, and malformed files give errors that say where.
#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <random>
#include <set>
#include <sstream>
#include <string>
#include <pugixml.hpp>

#include "support/exchange_support.h"
#include "support/test_splines.h"
#include "volspline/construct/primitives.h"
#include "volspline/core/error.h"
#include "volspline/io/atomic_file.h"
#include "volspline/io/gismo_xml.h"

namespace volspline {
namespace {

/// ../shared/data/gismo next to the source tree, or $VOLSPLINE_GISMO_DATA.
std::filesystem::path gismo_data() {
  if (const char* env = std::getenv("VOLSPLINE_GISMO_DATA")) return env;
  return std::filesystem::path(VOLSPLINE_SOURCE_DIR) / ".." / "shared" / "data" / "gismo";
}

#define REQUIRE_GISMO_DATA(file)                                                                                    \
  if (!std::filesystem::exists(gismo_data() / (file))) {                                                            \
    GTEST_SKIP() << "G+Smo data file " << (gismo_data() / (file)) << " is absent (set VOLSPLINE_GISMO_DATA to its folder)"; \
  }

/// The coefficients of every <Geometry>, read with pugixml alone.
std::vector<std::vector<double>> raw_coefficients(const std::filesystem::path& file, const char* element = "coefs") {
  pugi::xml_document doc;
  EXPECT_TRUE(doc.load_file(file.c_str()));
  std::vector<std::vector<double>> out;
  for (pugi::xml_node g = doc.child("xml").child("Geometry"); g; g = g.next_sibling("Geometry")) {
    pugi::xml_node node = g.child(element);
    if (!node) node = g.child("Basis").child(element);
    std::istringstream in(node.child_value());
    std::vector<double> values;
    for (double x; in >> x;) values.push_back(x);
    out.push_back(values);
  }
  return out;
}

Eigen::Vector3d trilinear(const std::vector<double>& c, double u, double v, double w) {
  Eigen::Vector3d p = Eigen::Vector3d::Zero();
  for (int k = 0; k < 2; ++k)
    for (int j = 0; j < 2; ++j)
      for (int i = 0; i < 2; ++i) {
        const double b = (i ? u : 1 - u) * (j ? v : 1 - v) * (k ? w : 1 - w);
        const std::size_t at = 3 * static_cast<std::size_t>(i + 2 * j + 4 * k);  // first direction fastest
        p += b * Eigen::Vector3d(c[at], c[at + 1], c[at + 2]);
      }
  return p;
}

double jacobian(const BSplineVolume& s, const std::array<double, 3>& t) {
  const auto d = s.evaluate_derivatives(t, 1);
  const Eigen::Vector3d du(d[3], d[4], d[5]), dv(d[6], d[7], d[8]), dw(d[9], d[10], d[11]);
  return du.dot(dv.cross(dw));
}

void expect_trilinear_patches(const std::string& name, std::size_t count) {
  const Model model = read_gismo_xml(gismo_data() / name);
  const auto raw = raw_coefficients(gismo_data() / name);
  ASSERT_EQ(model.objects.size(), count);
  ASSERT_EQ(raw.size(), count);
  std::mt19937 rng(1);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  for (std::size_t i = 0; i < count; ++i) {
    const auto& s = std::get<BSplineVolume>(model.objects[i].spline);
    EXPECT_FALSE(s.is_rational());
    for (int n = 0; n < 50; ++n) {
      const double u = unit(rng), v = unit(rng), w = unit(rng);
      EXPECT_NEAR((s.evaluate({u, v, w}) - trilinear(raw[i], u, v, w)).norm(), 0.0, 1e-15) << name << " patch " << i;
    }
  }
}

TEST(GismoData, CubeFileIsSevenTrilinearHexahedraTheFirstRightHanded) {
  REQUIRE_GISMO_DATA("cube.xml");
  expect_trilinear_patches("cube.xml", 7);
  // README: the unit cube, then six left-handed frusta (Jacobian negative everywhere).
  const Model model = read_gismo_xml(gismo_data() / "cube.xml");
  std::mt19937 rng(2);
  for (std::size_t i = 0; i < model.objects.size(); ++i) {
    const auto& s = std::get<BSplineVolume>(model.objects[i].spline);
    for (int n = 0; n < 20; ++n) {
      const double j = jacobian(s, test_support::random_parameter(rng, s));
      if (i == 0) {
        EXPECT_NEAR(j, 1.0, 1e-15);
      } else {
        EXPECT_LT(j, 0.0) << "patch " << i;
      }
    }
    EXPECT_EQ(model.objects[i].metadata["gismo"]["id"], 1);
  }
}

TEST(GismoData, CylinderIsAThickWalledNurbsCylinderAsGismoEvaluatesIt) {
  REQUIRE_GISMO_DATA("cylinder.xml");
  const Model model = read_gismo_xml(gismo_data() / "cylinder.xml");
  ASSERT_EQ(model.objects.size(), 1u);
  const auto& s = std::get<BSplineVolume>(model.objects[0].spline);
  ASSERT_TRUE(s.is_rational());
  EXPECT_EQ(s.degrees(), (BSplineVolume::Index{2, 1, 1}));
  // G+Smo: Cartesian coefficients c_i and weights w_i, p = sum w_i N_i c_i / sum w_i N_i. In the
  // middle of a quadratic span with coefficients c0, c1, c2 that is (c0 + 2 w1 c1 + c2) / (2 + 2 w1).
  const auto c = raw_coefficients(gismo_data() / "cylinder.xml")[0];
  const auto w = raw_coefficients(gismo_data() / "cylinder.xml", "weights")[0];
  ASSERT_EQ(w.size(), 36u);
  for (int span = 0; span < 4; ++span) {
    for (int j = 0; j < 2; ++j) {
      for (int k = 0; k < 2; ++k) {
        const auto at = [&](int i) { return static_cast<std::size_t>(i + 9 * (j + 2 * k)); };
        const auto point = [&](int i) { return Eigen::Vector3d(c[3 * at(i)], c[3 * at(i) + 1], c[3 * at(i) + 2]); };
        const int i0 = 2 * span;
        const Eigen::Vector3d expected = (w[at(i0)] * point(i0) + 2 * w[at(i0 + 1)] * point(i0 + 1) + w[at(i0 + 2)] * point(i0 + 2)) /
                                         (w[at(i0)] + 2 * w[at(i0 + 1)] + w[at(i0 + 2)]);
        EXPECT_NEAR((s.evaluate({span + 0.5, double(j), double(k)}) - expected).norm(), 0.0, 1e-15);
      }
    }
  }
  // Radius 0.5 + 0.5 v, z = 4 w: the weights are 1/sqrt(2) to 12 digits, so circles to ~1e-12.
  std::mt19937 rng(3);
  for (int n = 0; n < 200; ++n) {
    const auto t = test_support::random_parameter(rng, s);
    const Eigen::Vector3d p = s.evaluate(t);
    EXPECT_NEAR(std::hypot(p.x(), p.y()), 0.5 + 0.5 * t[1], 1e-11);
    EXPECT_NEAR(p.z(), 4 * t[2], 1e-14);
    EXPECT_LT(jacobian(s, t), 0.0);  // left-handed, as the README says
  }
}

/// The four corners of side `side` (G+Smo: 1..6 = u min, u max, v min, v max, w min, w max).
std::set<std::array<double, 3>> side_corners(const BSplineVolume& s, int side) {
  std::set<std::array<double, 3>> corners;
  const int fixed = (side - 1) / 2;
  for (int a = 0; a < 2; ++a)
    for (int b = 0; b < 2; ++b) {
      std::array<double, 3> t{};
      t[static_cast<std::size_t>(fixed)] = (side - 1) % 2;
      t[static_cast<std::size_t>((fixed + 1) % 3)] = a;
      t[static_cast<std::size_t>((fixed + 2) % 3)] = b;
      const Eigen::Vector3d p = s.evaluate(t);
      corners.insert({p.x(), p.y(), p.z()});
    }
  return corners;
}

TEST(GismoData, FicheraMultipatchKeepsATopologyWhoseInterfacesMatchTheGeometry) {
  REQUIRE_GISMO_DATA("fichera.xml");
  expect_trilinear_patches("fichera.xml", 7);
  const Model model = read_gismo_xml(gismo_data() / "fichera.xml");
  const auto& mp = model.metadata["gismo"]["multipatch"];
  ASSERT_EQ(mp.size(), 1u);
  EXPECT_EQ(mp[0]["parDim"], 3);
  EXPECT_EQ(mp[0]["patches"], (nlohmann::json{0, 1, 2, 3, 4, 5, 6}));
  ASSERT_EQ(mp[0]["interfaces"].size(), 9u);
  ASSERT_EQ(mp[0]["boundary"].size(), 24u);
  std::map<long long, const BSplineVolume*> by_id;
  for (const auto& object : model.objects) by_id[object.metadata["gismo"]["id"]] = &std::get<BSplineVolume>(object.spline);
  // Every interface glues two sides with the same corners; every patch side is exactly once an
  // interface side or a boundary side.
  std::set<std::pair<long long, long long>> sides;
  for (const auto& row : mp[0]["interfaces"]) {
    EXPECT_EQ(side_corners(*by_id.at(row[0]), row[1].get<int>()), side_corners(*by_id.at(row[2]), row[3].get<int>())) << row.dump();
    EXPECT_TRUE(sides.insert({row[0].get<long long>(), row[1].get<long long>()}).second);
    EXPECT_TRUE(sides.insert({row[2].get<long long>(), row[3].get<long long>()}).second);
  }
  for (const auto& row : mp[0]["boundary"]) EXPECT_TRUE(sides.insert({row[0].get<long long>(), row[1].get<long long>()}).second) << row.dump();
  EXPECT_EQ(sides.size(), 42u);

  // Written and read again: the same geometry and topology.
  const Model back = parse_gismo_xml(gismo_xml_text(model), "back.xml");
  EXPECT_EQ(back.metadata, model.metadata);
  std::mt19937 rng(4);
  EXPECT_EQ(test_support::max_model_difference(model, back, rng, false), 0.0);
}

TEST(GismoXml, RoundTripOfCurvesSurfacesAndVolumesIsExact) {
  std::mt19937 rng(5);
  for (const int dimension : {1, 2, 3}) {
    const Model model = test_support::random_exchange_model(rng, dimension);
    const std::string text = gismo_xml_text(model);
    const Model back = parse_gismo_xml(text, "x.xml");
    EXPECT_LE(test_support::max_model_difference(model, back, rng, false), 1e-12);
    for (const char* type : {"\"BSpline\"", "\"Nurbs\"", "\"TensorBSpline2\"", "\"TensorNurbs2\"", "\"TensorBSpline3\"", "\"TensorNurbs3\""}) {
      EXPECT_NE(text.find(std::string("type=") + type), std::string::npos) << type;
    }
    // Ids are the object indices, written back as metadata.
    EXPECT_EQ(back.objects[5].metadata["gismo"]["id"], 5);
  }
}

TEST(GismoXml, AZeroWeightCoefficientHasNoInfluenceAsInGismo) {
  const std::string file = R"(<xml><Geometry type="Nurbs"><Basis type="NurbsBasis">
    <Basis type="BSplineBasis"><KnotVector degree="2">0 0 0 1 2 2 2</KnotVector></Basis>
    <weights>1 0 1 1</weights></Basis><coefs geoDim="2">0 0  X 7  2 0  3 1</coefs></Geometry></xml>)";
  const auto curve = [&](const std::string& x) {
    std::string text = file;
    text.replace(text.find('X'), 1, x);
    return std::get<BSplineCurve>(parse_gismo_xml(text, "z.xml").objects[0].spline);
  };
  const BSplineCurve a = curve("5"), b = curve("-100");
  for (double t = 0; t <= 2.0; t += 0.125) EXPECT_EQ(a.evaluate({t}), b.evaluate({t}));
  // Writing a volspline point at infinity (Lasser's half torus) is refused: G+Smo cannot hold it.
  Model torus{{ModelObject{"", false, half_torus(), nullptr}}, nullptr};
  try {
    gismo_xml_text(torus);
    ADD_FAILURE() << "no error";
  } catch (const InvalidInput& e) {
    EXPECT_NE(std::string(e.what()).find("point at infinity"), std::string::npos) << e.what();
  }
}

std::string gismo_error_of(const std::string& text) {
  try {
    parse_gismo_xml(text, "bad.xml");
  } catch (const InvalidInput& e) {
    return e.what();
  }
  return "no error";
}

const char* kGood = R"(<?xml version="1.0"?>
<xml>
 <Geometry type="TensorBSpline2" id="3">
  <Basis type="TensorBSplineBasis2">
   <Basis type="BSplineBasis" index="0"><KnotVector degree="1">0 0 1 1</KnotVector></Basis>
   <Basis type="BSplineBasis" index="1"><KnotVector degree="1">0 0 1 1</KnotVector></Basis>
  </Basis>
  <coefs geoDim="2">0 0 1 0 0 1 1 1</coefs>
 </Geometry>
</xml>
)";

std::string edited(const std::string& from, const std::string& to) {
  std::string text = kGood;
  text.replace(text.find(from), from.size(), to);
  return text;
}

TEST(GismoXml, BadFilesSayWhereAndWhat) {
  EXPECT_EQ(gismo_error_of(kGood), "no error");
  EXPECT_EQ(gismo_error_of(std::string(kGood).substr(0, 200)).rfind("bad.xml: line ", 0), 0u);
  EXPECT_NE(gismo_error_of(std::string(kGood).substr(0, 200)).find("invalid XML"), std::string::npos);
  EXPECT_EQ(gismo_error_of(edited(R"(<KnotVector degree="1">0 0 1 1</KnotVector></Basis>
  </Basis>)", "</Basis></Basis>")),
            "bad.xml: line 6, /xml/Geometry/Basis/Basis[2]: missing element <KnotVector> (the knot vector of this direction)");
  EXPECT_EQ(gismo_error_of(edited("0 0 1 0 0 1 1 1", "0 0 1 0 0 1 1")),
            "bad.xml: line 8, /xml/Geometry/coefs: expected 8 numbers (4 coefficients (2 x 2 from the knot vectors) with geoDim 2 "
            "each), got 7");
  EXPECT_EQ(gismo_error_of(edited("0 0 1 0 0 1 1 1", "0 0 1 0 0 1 1 x")),
            "bad.xml: line 8, /xml/Geometry/coefs: expected a finite number, got 'x'");
  EXPECT_EQ(gismo_error_of(edited(R"(degree="1">0 0 1 1</KnotVector></Basis>
  </Basis>)", R"(degree="1">0 1 0 1</KnotVector></Basis>
  </Basis>)")).rfind("bad.xml: line 6, /xml/Geometry/Basis/Basis[2]/KnotVector: knots must not decrease", 0), 0u);
  EXPECT_EQ(gismo_error_of(edited(R"(degree="1">0 0 1 1</KnotVector></Basis>
  </Basis>)", R"(degree="3">0 0 1 1</KnotVector></Basis>
  </Basis>)")),
            "bad.xml: line 6, /xml/Geometry/Basis/Basis[2]/KnotVector: a knot vector of degree 3 needs at least 8 knots, got 4");
  EXPECT_EQ(gismo_error_of(edited("TensorBSpline2\" id", "THBSpline2\" id")).rfind("bad.xml: line 3, /xml/Geometry: expected a geometry of type BSpline", 0), 0u);
  EXPECT_EQ(gismo_error_of(edited("geoDim=\"2\"", "")), "bad.xml: line 8, /xml/Geometry/coefs: missing attribute geoDim (an integer from 1)");
  EXPECT_EQ(gismo_error_of("<nope/>"), "bad.xml: line 1, /nope: expected the root element <xml> of a G+Smo file, got <nope>");
  EXPECT_EQ(gismo_error_of(edited("</xml>", R"(<MultiPatch parDim="2"><patches type="id_range">3 4</patches></MultiPatch></xml>)")),
            "bad.xml: line 10, /xml/MultiPatch/patches: the range 3..4 names more patches than the 1 geometries of the file");
  EXPECT_EQ(gismo_error_of(edited("</xml>", R"(<MultiPatch parDim="2"><patches type="id_index">4</patches></MultiPatch></xml>)")),
            "bad.xml: line 10, /xml/MultiPatch/patches: patch id 4 is not the id of any <Geometry>");
}

}  // namespace
}  // namespace volspline
