// Output files appear whole or not at all, and nothing but the target is ever left behind.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <string>
#include <sys/stat.h>
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

}  // namespace
}  // namespace volspline
