// Every `build/bin/volspline ...` line of README.md's ```sh blocks runs as written from a fresh
// clone: each is run by the shell in a scratch folder holding a copy of examples/ (all a clone
// has that the commands read), with build/bin/volspline standing for the binary under test and
// /tmp/ for a scratch folder of its own; the lines run in order, so later ones may read what
// earlier ones wrote, as in the README.
#include <gtest/gtest.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <regex>
#include <sstream>
#include <string>
#include <sys/wait.h>
#include <vector>

#include "support/temporary_directory.h"

namespace volspline {
namespace {

const std::string kCommand = "build/bin/volspline";

// The lines of the ```sh blocks of `markdown` that run the command line.
std::vector<std::string> readme_command_lines(const std::string& markdown) {
  std::vector<std::string> lines;
  std::istringstream in(markdown);
  std::string line;
  bool in_sh_block = false;
  while (std::getline(in, line)) {
    if (line.rfind("```", 0) == 0) {
      in_sh_block = !in_sh_block && line == "```sh";
      continue;
    }
    if (in_sh_block && line.rfind(kCommand + " ", 0) == 0) lines.push_back(line);
  }
  return lines;
}

// `line` with the binary under test for every build/bin/volspline, `scratch` for every /tmp/
// and its trailing comment (" # ...") dropped.
std::string runnable(std::string line, const std::filesystem::path& scratch) {
  line = std::regex_replace(line, std::regex("[ \t]+#.*$"), "");
  // /tmp/ first: the binary's own path may lie below /tmp (a clone there) and must stay as it is.
  line = std::regex_replace(line, std::regex("(^|[ =])/tmp/"), "$1" + scratch.string() + "/");
  line = std::regex_replace(line, std::regex("(^|[ ;&|])build/bin/volspline "), "$1" + std::string(VOLSPLINE_CLI) + " ");
  return line;
}

TEST(ReadmeCommands, EveryCommandRunsAsWritten) {
  std::ifstream file(std::string(VOLSPLINE_SOURCE_DIR) + "/README.md");
  ASSERT_TRUE(file) << "README.md not found";
  std::stringstream text;
  text << file.rdbuf();
  const std::vector<std::string> lines = readme_command_lines(text.str());
  ASSERT_GE(lines.size(), 8u) << "the README's examples were not found";

  test_support::TemporaryDirectory clone;
  std::filesystem::copy(std::string(VOLSPLINE_SOURCE_DIR) + "/examples", clone.path() / "examples",
                        std::filesystem::copy_options::recursive);
  const std::filesystem::path scratch = clone.path() / "tmp";
  std::filesystem::create_directories(scratch);
  for (const std::string& line : lines) {
    const std::string log = (clone.path() / "log.txt").string();
    const std::string command = "cd '" + clone.path().string() + "' && { " + runnable(line, scratch) + " ; } >'" + log + "' 2>&1 </dev/null";
    const int status = std::system(command.c_str());
    std::ifstream in(log);
    std::stringstream output;
    output << in.rdbuf();
    EXPECT_TRUE(WIFEXITED(status) && WEXITSTATUS(status) == 0) << line << "\n" << output.str();
  }
}

TEST(ReadmeCommands, FindsTheCommandLinesOfShellBlocksOnly) {
  const std::string markdown =
      "text build/bin/volspline info x\n```sh\nbuild/bin/volspline info a.json   # comment\nmake demo\n```\n"
      "```json\nbuild/bin/volspline no\n```\n```sh\nbuild/bin/volspline make ball -o /tmp/b.json && build/bin/volspline info /tmp/b.json\n```\n";
  const auto lines = readme_command_lines(markdown);
  ASSERT_EQ(lines.size(), 2u);
  EXPECT_EQ(runnable(lines[0], "/s"), std::string(VOLSPLINE_CLI) + " info a.json");
  EXPECT_EQ(runnable(lines[1], "/s"),
            std::string(VOLSPLINE_CLI) + " make ball -o /s/b.json && " + std::string(VOLSPLINE_CLI) + " info /s/b.json");
}

}  // namespace
}  // namespace volspline
