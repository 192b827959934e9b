// Hostile but legal use of the command line's outputs (docs/testing.md, "Hostile input: output
// files and limits"): every command's outputs form one transaction, so a failing one leaves none
// of them; outputs are written through symbolic links, never over what is not a regular file, and
// never twice to one file; standard output errors are errors. The mechanism itself is proven in
// tests/io/atomic_file_test.cpp; these check that the commands use it.
#include <gtest/gtest.h>

#include <cstdlib>
#include <fstream>
#include <string>

#include <nlohmann/json.hpp>

#include "support/cli_runner.h"
#include "support/temporary_directory.h"
#include "volspline/io/atomic_file.h"

namespace volspline {
namespace {

using test_support::run_cli;

std::string output_files_cli_path(const test_support::TemporaryDirectory& dir, const std::string& name) { return (dir / name).string(); }

// A small model, written once per test.
std::string output_files_cli_model(const test_support::TemporaryDirectory& dir) {
  const std::string model = output_files_cli_path(dir, "box.json");
  const auto r = run_cli("make box --size 1,2,3 -o " + model, dir.path());
  EXPECT_EQ(r.code, 0) << r.err;
  return model;
}

const char* kOutputFilesScene = R"({"volspline_scene": 1, "spacing": 0.5, "box": {"min": [-1, -1, -1], "max": [1, 1, 1]},
  "root": {"sphere": {"center": [0, 0, 0], "radius": 0.7}}})";

TEST(OutputFilesCli, AFailingOutputLeavesNoneOfTheOthersInEveryCommandThatWritesSeveral) {
  test_support::TemporaryDirectory dir;
  const std::string model = output_files_cli_model(dir);
  write_file_atomically(dir / "scene.json", kOutputFilesScene);
  // Folders where an output should go: each named with the extension its output needs, so that
  // the command fails at writing and not at choosing the format.
  for (const char* folder : {"taken", "taken.png", "taken.ply", "taken.json"}) std::filesystem::create_directory(dir / folder);
  const std::string a = output_files_cli_path(dir, "a.ply"), png = output_files_cli_path(dir, "a.png");
  const std::string taken = output_files_cli_path(dir, "taken"), missing = output_files_cli_path(dir, "none/s.json");
  const std::string scene = output_files_cli_path(dir, "scene.json");
  const std::vector<std::string> commands{
      "blend " + scene + " --levels 1 -o " + a + " --png " + png + " --stats " + missing,
      "blend " + scene + " --levels 1 -o " + output_files_cli_path(dir, "taken.ply") + " --png " + png,
      "blend " + scene + " --levels 1 -o " + a + " --png " + output_files_cli_path(dir, "taken.png"),
      "boundary " + model + " -o " + a + " --png " + png + " --stats " + taken,
      "faces " + model + " -o " + a + " --png " + output_files_cli_path(dir, "taken.png"),
      "faces " + model + " -o " + output_files_cli_path(dir, "none/f.ply") + " --png " + png,
      "view " + model + " -o " + png + " --faces --mesh " + output_files_cli_path(dir, "taken.ply"),
      "convert " + model + " -o " + output_files_cli_path(dir, "taken.json"),
  };
  const std::size_t before = dir.entries();
  for (const std::string& command : commands) {
    const auto r = run_cli(command, dir.path());
    EXPECT_EQ(r.code, 2) << command << "\n" << r.err;
    EXPECT_NE(r.err.find("cannot write"), std::string::npos) << command << ": failed before writing: " << r.err;
    EXPECT_FALSE(std::filesystem::exists(a)) << command;
    EXPECT_FALSE(std::filesystem::exists(png)) << command;
    EXPECT_EQ(dir.entries(), before) << command << ": a file or temporary file was left behind";
  }
}

TEST(OutputFilesCli, TheSameFileForTwoOutputsIsRefusedUnderAnySpelling) {
  test_support::TemporaryDirectory dir;
  const std::string model = output_files_cli_model(dir);
  write_file_atomically(dir / "x.ply", "old");
  std::filesystem::create_symlink(dir / "x.ply", dir / "link.ply");
  for (const std::string& stats : {output_files_cli_path(dir, "x.ply"), output_files_cli_path(dir, "./x.ply"),
                                   output_files_cli_path(dir, "link.ply")}) {
    const auto r = run_cli("boundary " + model + " -o " + output_files_cli_path(dir, "x.ply") + " --stats " + stats, dir.path());
    EXPECT_EQ(r.code, 2) << stats;
    EXPECT_NE(r.err.find("same file"), std::string::npos) << r.err;
    EXPECT_EQ(read_file(dir / "x.ply"), "old");
  }
}

TEST(OutputFilesCli, OutputsGoThroughSymbolicLinksAndNeverOverWhatIsNotARegularFile) {
  test_support::TemporaryDirectory dir;
  const std::string model = output_files_cli_model(dir);
  std::filesystem::create_directory(dir / "real");
  std::filesystem::create_symlink("real/faces.ply", dir / "link.ply");
  auto r = run_cli("faces " + model + " -o " + output_files_cli_path(dir, "link.ply"), dir.path());
  ASSERT_EQ(r.code, 0) << r.err;
  EXPECT_TRUE(std::filesystem::is_symlink(dir / "link.ply"));
  EXPECT_GT(std::filesystem::file_size(dir / "real" / "faces.ply"), 100u);
  // Something that is not a regular file but has a mesh extension: a folder.
  std::filesystem::create_directory(dir / "folder.ply");
  r = run_cli("faces " + model + " -o " + output_files_cli_path(dir, "folder.ply"), dir.path());
  EXPECT_EQ(r.code, 2);
  EXPECT_NE(r.err.find("regular file"), std::string::npos) << r.err;
  EXPECT_TRUE(std::filesystem::is_directory(dir / "folder.ply"));
}

TEST(OutputFilesCli, AFailureToWriteStandardOutputIsAnError) {
  test_support::TemporaryDirectory dir;
  const std::string model = output_files_cli_model(dir);
  const std::string err = output_files_cli_path(dir, "err.txt");
  for (const std::string& command : {"eval " + model + " --grid 40,40,40", "info --json " + model, "eval " + model + " --at 0,0,0"}) {
    const int status = std::system((std::string(VOLSPLINE_CLI) + " " + command + " >/dev/full 2>" + err).c_str());
    ASSERT_TRUE(WIFEXITED(status));
    EXPECT_EQ(WEXITSTATUS(status), 2) << command;
    EXPECT_NE(read_file(err).find("disk is full"), std::string::npos) << command << ": " << read_file(err);
  }
}

TEST(OutputFilesCli, AFailedDemoLeavesNoFolder) {
  test_support::TemporaryDirectory dir;
  const auto r = run_cli("demo --only nosuch --out " + output_files_cli_path(dir, "made/demo"), dir.path());
  EXPECT_EQ(r.code, 2);
  EXPECT_FALSE(std::filesystem::exists(dir / "made"));
}

TEST(OutputFilesCli, ObjectIndicesAreSignedAndNegativeOnesRefused) {
  test_support::TemporaryDirectory dir;
  const std::string model = output_files_cli_model(dir);
  for (const std::string& command : {"eval " + model + " --at 0,0,0 --object -1", "xray " + model + " -o x.png --object -1"}) {
    const auto r = run_cli(command, dir.path());
    EXPECT_EQ(r.code, 2) << command;
    EXPECT_NE(r.err.find("-1"), std::string::npos) << r.err;
    EXPECT_EQ(r.err.find("18446744073709551615"), std::string::npos) << r.err;
  }
}

TEST(OutputFilesCli, JsonOutputReplacesInvalidUtf8AndHasNoInfinityStrings) {
  test_support::TemporaryDirectory dir;
  write_file_atomically(dir / "bad-name.itd", "[OBJECT QU\xff\xfeRTER\n    [CURVE BSPLINE 2 2 E3\n        [KV 0 0 1 1]\n"
                                              "        [0 0 0]\n        [1 0 0]\n    ]\n]\n");
  const auto r = run_cli("info --json " + output_files_cli_path(dir, "bad-name.itd"), dir.path());
  ASSERT_NE(r.code, 1) << r.err;  // a refusal of the name (2) would be fine too
  if (r.code == 0) {
    const nlohmann::json info = nlohmann::json::parse(r.out);
    EXPECT_NE(info.dump().find("QU\xef\xbf\xbd"), std::string::npos) << r.out;  // U+FFFD
  }
  const std::string model = output_files_cli_path(dir, "shell.json");
  ASSERT_EQ(run_cli("make half-torus -o " + model, dir.path()).code, 0);
  const auto j = run_cli("jacobian --json " + model, dir.path());
  ASSERT_EQ(j.code, 0) << j.err;
  const nlohmann::json out = nlohmann::json::parse(j.out);
  for (const auto& object : out["objects"]) {
    ASSERT_TRUE(object.contains("bounds_finite"));
    EXPECT_EQ(object["bounds_finite"].get<bool>(), object["lower"].is_number() && object["upper"].is_number());
    for (const char* key : {"lower", "upper", "witness_value"}) EXPECT_FALSE(object[key].is_string()) << key;
  }
}

TEST(OutputFilesCli, TheUnknownExtensionHintNamesTheOptionTheCommandTakes) {
  test_support::TemporaryDirectory dir;
  write_file_atomically(dir / "model.xyz", "{}");
  for (const char* command : {"info ", "eval --at 0,0,0 ", "view -o v.png --faces "}) {
    const auto r = run_cli(command + output_files_cli_path(dir, "model.xyz"), dir.path());
    EXPECT_EQ(r.code, 2) << command;
    EXPECT_NE(r.err.find("--input-format"), std::string::npos) << r.err;
  }
  const auto r = run_cli("convert " + output_files_cli_model(dir) + " -o out.xyz", dir.path());
  EXPECT_EQ(r.code, 2);
  EXPECT_NE(r.err.find("--format"), std::string::npos) << r.err;
  EXPECT_EQ(r.err.find("--input-format"), std::string::npos) << r.err;
}

// ---- Limits known before the work -------------------------------------------------------------

TEST(OutputFilesCli, RequestsBeyondTheLimitsAreRefusedBeforeTheWorkSayingWhatAndTheLimit) {
  test_support::TemporaryDirectory dir;
  const std::string model = output_files_cli_model(dir);
  const std::string picture = output_files_cli_path(dir, "v.png");
  struct Case {
    std::string command, says;
  };
  const std::vector<Case> cases{
      {"convert " + model + " --elevate u:1000000 -o e.json", "64"},
      {"view " + model + " -o " + picture + " --slices x:1 --resolution 512", "memory limit"},
      {"view " + model + " -o " + picture + " --iso u:1000 --resolution 512", "memory limit"},
      {"jacobian " + model + " --max-cells 100000000", "--max-cells 100000000"},
      {"--memory-limit 1M info --input-format json /dev/zero", "256 KiB"},
      {"--memory-limit 64M view " + model + " -o " + picture + " --slices x:1 --resolution 256", "64 MiB"},
      {"--work-limit 1000 jacobian " + model, "work limit"},
  };
  for (const Case& c : cases) {
    const auto r = run_cli(c.command, dir.path());
    EXPECT_EQ(r.code, 2) << c.command << "\n" << r.err;
    EXPECT_NE(r.err.find(c.says), std::string::npos) << c.command << "\n" << r.err;
    EXPECT_FALSE(std::filesystem::exists(dir / "v.png")) << c.command;
  }
  // The environment variable sets the limit as the option does, and a raised limit lets the
  // refused request through.
  const std::string slices = "view " + model + " -o " + picture + " --slices x:1 --resolution 64";
  EXPECT_EQ(run_cli("--memory-limit 1M " + slices, dir.path()).code, 2);
  EXPECT_EQ(std::system(("VOLSPLINE_MEMORY_LIMIT=1M " + std::string(VOLSPLINE_CLI) + " " + slices + " >/dev/null 2>&1").c_str()) >> 8, 2);
  EXPECT_EQ(run_cli("--memory-limit 1G " + slices, dir.path()).code, 0);
  EXPECT_EQ(run_cli("--memory-limit lots " + slices, dir.path()).code, 2);
}

}  // namespace
}  // namespace volspline
