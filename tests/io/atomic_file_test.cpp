// Output files appear whole or not at all, and nothing but the target is ever left behind.
#include <gtest/gtest.h>

#include <cerrno>
#include <csignal>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <string>
#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>

#include "support/temporary_directory.h"
#include "volspline/core/error.h"
#include "volspline/io/atomic_file.h"

namespace volspline {
namespace {

std::string contents(const std::filesystem::path& path) { return read_file(path); }

TEST(AtomicFile, TheTargetAppearsOnlyOnCommitAndAlone) {
  test_support::TemporaryDirectory dir;
  const auto target = dir / "out.bin";
  {
    AtomicFile file(target);
    file.stream() << "first half ";
    EXPECT_FALSE(std::filesystem::exists(target)) << "visible before commit";
    file.stream() << "second half";
    file.commit();
  }
  EXPECT_EQ(contents(target), "first half second half");
  EXPECT_EQ(dir.entries(), 1u) << "a temporary file was left beside the target";
}

TEST(AtomicFile, WithoutCommitNothingIsLeftAndAnOldTargetIsUntouched) {
  test_support::TemporaryDirectory dir;
  const auto target = dir / "model.json";
  write_file_atomically(target, "old contents");
  try {
    AtomicFile file(target);
    file.stream() << "half of the new cont";
    throw std::runtime_error("the writer failed half way");
  } catch (const std::runtime_error&) {
  }
  EXPECT_EQ(contents(target), "old contents");
  EXPECT_EQ(dir.entries(), 1u);
}

TEST(AtomicFile, CommitReplacesAnExistingFileWhole) {
  test_support::TemporaryDirectory dir;
  const auto target = dir / "picture.png";
  write_file_atomically(target, std::string(100000, 'a'));
  write_file_atomically(target, "short");
  EXPECT_EQ(contents(target), "short");
  EXPECT_EQ(dir.entries(), 1u);
}

TEST(AtomicFile, BinaryBytesRoundTripExactly) {
  test_support::TemporaryDirectory dir;
  std::string bytes;
  for (int i = 0; i < 256; ++i) bytes.push_back(static_cast<char>(i));
  bytes += std::string("\r\n\0\n", 4);
  write_file_atomically(dir / "bytes", bytes);
  EXPECT_EQ(contents(dir / "bytes"), bytes);
}

TEST(AtomicFile, UnwritablePlacesAreIoErrorsNamingTheFileAndCreateNothing) {
  test_support::TemporaryDirectory dir;
  const auto missing_folder = dir / "no-such-folder" / "out.ply";
  try {
    AtomicFile file(missing_folder);
    FAIL() << "opened a file in a folder that does not exist";
  } catch (const IoError& e) {
    EXPECT_NE(std::string(e.what()).find("out.ply"), std::string::npos) << e.what();
  }
  // The target is a folder: the rename must fail and the temporary must go.
  std::filesystem::create_directory(dir / "taken");
  std::filesystem::create_directory(dir / "taken" / "inside");
  EXPECT_THROW(write_file_atomically(dir / "taken", "x"), IoError);
  EXPECT_TRUE(std::filesystem::is_directory(dir / "taken" / "inside"));
  EXPECT_TRUE(std::filesystem::is_directory(dir / "taken"));
  EXPECT_EQ(dir.entries(), 1u) << "a temporary file was left behind";  // only "taken": "no-such-folder" was never made
}

TEST(AtomicFile, ReadingMissingFilesAndFoldersIsAnIoErrorNamingThePath) {
  test_support::TemporaryDirectory dir;
  for (const auto& path : {dir / "absent.json", dir.path()}) {
    try {
      (void)read_file(path);
      FAIL() << "read " << path;
    } catch (const IoError& e) {
      EXPECT_NE(std::string(e.what()).find(path.filename().string()), std::string::npos) << e.what();
    }
  }
}

// ---- All outputs of one command as one transaction -------------------------------------------

TEST(OutputTransaction, FilesAppearTogetherOnCommitAndNotAtAllWithout) {
  test_support::TemporaryDirectory dir;
  write_file_atomically(dir / "old.json", "old");
  {
    OutputTransaction outputs;
    write_file_atomically(dir / "a.ply", "mesh");
    write_file_atomically(dir / "old.json", "new");
    AtomicFile stats(dir / "s.json");
    stats.stream() << "stats";
    stats.commit();
    EXPECT_FALSE(std::filesystem::exists(dir / "a.ply")) << "visible before the transaction committed";
    EXPECT_EQ(contents(dir / "old.json"), "old");
    outputs.commit();
  }
  EXPECT_EQ(contents(dir / "a.ply"), "mesh");
  EXPECT_EQ(contents(dir / "old.json"), "new");
  EXPECT_EQ(contents(dir / "s.json"), "stats");
  EXPECT_EQ(dir.entries(), 3u);
  {
    OutputTransaction outputs;  // a command that fails after writing two of its outputs
    write_file_atomically(dir / "a.ply", "mesh 2");
    write_file_atomically(dir / "b.png", "picture 2");
  }
  EXPECT_EQ(contents(dir / "a.ply"), "mesh");
  EXPECT_FALSE(std::filesystem::exists(dir / "b.png"));
  EXPECT_EQ(dir.entries(), 3u) << "a temporary file was left behind";
}

TEST(OutputTransaction, AFailedRenameRestoresWhatTheEarlierOnesReplaced) {
  test_support::TemporaryDirectory dir;
  write_file_atomically(dir / "a.ply", "old a");
  write_file_atomically(dir / "b.png", "old b");
  OutputTransaction outputs;
  write_file_atomically(dir / "a.ply", "new a");
  write_file_atomically(dir / "b.png", "new b");
  write_file_atomically(dir / "c.json", "new c");
  write_file_atomically(dir / "d.json", "new d");
  // Something takes the place of the third output between its writing and the commit.
  std::filesystem::create_directory(dir / "d.json");
  std::filesystem::create_directory(dir / "d.json" / "inside");
  try {
    outputs.commit();
    FAIL() << "renamed a file over a folder";
  } catch (const IoError& e) {
    EXPECT_NE(std::string(e.what()).find("d.json"), std::string::npos) << e.what();
  }
  EXPECT_EQ(contents(dir / "a.ply"), "old a");
  EXPECT_EQ(contents(dir / "b.png"), "old b");
  EXPECT_FALSE(std::filesystem::exists(dir / "c.json")) << "a file that was not there before stayed";
  EXPECT_TRUE(std::filesystem::is_directory(dir / "d.json" / "inside"));
  EXPECT_EQ(dir.entries(), 3u) << "a temporary or backup file was left behind";
}

TEST(OutputTransaction, PublishingEachFileStillUndoesThemAll) {
  test_support::TemporaryDirectory dir;
  write_file_atomically(dir / "old.json", "old");
  {
    OutputTransaction outputs;
    outputs.publish_each_file();
    create_output_directories(dir / "made" / "deeper");
    write_file_atomically(dir / "made" / "deeper" / "x.json", "x");
    write_file_atomically(dir / "old.json", "new");
    EXPECT_EQ(contents(dir / "made" / "deeper" / "x.json"), "x") << "not readable back at once";
    EXPECT_EQ(contents(dir / "old.json"), "new");
  }
  EXPECT_EQ(contents(dir / "old.json"), "old");
  EXPECT_FALSE(std::filesystem::exists(dir / "made")) << "the folders it made stayed";
  EXPECT_EQ(dir.entries(), 1u);
  {
    OutputTransaction outputs;
    create_output_directories(dir / "kept");
    write_file_atomically(dir / "kept" / "x.json", "x");
    outputs.commit();
  }
  EXPECT_EQ(contents(dir / "kept" / "x.json"), "x");
}

// ---- Two outputs naming one file --------------------------------------------------------------

TEST(AtomicFile, TwoOutputsNamingOneFileUnderAnySpellingAreRefused) {
  test_support::TemporaryDirectory dir;
  std::filesystem::create_directory(dir / "sub");
  write_file_atomically(dir / "x.ply", "original");
  std::filesystem::create_symlink(dir / "x.ply", dir / "link.ply");
  std::filesystem::create_hard_link(dir / "x.ply", dir / "hard.ply");
  const std::filesystem::path relative = std::filesystem::relative(dir / "x.ply");
  for (const auto& other : {dir / "x.ply", dir / "sub" / ".." / "x.ply", dir.path() / "." / "x.ply", dir / "link.ply",
                            dir / "hard.ply", relative}) {
    OutputTransaction outputs;
    write_file_atomically(dir / "x.ply", "mesh");
    EXPECT_THROW(write_file_atomically(other, "stats"), InvalidInput) << other;
  }
  AtomicFile open(dir / "y.ply");  // also without a transaction, while both are open
  EXPECT_THROW(AtomicFile(dir / "sub" / ".." / "y.ply"), InvalidInput);
  EXPECT_EQ(contents(dir / "x.ply"), "original");
  EXPECT_EQ(dir.entries(), 5u) << "x, link, hard, sub and y's temporary";
}

// ---- Symbolic links and what is not a regular file ---------------------------------------------

TEST(AtomicFile, AnOutputThroughASymbolicLinkReplacesItsTargetAndKeepsTheLink) {
  test_support::TemporaryDirectory dir;
  std::filesystem::create_directory(dir / "real");
  write_file_atomically(dir / "real" / "model.json", "old");
  std::filesystem::create_symlink("real/model.json", dir / "link.json");  // relative to the link's folder
  std::filesystem::create_symlink("link.json", dir / "link2.json");      // a chain
  std::filesystem::create_symlink("real/new.json", dir / "dangling.json");
  write_file_atomically(dir / "link2.json", "new");
  write_file_atomically(dir / "dangling.json", "created");
  EXPECT_TRUE(std::filesystem::is_symlink(dir / "link.json"));
  EXPECT_TRUE(std::filesystem::is_symlink(dir / "link2.json"));
  EXPECT_TRUE(std::filesystem::is_symlink(dir / "dangling.json"));
  EXPECT_EQ(contents(dir / "real" / "model.json"), "new");
  EXPECT_EQ(contents(dir / "real" / "new.json"), "created");
  EXPECT_EQ(std::distance(std::filesystem::directory_iterator(dir / "real"), {}), 2);
}

TEST(AtomicFile, OnlyRegularFilesAreReplaced) {
  test_support::TemporaryDirectory dir;
  std::filesystem::create_directory(dir / "folder");
  ASSERT_EQ(::mkfifo((dir / "fifo").c_str(), 0600), 0);
  std::filesystem::create_symlink(dir / "folder", dir / "link-to-folder");
  for (const auto& path : {dir / "folder", dir / "fifo", dir / "link-to-folder", std::filesystem::path("/dev/null")}) {
    try {
      write_file_atomically(path, "x");
      FAIL() << "replaced " << path;
    } catch (const IoError& e) {
      EXPECT_NE(std::string(e.what()).find("regular file"), std::string::npos) << e.what();
    }
  }
  struct stat status {};
  ASSERT_EQ(::stat("/dev/null", &status), 0);
  EXPECT_TRUE(S_ISCHR(status.st_mode));
  EXPECT_TRUE(std::filesystem::is_fifo(dir / "fifo"));
  EXPECT_TRUE(std::filesystem::is_symlink(dir / "link-to-folder"));
  EXPECT_EQ(dir.entries(), 3u);
}

TEST(AtomicFile, ANewFileGetsTheUsualModeAndAReplacedOneKeepsItsMode) {
  test_support::TemporaryDirectory dir;
  const mode_t mask = ::umask(022);
  ::umask(mask);
  write_file_atomically(dir / "new", "x");
  struct stat status {};
  ASSERT_EQ(::stat((dir / "new").c_str(), &status), 0);
  EXPECT_EQ(status.st_mode & 0777, 0666 & ~mask) << "the temporary file's 0600 stayed";
  ASSERT_EQ(::chmod((dir / "new").c_str(), 0640), 0);
  write_file_atomically(dir / "new", "y");
  ASSERT_EQ(::stat((dir / "new").c_str(), &status), 0);
  EXPECT_EQ(status.st_mode & 0777, 0640u);
}

// ---- Temporary names: exclusive and random, not from the process id ---------------------------

TEST(AtomicFile, NamesAnotherProcessMightUseAreNeverTouched) {
  // Processes in other PID namespaces share process ids: a name built from the id could be one
  // another writer is using.
  test_support::TemporaryDirectory dir;
  for (int n = 0; n < 8; ++n) write_file_atomically(dir / (".out.ply.tmp-" + std::to_string(::getpid()) + "-" + std::to_string(n)), "theirs");
  for (int i = 0; i < 8; ++i) write_file_atomically(dir / "out.ply", "mine");
  for (int n = 0; n < 8; ++n) EXPECT_EQ(contents(dir / (".out.ply.tmp-" + std::to_string(::getpid()) + "-" + std::to_string(n))), "theirs");
  EXPECT_EQ(dir.entries(), 9u);
}

TEST(AtomicFile, TwoWritersOfOneFileLeaveOneWholeFile) {
  test_support::TemporaryDirectory dir;
  const auto target = dir / "shared.ply";
  const std::string first(300000, 'a'), second(200000, 'b');
  std::vector<pid_t> writers;
  for (const std::string* bytes : {&first, &second}) {
    const pid_t pid = ::fork();
    ASSERT_GE(pid, 0);
    if (pid == 0) {
      int failures = 0;
      for (int i = 0; i < 30; ++i) {
        try {
          write_file_atomically(target, *bytes);
        } catch (...) {
          ++failures;
        }
      }
      ::_exit(failures == 0 ? 0 : 1);
    }
    writers.push_back(pid);
  }
  // Whenever the file is there, it is one writer's whole output.
  for (int i = 0; i < 200; ++i) {
    std::error_code ec;
    if (!std::filesystem::exists(target, ec)) continue;
    const std::string seen = contents(target);
    ASSERT_TRUE(seen == first || seen == second) << "a mixed file of " << seen.size() << " bytes";
  }
  for (const pid_t pid : writers) {
    int status = 0;
    ASSERT_EQ(::waitpid(pid, &status, 0), pid);
    EXPECT_TRUE(WIFEXITED(status) && WEXITSTATUS(status) == 0);
  }
  const std::string final_bytes = contents(target);
  EXPECT_TRUE(final_bytes == first || final_bytes == second);
  EXPECT_EQ(dir.entries(), 1u);
}

// ---- Signals ---------------------------------------------------------------------------------

void atomic_file_test_interrupted_writer(const std::filesystem::path& folder, int signal_number) {
  remove_temporary_files_on_signals();
  OutputTransaction outputs;
  create_output_directories(folder / "made");
  write_file_atomically(folder / "made" / "pending.ply", "finished but not committed");
  AtomicFile file(folder / "half.png");
  file.stream() << "half of a picture";
  file.stream().flush();
  std::raise(signal_number);
}

TEST(AtomicFileDeathTest, SigintAndSigtermRemoveTheTemporaryFilesAndExit128PlusTheSignal) {
  GTEST_FLAG_SET(death_test_style, "fast");  // the child must see this test's folder
  for (const auto& signal_and_code : {std::pair(SIGINT, 130), std::pair(SIGTERM, 143)}) {
    const int signal_number = signal_and_code.first, code = signal_and_code.second;
    test_support::TemporaryDirectory dir;
    const std::filesystem::path folder = dir.path();
    EXPECT_EXIT(atomic_file_test_interrupted_writer(folder, signal_number), testing::ExitedWithCode(code), "");
    EXPECT_EQ(dir.entries(), 0u) << "signal " << signal_number << " left a temporary file or folder";
  }
}

// ---- Messages and reading --------------------------------------------------------------------

TEST(AtomicFile, AFullDiskIsCalledAFullDisk) {
  EXPECT_NE(write_failure_reason(ENOSPC).find("disk is full"), std::string::npos);
  EXPECT_NE(write_failure_reason(EDQUOT).find("quota"), std::string::npos);
  EXPECT_EQ(write_failure_reason(EACCES), std::strerror(EACCES));
}

TEST(AtomicFile, ReadingRefusesFilesAndStreamsBeyondTheLimitNamingBoth) {
  test_support::TemporaryDirectory dir;
  write_file_atomically(dir / "big.json", std::string(1001, ' '));
  EXPECT_EQ(read_file(dir / "big.json", 1001).size(), 1001u);
  for (const auto& path : {dir / "big.json", std::filesystem::path("/dev/zero")}) {
    try {
      (void)read_file(path, 1000);
      FAIL() << "read " << path;
    } catch (const IoError& e) {
      const std::string message = e.what();
      EXPECT_NE(message.find(path.filename().string()), std::string::npos) << message;
      EXPECT_NE(message.find("1000 bytes"), std::string::npos) << message;
      EXPECT_NE(message.find("--memory-limit"), std::string::npos) << message;
    }
  }
}

}  // namespace
}  // namespace volspline
