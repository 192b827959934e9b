// Progress and verbosity of the command line: a bar on stderr only for terminals (or
// VOLSPLINE_PROGRESS=always), phase timings with -v, silence with -q.
#include <gtest/gtest.h>

#include <cstdlib>
#include <fstream>
#include <filesystem>
#include <regex>
#include <sstream>
#include <string>
#include <thread>

#include "support/cli_runner.h"
#include "support/temporary_directory.h"
#include "volspline/construct/paper_examples.h"
#include "volspline/io/model_file.h"
#include "volspline/progress_bar.h"  // apps/volspline

namespace volspline {
namespace {

using cli::ProgressReporter;
using cli::report_settings;
using cli::ReportSettings;

// Sets an environment variable for the CLI runs of one test (ctest runs each test in its own
// process).
class ScopedEnv {
 public:
  ScopedEnv(const char* name, const char* value) : name_(name) { setenv(name, value, 1); }
  ~ScopedEnv() { unsetenv(name_); }

 private:
  const char* name_;
};

class ProgressCli : public ::testing::Test {
 protected:
  test_support::TemporaryDirectory tmp;
  std::string model() {
    Model m;
    m.objects.push_back({"twisted-loft", false, twisted_loft(), nullptr});
    write_model(m, tmp.path() / "loft.json");
    return (tmp.path() / "loft.json").string();
  }
  std::string out(const std::string& name) const { return (tmp.path() / name).string(); }
};

TEST(ReportSettings, BarOnlyForTerminalsOrWhenForced) {
  EXPECT_TRUE(report_settings(false, false, true, nullptr, nullptr).bar);
  EXPECT_FALSE(report_settings(false, false, false, nullptr, nullptr).bar);
  EXPECT_TRUE(report_settings(false, false, false, "always", nullptr).bar);
  EXPECT_FALSE(report_settings(false, false, true, "never", nullptr).bar);
  EXPECT_TRUE(report_settings(false, false, true, "nonsense", nullptr).bar);  // unknown: auto
  const ReportSettings quiet = report_settings(true, false, true, "always", "0");
  EXPECT_TRUE(quiet.quiet);
  EXPECT_FALSE(quiet.bar);
  EXPECT_DOUBLE_EQ(report_settings(false, false, true, nullptr, nullptr).delay, 1.0);
  EXPECT_DOUBLE_EQ(report_settings(false, false, true, nullptr, "0.25").delay, 0.25);
  EXPECT_DOUBLE_EQ(report_settings(false, false, true, nullptr, "-3").delay, 1.0);
  EXPECT_DOUBLE_EQ(report_settings(false, false, true, nullptr, "2x").delay, 1.0);
}

TEST(ProgressReporter, NothingBeforeTheDelayAndNoProgressObjectWhenSilent) {
  std::ostringstream err;
  {
    ProgressReporter r(err, ReportSettings{.bar = true, .delay = 60});
    const ProgressPhase phase(r.progress(), "work", 100);
    for (int i = 0; i < 100; ++i) phase.advance();
    r.finish();
    EXPECT_EQ(r.drawings(), 0);
  }
  EXPECT_EQ(err.str(), "");
  ProgressReporter quiet(err, ReportSettings{.quiet = true, .bar = true, .delay = 0});
  EXPECT_EQ(quiet.progress(), nullptr);
  quiet.warn("not shown");
  ProgressReporter plain(err, ReportSettings{});
  EXPECT_EQ(plain.progress(), nullptr);  // neither bar nor timings: operations skip reporting
  EXPECT_EQ(err.str(), "");
}

TEST(ProgressReporter, BarIsRateLimitedAndErased) {
  std::ostringstream err;
  ProgressReporter r(err, ReportSettings{.bar = true, .delay = 0, .interval = 0.1});
  const auto start = std::chrono::steady_clock::now();
  {
    const ProgressPhase phase(r.progress(), "work", 1000);
    for (int i = 0; i < 1000; ++i) {
      phase.advance();
      if (i % 100 == 0) std::this_thread::sleep_for(std::chrono::milliseconds(20));
    }
  }
  const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  r.finish();
  const std::string text = err.str();
  // At most one drawing per interval (plus the first), and at least the first.
  EXPECT_GE(r.drawings(), 1);
  EXPECT_LE(r.drawings(), 1 + static_cast<int>(seconds / 0.1) + 1) << seconds;
  EXPECT_EQ(text.find('\n'), std::string::npos);
  EXPECT_NE(text.find("\rvolspline: work"), std::string::npos);
  EXPECT_NE(text.find("%"), std::string::npos);
  // The last thing on the line is blanks, and the cursor is back at its start.
  const auto last = text.rfind('\r', text.size() - 2);
  ASSERT_NE(last, std::string::npos);
  EXPECT_EQ(text.back(), '\r');
  EXPECT_EQ(text.substr(last + 1, text.size() - last - 2).find_first_not_of(' '), std::string::npos);
}

TEST(ProgressReporter, VerboseTimingsAndLabels) {
  std::ostringstream err;
  ProgressReporter r(err, ReportSettings{.verbose = true});
  r.set_label("object 1");
  { const ProgressPhase phase(r.progress(), "first"); }
  r.set_label("");
  { const ProgressPhase phase(r.progress(), "second"); }
  r.warn("careful");
  r.finish();
  r.finish();  // idempotent
  EXPECT_TRUE(std::regex_match(err.str(), std::regex("volspline: object 1 first [0-9]+\\.[0-9]{3} s\n"
                                                     "volspline: second [0-9]+\\.[0-9]{3} s\n"
                                                     "volspline: warning: careful\n"
                                                     "volspline: total [0-9]+\\.[0-9]{3} s\n")))
      << err.str();
}

TEST_F(ProgressCli, NoBarWhenStderrIsNotATerminal) {
  const auto r = test_support::run_cli("boundary " + model() + " -o " + out("b.ply"), tmp.path());
  ASSERT_EQ(r.code, 0) << r.err;
  EXPECT_EQ(r.err, "");
}

TEST_F(ProgressCli, VerbosePrintsPhaseTimingsBeforeOrAfterTheSubcommand) {
  const std::string in = model();
  for (const std::string& args : {"-v boundary " + in + " -o " + out("b.ply"), "boundary " + in + " -o " + out("b.ply") + " --verbose"}) {
    const auto r = test_support::run_cli(args, tmp.path());
    ASSERT_EQ(r.code, 0) << r.err;
    for (const char* phase : {"reading", "subdivision", "tetrahedra", "marching", "mapping", "faces", "writing", "total"})
      EXPECT_TRUE(std::regex_search(r.err, std::regex(std::string("(^|\n)volspline: ") + phase + " [0-9]+\\.[0-9]{3} s\n")))
          << phase << "\n" << r.err;
    EXPECT_EQ(r.err.find('\r'), std::string::npos);
  }
  const auto j = test_support::run_cli("-v jacobian " + in, tmp.path());
  EXPECT_EQ(j.code, 0) << j.err;
  EXPECT_NE(j.err.find("volspline: certification "), std::string::npos) << j.err;
  const auto c = test_support::run_cli("-v convert " + in + " -o " + out("c.xml"), tmp.path());
  EXPECT_EQ(c.code, 0) << c.err;
  for (const char* phase : {"reading", "converting", "writing"}) EXPECT_NE(c.err.find(std::string("volspline: ") + phase), std::string::npos) << c.err;
}

TEST_F(ProgressCli, QuietSaysNothingOnStderrEvenWhenTheBarIsForced) {
  const ScopedEnv always("VOLSPLINE_PROGRESS", "always");
  const ScopedEnv delay("VOLSPLINE_PROGRESS_DELAY", "0");
  const auto r = test_support::run_cli("-q boundary " + model() + " -o " + out("b.ply"), tmp.path());
  ASSERT_EQ(r.code, 0) << r.err;
  EXPECT_EQ(r.err, "");
  EXPECT_NE(r.out.find("wrote"), std::string::npos);  // stdout is unchanged
  // A warning is silenced too: a sphere that does not reach the box.
  std::ofstream(tmp.path() / "far.json") << R"({"volspline_scene": 1, "spacing": 0.25, "box": {"min": [-1, -1, -1], "max": [1, 1, 1]},
      "root": {"sphere": {"center": [0, 0, 0], "radius": 5}}})";
  const std::string blend = "blend " + (tmp.path() / "far.json").string() + " -o " + out("far.ply");
  const auto loud = test_support::run_cli("--verbose " + blend, tmp.path());
  EXPECT_EQ(loud.code, 0);
  EXPECT_NE(loud.err.find("volspline: warning: the zero set does not cross"), std::string::npos) << loud.err;
  const auto quiet = test_support::run_cli(blend + " --quiet", tmp.path());
  EXPECT_EQ(quiet.code, 0);
  EXPECT_EQ(quiet.err, "");
  EXPECT_EQ(test_support::run_cli("-q -v " + blend, tmp.path()).code, 2);  // they exclude each other
}

// sweep-envelope reports its phases too (the translated box: the superset's faces, the
// arrangement's cut and classification, the checks), and -q silences them.
TEST_F(ProgressCli, SweepEnvelopeReportsItsPhases) {
  const std::string box = (std::filesystem::path(VOLSPLINE_SOURCE_DIR) / "examples" / "swept-translated-box.json").string();
  const auto r = test_support::run_cli("-v sweep-envelope " + box + " -o " + out("e.ply"), tmp.path());
  ASSERT_EQ(r.code, 0) << r.err;
  for (const char* phase : {"reading", "refinement", "classification", "checks", "writing", "total"})
    EXPECT_TRUE(std::regex_search(r.err, std::regex(std::string("(^|\n)volspline: ") + phase + " [0-9]+\\.[0-9]{3} s\n")))
        << phase << "\n" << r.err;
  const ScopedEnv always("VOLSPLINE_PROGRESS", "always");
  const ScopedEnv delay("VOLSPLINE_PROGRESS_DELAY", "0");
  const auto bar = test_support::run_cli("sweep-envelope " + box + " -o " + out("e.ply"), tmp.path());
  ASSERT_EQ(bar.code, 0) << bar.err;
  EXPECT_NE(bar.err.find("\rvolspline: reading"), std::string::npos) << bar.err;
  EXPECT_EQ(bar.err.find('\n'), std::string::npos) << bar.err;
  const auto quiet = test_support::run_cli("-q sweep-envelope " + box + " -o " + out("e.ply"), tmp.path());
  ASSERT_EQ(quiet.code, 0) << quiet.err;
  EXPECT_EQ(quiet.err, "");
}

TEST_F(ProgressCli, ForcedBarRewritesOneLineAndEndsErased) {
  const ScopedEnv always("VOLSPLINE_PROGRESS", "always");
  const ScopedEnv delay("VOLSPLINE_PROGRESS_DELAY", "0");
  const auto r = test_support::run_cli("boundary " + model() + " -o " + out("b.ply"), tmp.path());
  ASSERT_EQ(r.code, 0) << r.err;
  const std::string& e = r.err;
  EXPECT_NE(e.find("\rvolspline: reading"), std::string::npos) << e;  // the first phase, drawn at once
  EXPECT_EQ(e.find('\n'), std::string::npos) << e;  // never a new line
  ASSERT_GE(e.size(), 2u);
  EXPECT_EQ(e.back(), '\r');
  const auto last = e.rfind('\r', e.size() - 2);
  ASSERT_NE(last, std::string::npos);
  EXPECT_EQ(e.substr(last + 1, e.size() - last - 2).find_first_not_of(' '), std::string::npos) << "not erased at the end";
  // And an error still comes out on a line of its own after the bar is gone.
  const auto bad = test_support::run_cli("boundary " + (tmp.path() / "missing.json").string() + " -o " + out("m.ply"), tmp.path());
  EXPECT_EQ(bad.code, 2);
  EXPECT_NE(bad.err.find("volspline: error:"), std::string::npos) << bad.err;
}

}  // namespace
}  // namespace volspline
