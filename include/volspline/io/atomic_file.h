#pragma once
// Output files appear whole or not at all, and nothing but the targets is ever left behind.
//
// - AtomicFile writes to a temporary file beside the target, created exclusively (O_EXCL) under
//   a random name, and renames it over the target on commit(). A failure before commit()
//   removes the temporary file.
// - A target that is a symbolic link is written through: the file it points to is replaced and
//   the link kept. Anything that is not a regular file (a directory, a device node, a FIFO) is
//   never replaced: IoError.
// - OutputTransaction makes all outputs of one command one transaction: while one is open,
//   commit() only hands the finished temporary file over; OutputTransaction::commit() renames
//   them all, and if one rename fails restores what the earlier ones replaced. Two outputs of
//   the same transaction (or two open AtomicFiles) naming one file, under any spelling, through
//   links or hard links, are refused (InvalidInput).
// - remove_temporary_files_on_signals() makes SIGINT and SIGTERM remove every pending temporary
//   file before the process exits with 128 + the signal number (130, 143).
// docs/testing.md, "Hostile input: output files and limits", lists the cases and the tests.
#include <cstdint>
#include <filesystem>
#include <memory>
#include <ostream>
#include <string>
#include <string_view>
#include <vector>

namespace volspline {

class AtomicFile {
 public:
  /// Opens a temporary file next to `path` (next to the file it points to, if `path` is a
  /// symbolic link). \throw IoError if it cannot be created or `path` is not a regular file;
  /// InvalidInput if another output of this process is writing the same file.
  explicit AtomicFile(std::filesystem::path path, bool binary = true);
  ~AtomicFile();
  AtomicFile(const AtomicFile&) = delete;
  AtomicFile& operator=(const AtomicFile&) = delete;

  std::ostream& stream();
  /// Flushes and closes the temporary file and renames it onto the target, or, while an
  /// OutputTransaction is open, hands it to the transaction. \throw IoError on any write failure
  /// (naming the file and saying why, "the disk is full" for ENOSPC).
  void commit();

  struct Impl;

 private:
  std::unique_ptr<Impl> impl_;
};

/// All files one command writes, renamed onto their targets together (see the file comment).
/// At most one is open at a time; AtomicFile and write_file_atomically use the open one.
class OutputTransaction {
 public:
  OutputTransaction();
  /// Without commit(): removes the pending temporary files, restores files already replaced
  /// (publish_each_file) and removes the folders create_output_directories made.
  ~OutputTransaction();
  OutputTransaction(const OutputTransaction&) = delete;
  OutputTransaction& operator=(const OutputTransaction&) = delete;

  /// Renames every pending file onto its target. If one rename fails, the files renamed before
  /// it are restored (or removed where there was none) and IoError is thrown.
  void commit();
  /// From now on each file is renamed when it is committed, for a command that reads back what it
  /// wrote (demo); the transaction still undoes them all if it is not committed.
  void publish_each_file();
  /// The open transaction, or nullptr.
  static OutputTransaction* current();

  struct Entry;
  struct State;

 private:
  friend class AtomicFile;
  friend void create_output_directories(const std::filesystem::path& folder);
  void adopt(Entry entry, const void* claim_owner);
  void remember_folder(const std::filesystem::path& folder);
  std::unique_ptr<State> state_;
};

/// Creates `folder` and its missing parents; the open transaction, if it is not committed, removes
/// the ones this made again (when they are empty). \throw IoError naming the folder.
void create_output_directories(const std::filesystem::path& folder);

/// Installs handlers for SIGINT and SIGTERM that remove the pending temporary files (and the
/// empty folders create_output_directories made) and exit with 128 + the signal number.
void remove_temporary_files_on_signals();

/// Why a write failed, for messages: "the disk is full" for ENOSPC, "the disk quota is exceeded"
/// for EDQUOT, otherwise strerror.
std::string write_failure_reason(int errno_value);

/// Writes `bytes` to `path` atomically. \throw IoError, InvalidInput as AtomicFile.
void write_file_atomically(const std::filesystem::path& path, std::string_view bytes);

/// Reads a whole file. \throw IoError naming the file if it cannot be read, is a directory, or
/// is larger than `max_bytes` (also for pipes and devices, which are read only up to the limit).
std::string read_file(const std::filesystem::path& path);
std::string read_file(const std::filesystem::path& path, std::uint64_t max_bytes);

}  // namespace volspline
