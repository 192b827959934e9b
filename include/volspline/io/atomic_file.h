#pragma once
// Output files appear whole or not at all: data is written to a temporary file beside the
// target and renamed over it on commit(). A failure before commit() removes the temporary file,
// so no half-written output is ever left behind.
#include <filesystem>
#include <fstream>
#include <string>
#include <string_view>

namespace volspline {

class AtomicFile {
 public:
  /// Opens a temporary file next to `path`. \throw IoError if it cannot be created.
  explicit AtomicFile(std::filesystem::path path, bool binary = true);
  ~AtomicFile();
  AtomicFile(const AtomicFile&) = delete;
  AtomicFile& operator=(const AtomicFile&) = delete;

  std::ostream& stream() { return out_; }
  /// Flushes, closes and renames onto the target. \throw IoError on any write failure.
  void commit();

 private:
  std::filesystem::path path_;
  std::filesystem::path temporary_;
  std::ofstream out_;
  bool committed_ = false;
};

/// Writes `bytes` to `path` atomically. \throw IoError.
void write_file_atomically(const std::filesystem::path& path, std::string_view bytes);

/// Reads a whole file. \throw IoError naming the file if it cannot be read.
std::string read_file(const std::filesystem::path& path);

}  // namespace volspline
