// Nesting depth is bounded in every reader of nested input (issue 16: an IRIT file of 5,000
// nested [OBJECT blocks overflowed the stack). IRIT recurses into OBJECTs and stops at
// kMaxIritObjectDepth; JSON (models, scenes, skeletons) is parsed by nlohmann's iterative SAX
// parser into a DOM whose depth stops at kMaxJsonDepth; XML (G+Smo, VTU) is parsed by pugixml,
// iteratively, and refused beyond kMaxXmlDepth. Each reader gets files just inside its limit,
// just beyond it, 5,000 and 200,000 levels deep: none may crash, the deep ones are InvalidInput
// naming the file. Run in the ASan build too, whose frames are larger.
#include <gtest/gtest.h>

#include <string>

#include "io/xml_support.h"
#include "volspline/boxspline/scene_file.h"
#include "volspline/core/error.h"
#include "volspline/io/gismo_xml.h"
#include "volspline/io/irit_itd.h"
#include "volspline/io/model_file.h"
#include "volspline/io/skeleton_file.h"
#include "volspline/io/strict_json.h"
#include "volspline/io/vtk_xml.h"

#include <utility>

#include "support/invalid_input_message.h"

namespace volspline {
namespace {

template <class F>
std::string nesting_error_of(F&& f) {
  return test_support::invalid_input_message(std::forward<F>(f));
}

bool nesting_contains(const std::string& text, const std::string& part) { return text.find(part) != std::string::npos; }

std::string nesting_repeated(const std::string& s, std::size_t n) {
  std::string out;
  out.reserve(s.size() * n);
  for (std::size_t i = 0; i < n; ++i) out += s;
  return out;
}

const char* const nesting_kCurve = "[CURVE BSPLINE 2 2 E1 [KV 0 0 1 1] [0] [1]]\n";

std::string nesting_nested_objects(std::size_t depth) {
  return nesting_repeated("[OBJECT o\n", depth) + nesting_kCurve + nesting_repeated("]\n", depth);
}

TEST(NestingDepth, IritObjectsNestUpToTheLimitAndNoFurther) {
  const Model inside = parse_irit_itd(nesting_nested_objects(kMaxIritObjectDepth), "ok.itd");
  ASSERT_EQ(inside.objects.size(), 1u);
  EXPECT_EQ(inside.objects[0].name, "o");
  for (const std::size_t depth : {kMaxIritObjectDepth + 1, std::size_t{5000}, std::size_t{200000}}) {
    const std::string e = nesting_error_of([&] { parse_irit_itd(nesting_nested_objects(depth), "deep.itd"); });
    EXPECT_EQ(e.rfind("deep.itd: line " + std::to_string(kMaxIritObjectDepth + 1), 0), 0u) << depth << ": " << e;
    EXPECT_TRUE(nesting_contains(e, "nested at most 64 deep")) << e;
  }
  // Unclosed ones (a truncated file) and deep attribute groups, which are skipped iteratively.
  EXPECT_EQ(nesting_error_of([] { parse_irit_itd(nesting_repeated("[OBJECT o\n", 5000), "open.itd"); }).rfind("open.itd: line ", 0), 0u);
  const std::string attributes = "[OBJECT " + nesting_repeated("[", 200000) + nesting_repeated("]", 200000) + " o\n" + nesting_kCurve + "]\n";
  EXPECT_EQ(parse_irit_itd(attributes, "a.itd").objects.size(), 1u);
}

std::string nesting_nested_arrays(std::size_t depth) { return nesting_repeated("[", depth) + nesting_repeated("]", depth); }

TEST(NestingDepth, JsonDocumentsModelsScenesAndSkeletonsStopAtTheLimit) {
  EXPECT_NO_THROW(parse_json_document(nesting_nested_arrays(kMaxJsonDepth)));
  EXPECT_TRUE(nesting_contains(nesting_error_of([] { parse_json_document(nesting_nested_arrays(kMaxJsonDepth + 1)); }), "at most 64 levels"));
  for (const std::size_t depth : {std::size_t{5000}, std::size_t{200000}}) {
    const std::string deep = nesting_nested_arrays(depth);
    const std::string model = R"({"volspline":1,"metadata":)" + deep + R"(,"objects":[]})";
    const std::string e = nesting_error_of([&] { parse_model(model, "m.json"); });
    EXPECT_EQ(e.rfind("m.json: metadata", 0), 0u) << e;
    EXPECT_TRUE(nesting_contains(e, "at most 64 levels")) << e;
    // A scene's blend tree nests through JSON too.
    const std::string scene = R"({"volspline_scene":1,"spacing":0.1,"box":{"min":[0,0,0],"max":[1,1,1]},"root":)" +
                              nesting_repeated(R"({"union":[)", depth) + R"({"sphere":{"center":[0,0,0],"radius":1}})" +
                              nesting_repeated("]}", depth) + "}";
    const std::string s = nesting_error_of([&] { parse_scene(scene, "s.json"); });
    EXPECT_EQ(s.rfind("s.json: root", 0), 0u) << s;
    EXPECT_TRUE(nesting_contains(s, "at most 64 levels")) << s;
    EXPECT_EQ(nesting_error_of([&] { parse_skeleton(deep, "k.json"); }).rfind("k.json", 0), 0u);
  }
}

std::string nesting_gismo_with_nesting(std::size_t depth) {
  return "<?xml version=\"1.0\"?>\n<xml>\n" + nesting_repeated("<a>", depth) + nesting_repeated("</a>", depth) +
         "\n<Geometry type=\"BSpline\"><Basis type=\"BSplineBasis\"><KnotVector degree=\"1\">0 0 1 1</KnotVector></Basis>"
         "<coefs geoDim=\"1\">0 1</coefs></Geometry>\n</xml>\n";
}

std::string nesting_vtu_with_nesting(std::size_t depth) {
  return "<?xml version=\"1.0\"?>\n<VTKFile type=\"UnstructuredGrid\" version=\"2.2\">" + nesting_repeated("<a>", depth) + nesting_repeated("</a>", depth) +
         "\n<UnstructuredGrid></UnstructuredGrid></VTKFile>\n";
}

TEST(NestingDepth, XmlReadersStopAtTheLimitWithoutRecursing) {
  // <xml> is level 1, so kMaxXmlDepth - 1 elements fit inside it.
  const std::size_t inside = detail::kMaxXmlDepth - 1;
  EXPECT_EQ(parse_gismo_xml(nesting_gismo_with_nesting(inside), "ok.xml").objects.size(), 1u);
  const std::string ok = nesting_error_of([&] { parse_vtu(nesting_vtu_with_nesting(inside), "ok.vtu"); });
  EXPECT_TRUE(nesting_contains(ok, "at least one cell")) << ok;
  for (const std::size_t depth : {inside + 1, std::size_t{5000}, std::size_t{200000}}) {
    const std::string g = nesting_error_of([&] { parse_gismo_xml(nesting_gismo_with_nesting(depth), "deep.xml"); });
    EXPECT_EQ(g.rfind("deep.xml: line 3, column ", 0), 0u) << g;
    EXPECT_TRUE(nesting_contains(g, "at most 64 levels of nested elements")) << g;
    const std::string v = nesting_error_of([&] { parse_vtu(nesting_vtu_with_nesting(depth), "deep.vtu"); });
    EXPECT_EQ(v.rfind("deep.vtu: line 2, column ", 0), 0u) << v;
    EXPECT_TRUE(nesting_contains(v, "at most 64 levels of nested elements")) << v;
  }
}

}  // namespace
}  // namespace volspline
