// volspline batch OPERATION MODELS... --out DIR [...]: hands the command line to the Python
// module volspline.batch (Dask, docs/python.md "Batch runs (Dask)"), which runs this executable
// once per model. Nothing is computed here.
#include <unistd.h>

#include <cerrno>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <iostream>
#include <optional>
#include <string>
#include <vector>

#include "commands.h"
#include "volspline/core/error.h"
#include "volspline/core/resource_limits.h"

namespace volspline::cli {

namespace {

// Debian's interpreter, where python3-dask and python3-distributed install; a PATH that puts
// another Python first must not decide which one runs (as for the module's build).
constexpr const char* kBatchPython = "/usr/bin/python3";

// Runs volspline.batch.main; an import failure (no module built or installed, a broken
// extension) is a clear error with exit code 2 instead of a traceback. Dask itself is checked
// by main(), which says what to install.
constexpr const char* kBatchLauncher =
    "import sys\n"
    "try:\n"
    "    from volspline.batch import main\n"
    "except ImportError as e:\n"
    "    sys.stderr.write('volspline batch: error: cannot import the Python module volspline.batch (%s); build it "
    "(-DVOLSPLINE_BUILD_PYTHON=ON) or install it (cmake --install)\\n' % e)\n"
    "    sys.exit(2)\n"
    "sys.exit(main(sys.argv[1:]))\n";

std::filesystem::path batch_own_executable() {
  std::error_code error;
  auto path = std::filesystem::read_symlink("/proc/self/exe", error);
  return error ? std::filesystem::path{} : path;
}

// The folder holding the package volspline/ that belongs to this executable: the build tree's
// python/ (beside bin/), or the installed PREFIX/lib/python3.X/dist-packages. None: Python's
// own search path decides.
std::optional<std::filesystem::path> batch_package_root(const std::filesystem::path& executable) {
  namespace fs = std::filesystem;
  const fs::path prefix = executable.parent_path().parent_path();
  std::error_code error;
  if (fs::exists(prefix / "python" / "volspline" / "batch.py", error)) return prefix / "python";
  for (const auto& entry : fs::directory_iterator(prefix / "lib", error)) {
    if (entry.path().filename().string().rfind("python3", 0) != 0) continue;
    for (const char* site : {"dist-packages", "site-packages"})
      if (fs::exists(entry.path() / site / "volspline" / "batch.py", error)) return entry.path() / site;
  }
  return std::nullopt;
}

[[noreturn]] void exec_batch(const std::vector<std::string>& batch_arguments, bool quiet) {
  if (::access(kBatchPython, X_OK) != 0)
    throw InvalidInput(std::string("volspline batch runs on Debian's ") + kBatchPython +
                       ", which is missing; on Debian: apt-get install python3 python3-dask python3-distributed");
  const std::filesystem::path executable = batch_own_executable();
  if (const auto root = batch_package_root(executable)) {
    const char* old = std::getenv("PYTHONPATH");
    const std::string path = root->string() + (old != nullptr && *old != '\0' ? ":" + std::string(old) : "");
    ::setenv("PYTHONPATH", path.c_str(), 1);
  }
  // This executable runs the models, unless the arguments name another with --cli (the last wins).
  std::vector<std::string> arguments = {kBatchPython, "-c", kBatchLauncher};
  if (!executable.empty()) arguments.insert(arguments.end(), {"--cli", executable.string()});
  if (quiet) arguments.push_back("--quiet");
  arguments.insert(arguments.end(), batch_arguments.begin(), batch_arguments.end());
  std::vector<char*> argv;
  for (auto& a : arguments) argv.push_back(a.data());
  argv.push_back(nullptr);
  std::cout.flush();
  ::execv(kBatchPython, argv.data());
  throw InvalidInput(std::string("cannot run ") + kBatchPython + ": " + std::strerror(errno));
}

}  // namespace

std::optional<int> run_batch_command(int argc, char** argv) {
  // The global options may come first; --memory-limit and --work-limit reach every model's
  // command through the environment, which the CLI reads when they are not given.
  bool quiet = false;
  std::vector<std::pair<const char*, std::string>> environment;
  int i = 1;
  for (; i < argc; ++i) {
    const std::string a = argv[i];
    if (a == "-q" || a == "--quiet") {
      quiet = true;
    } else if (a == "-v" || a == "--verbose") {
      // Accepted and dropped: the models' commands report through their rows, not stderr.
    } else if (a == "--memory-limit" || a == "--work-limit" || a.rfind("--memory-limit=", 0) == 0 || a.rfind("--work-limit=", 0) == 0) {
      const bool memory = a.rfind("--memory-limit", 0) == 0;
      const auto equals = a.find('=');
      std::string value;
      if (equals != std::string::npos) {
        value = a.substr(equals + 1);
      } else if (i + 1 < argc) {
        value = argv[++i];
      }
      environment.emplace_back(memory ? "VOLSPLINE_MEMORY_LIMIT" : "VOLSPLINE_WORK_LIMIT", value);
    } else {
      break;
    }
  }
  if (i >= argc || std::string(argv[i]) != "batch") return std::nullopt;
  try {
    for (const auto& [name, value] : environment) {
      if (std::string(name) == "VOLSPLINE_MEMORY_LIMIT") {
        parse_byte_count(value, "--memory-limit");
      } else {
        parse_operation_count(value, "--work-limit");
      }
      ::setenv(name, value.c_str(), 1);
    }
    exec_batch(std::vector<std::string>(argv + i + 1, argv + argc), quiet);
  } catch (const Error& e) {
    std::cerr << "volspline: error: " << e.what() << "\n";
    return 2;
  }
}

void add_batch_command(CLI::App& app) {
  // Listed with the others for --help; main() hands `volspline [global options] batch ...` to
  // run_batch_command before parsing, since these arguments are volspline.batch's to parse
  // (CLI11 would take an operation named like a subcommand, `jacobian`, for that subcommand).
  auto* cmd = app.add_subcommand(
      "batch",
      "Run jacobian, boundary, convert, view, info or mass (info --mass) on many model files with Dask: "
      "one row per model in DIR/results.csv and .jsonl, outputs in DIR/outputs (volspline batch --help)");
  cmd->prefix_command();
  cmd->allow_extras();
  cmd->set_help_flag();
  cmd->fallthrough(false);
  cmd->callback([cmd] { exec_batch(cmd->remaining(), false); });
}

}  // namespace volspline::cli
