#include "volspline/io/atomic_file.h"

#include <atomic>
#include <cerrno>
#include <cstring>
#include <sstream>
#include <unistd.h>

#include "volspline/core/error.h"

namespace volspline {

namespace {
std::filesystem::path temporary_beside(const std::filesystem::path& path) {
  static std::atomic<unsigned> counter{0};
  std::ostringstream name;
  name << "." << path.filename().string() << ".tmp-" << ::getpid() << "-" << counter++;
  return path.parent_path() / name.str();
}
}  // namespace

AtomicFile::AtomicFile(std::filesystem::path path, bool binary)
    : path_(std::move(path)), temporary_(temporary_beside(path_)) {
  out_.open(temporary_, binary ? std::ios::binary | std::ios::out | std::ios::trunc
                               : std::ios::out | std::ios::trunc);
  if (!out_) {
    throw IoError("cannot write '" + path_.string() + "': " + std::strerror(errno));
  }
}

AtomicFile::~AtomicFile() {
  if (!committed_) {
    out_.close();
    std::error_code ignored;
    std::filesystem::remove(temporary_, ignored);
  }
}

void AtomicFile::commit() {
  out_.flush();
  const bool ok = static_cast<bool>(out_);
  out_.close();
  if (!ok || out_.fail()) {
    throw IoError("cannot write '" + path_.string() + "': write failed");
  }
  std::error_code ec;
  std::filesystem::rename(temporary_, path_, ec);
  if (ec) throw IoError("cannot write '" + path_.string() + "': " + ec.message());
  committed_ = true;
}

void write_file_atomically(const std::filesystem::path& path, std::string_view bytes) {
  AtomicFile file(path);
  file.stream().write(bytes.data(), static_cast<std::streamsize>(bytes.size()));
  file.commit();
}

std::string read_file(const std::filesystem::path& path) {
  std::error_code ec;
  if (std::filesystem::is_directory(path, ec)) {
    throw IoError("cannot read '" + path.string() + "': it is a directory");
  }
  std::ifstream in(path, std::ios::binary);
  if (!in) throw IoError("cannot read '" + path.string() + "': " + std::strerror(errno));
  std::ostringstream contents;
  contents << in.rdbuf();
  if (in.bad()) throw IoError("cannot read '" + path.string() + "': read failed");
  return contents.str();
}

}  // namespace volspline
