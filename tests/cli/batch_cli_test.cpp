// `volspline batch`: the command line hands its arguments to the Python module volspline.batch
// (Dask) with the build tree's package on PYTHONPATH; a small batch of boxes gives their exact
// volumes, a missing model its own failed row, and a rerun skips what is done. Skipped where
// Debian's Python has no Dask or the build has no Python module.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <map>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "support/cli_runner.h"
#include "support/temporary_directory.h"

namespace volspline {
namespace {

// Why `volspline batch` cannot run here, or empty.
std::string batch_unavailable() {
  namespace fs = std::filesystem;
  if (!fs::exists(fs::path(VOLSPLINE_CLI).parent_path().parent_path() / "python" / "volspline" / "batch.py"))
    return "the build has no Python module (VOLSPLINE_BUILD_PYTHON=OFF)";
  if (std::system("/usr/bin/python3 -c 'import dask, distributed' >/dev/null 2>&1") != 0)
    return "Debian's python3 has no Dask (apt-get install python3-dask python3-distributed)";
  return "";
}

std::vector<nlohmann::json> batch_rows(const std::filesystem::path& jsonl) {
  std::ifstream in(jsonl);
  std::vector<nlohmann::json> rows;
  for (std::string line; std::getline(in, line);) rows.push_back(nlohmann::json::parse(line));
  return rows;
}

TEST(BatchCli, MassOfBoxesEqualsTheirVolumesAndAMissingModelFailsInItsRow) {
  if (const std::string why = batch_unavailable(); !why.empty()) GTEST_SKIP() << why;
  test_support::TemporaryDirectory tmp;
  const auto dir = tmp.path();
  const std::map<std::string, double> boxes = {{"a.json", 6.0}, {"b.json", 8.0}};
  ASSERT_EQ(test_support::run_cli("make box --size 1,2,3 -o " + (dir / "a.json").string(), dir).code, 0);
  ASSERT_EQ(test_support::run_cli("make box --size 2,2,2 -o " + (dir / "b.json").string(), dir).code, 0);
  const std::string models = (dir / "a.json").string() + " " + (dir / "b.json").string() + " " + (dir / "missing.json").string();
  const std::string command = "-q batch mass " + models + " --out " + (dir / "out").string() + " --workers 1";

  const auto r = test_support::run_cli(command, dir);
  EXPECT_EQ(r.code, 3) << r.err;  // one model failed: its row says why
  EXPECT_NE(r.out.find("3 models: 2 ok, 1 failed"), std::string::npos) << r.out;
  const auto rows = batch_rows(dir / "out" / "results.jsonl");
  ASSERT_EQ(rows.size(), 3u);
  for (const auto& row : rows) {
    const std::string name = std::filesystem::path(row["file"].get<std::string>()).filename().string();
    if (name == "missing.json") {
      EXPECT_EQ(row["status"], "failed");
      EXPECT_EQ(row["exit_code"], 2);
      EXPECT_NE(row["error"].get<std::string>().find("missing.json"), std::string::npos) << row.dump();
      continue;
    }
    ASSERT_EQ(row["status"], "ok") << row.dump();
    // this executable ran the model
    EXPECT_EQ(std::filesystem::canonical(row["command"][0].get<std::string>()), std::filesystem::canonical(VOLSPLINE_CLI));
    const double volume = row["figures"][0]["volume"].get<double>();
    EXPECT_NEAR(volume, boxes.at(name), 1e-13 * boxes.at(name)) << name;
  }
  EXPECT_TRUE(std::filesystem::exists(dir / "out" / "results.csv"));

  const auto again = test_support::run_cli(command, dir);
  EXPECT_EQ(again.code, 3) << again.err;
  EXPECT_NE(again.out.find("(0 run, 3 skipped as done)"), std::string::npos) << again.out;
}

TEST(BatchCli, HelpAndBadUsage) {
  if (const std::string why = batch_unavailable(); !why.empty()) GTEST_SKIP() << why;
  test_support::TemporaryDirectory tmp;
  const auto help = test_support::run_cli("batch --help", tmp.path());
  EXPECT_EQ(help.code, 0) << help.err;
  EXPECT_NE(help.out.find("usage: volspline batch"), std::string::npos) << help.out;
  const auto listed = test_support::run_cli("--help", tmp.path());
  EXPECT_NE(listed.out.find("batch"), std::string::npos);
  const auto unknown = test_support::run_cli("batch nonsense a.json --out " + tmp.path().string(), tmp.path());
  EXPECT_EQ(unknown.code, 2);
  const auto no_models = test_support::run_cli("batch jacobian --out " + tmp.path().string(), tmp.path());
  EXPECT_EQ(no_models.code, 2);
  EXPECT_NE(no_models.err.find("no model files"), std::string::npos) << no_models.err;
}

}  // namespace
}  // namespace volspline
