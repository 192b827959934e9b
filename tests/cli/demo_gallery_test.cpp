// The gallery page of `volspline demo` and the selection of examples by --only.
#include "volspline/demo_gallery.h"  // apps/volspline

#include <gtest/gtest.h>

#include <regex>

#include "support/temporary_directory.h"
#include "volspline/core/error.h"
#include "volspline/io/atomic_file.h"

namespace volspline::cli {
namespace {

TEST(Gallery, EscapesTextAndLinksPicturesRelatively) {
  EXPECT_EQ(html_escape(R"(a<b>&"c"'d')"), "a&lt;b&gt;&amp;&quot;c&quot;&#39;d&#39;");
  EXPECT_EQ(url_escape("fig 1&2.png"), "fig%201%262.png");
  EXPECT_EQ(url_escape("sub/ball-1_x~.png"), "sub/ball-1_x~.png");
  Gallery g("demo <1>");
  g.add({"ball", "radius < 2 & exact", {"ball.png", "ball top.png"}, "volspline make ball --radius 1 -o b.json && echo '<x>'"});
  g.add({"other", "", {"other.png"}, "volspline view other.json -o other.png", "other page.html"});
  const std::string html = g.html();
  EXPECT_NE(html.find("<title>demo &lt;1&gt;</title>"), std::string::npos);
  EXPECT_NE(html.find("<p>radius &lt; 2 &amp; exact</p>"), std::string::npos);
  EXPECT_NE(html.find("<img src=\"ball.png\""), std::string::npos);
  EXPECT_NE(html.find("<img src=\"ball%20top.png\""), std::string::npos);
  // A picture links itself where the entry has no page, else the page.
  EXPECT_NE(html.find("<a href=\"ball.png\"><img src=\"ball.png\""), std::string::npos);
  EXPECT_NE(html.find("<a href=\"other%20page.html\"><img src=\"other.png\""), std::string::npos);
  EXPECT_NE(html.find("<code>volspline make ball --radius 1 -o b.json &amp;&amp; echo &#39;&lt;x&gt;&#39;</code>"), std::string::npos);
  EXPECT_NE(html.find("<code>volspline view other.json -o other.png</code>"), std::string::npos);
  // Nothing unescaped slipped through: every '<' opens one of the page's own tags.
  const std::regex tag("<(/?)([a-zA-Z0-9!]+)");
  for (std::sregex_iterator it(html.begin(), html.end(), tag), end; it != end; ++it)
    EXPECT_TRUE(std::regex_match((*it)[2].str(), std::regex("!DOCTYPE|html|head|meta|title|style|body|h1|h2|p|main|section|div|a|img|pre|code")))
        << (*it)[0];
  EXPECT_EQ(g.entries().size(), 2u);
  test_support::TemporaryDirectory dir;
  g.write(dir.path());
  EXPECT_EQ(read_file(dir.path() / "index.html"), html);
  EXPECT_THROW(g.write(dir.path() / "missing"), IoError);
}

TEST(DemoRun, OnlySelectsAndUnknownNamesAreReported) {
  DemoRun all("d", {}, nullptr);
  EXPECT_TRUE(all.wants("ball"));
  EXPECT_TRUE(all.wants_group("blend-fig", "blend figures"));
  EXPECT_FALSE(all.selective());
  EXPECT_NO_THROW(all.check_selection());

  DemoRun some("d", {"ball", "blend-fig2c", "nonsense"}, nullptr);
  EXPECT_TRUE(some.selective());
  EXPECT_TRUE(some.wants("ball"));
  EXPECT_FALSE(some.wants("torus"));
  EXPECT_TRUE(some.wants_group("blend-fig", "blend-fig1a..blend-fig4c"));
  EXPECT_FALSE(some.wants_group("view-", "view examples"));
  EXPECT_TRUE(some.wants("blend-fig2c"));
  EXPECT_FALSE(some.wants("blend-fig2a"));
  try {
    some.check_selection();
    ADD_FAILURE() << "expected InvalidInput";
  } catch (const InvalidInput& e) {
    EXPECT_EQ(e.where(), "--only");
    EXPECT_NE(e.message().find("'nonsense'"), std::string::npos) << e.message();
    EXPECT_EQ(e.message().find("'ball'"), std::string::npos) << e.message();
    EXPECT_NE(e.message().find("torus"), std::string::npos) << e.message();  // the known names
  }
}

}  // namespace
}  // namespace volspline::cli
