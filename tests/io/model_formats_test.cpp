// The table of model formats: extensions and names find the same row, in any letter case, and
// unknown ones are rejected with the list of known ones.
#include <gtest/gtest.h>

#include <set>
#include <string>

#include "volspline/core/error.h"
#include "volspline/io/model_formats.h"

namespace volspline {
namespace {

TEST(ModelFormats, ExtensionsAndNamesFindTheSameRow) {
  std::set<std::string> names, extensions;
  for (const ModelFormat& f : model_formats()) {
    EXPECT_TRUE(names.insert(f.name).second);
    EXPECT_TRUE(extensions.insert(f.extension).second);
    EXPECT_EQ(&model_format_from_path(std::string("dir.x/model") + f.extension), &f);
    std::string upper = std::string("MODEL") + f.extension;
    for (char& c : upper) c = static_cast<char>(std::toupper(static_cast<unsigned char>(c)));
    EXPECT_EQ(&model_format_from_path(upper), &f);
    EXPECT_EQ(&model_format_named(f.name), &f);
    EXPECT_EQ(&model_format_named(f.extension), &f);
    EXPECT_EQ(&model_format_named(f.extension + 1), &f);
    EXPECT_NE(f.parse, nullptr);
    EXPECT_NE(f.text, nullptr);
  }
  EXPECT_EQ(names, (std::set<std::string>{"json", "gismo", "irit", "vtu"}));
}

TEST(ModelFormats, UnknownOnesListTheKnownOnes) {
  try {
    model_format_from_path("model.step");
    ADD_FAILURE();
  } catch (const InvalidInput& e) {
    EXPECT_EQ(std::string(e.what()),
              "cannot tell the model format of 'model.step': expected the extension .json, .xml, .itd, .vtu (or name the "
              "format with --format json, gismo, irit, vtu)");
  }
  EXPECT_THROW(model_format_named("step"), InvalidInput);
  EXPECT_THROW(model_format_from_path("json"), InvalidInput);
}

}  // namespace
}  // namespace volspline
