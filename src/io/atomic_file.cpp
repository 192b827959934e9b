#include "volspline/io/atomic_file.h"

#include <array>
#include <atomic>
#include <cerrno>
#include <csignal>
#include <cstdlib>
#include <cstring>
#include <fcntl.h>
#include <mutex>
#include <optional>
#include <random>
#include <streambuf>
#include <sys/stat.h>
#include <unistd.h>

#include "volspline/core/error.h"
#include "volspline/core/resource_limits.h"

namespace volspline {

namespace {

// ---- What the signal handler removes -------------------------------------------------------
// A fixed table of C strings the handler may read without locking or allocating: a slot holds a
// malloc'ed path while its file (or folder) is pending and nullptr otherwise. Removing a path
// that was renamed meanwhile only fails with ENOENT.
constexpr std::size_t kAtomicFileSignalSlots = 4096;
std::array<std::atomic<char*>, kAtomicFileSignalSlots> atomic_file_pending_files{};
std::array<std::atomic<char*>, kAtomicFileSignalSlots> atomic_file_pending_folders{};

// Returns the slot, or kAtomicFileSignalSlots if all are taken (the file then is only removed by
// the destructors, not by a signal).
std::size_t atomic_file_hold_for_signals(std::array<std::atomic<char*>, kAtomicFileSignalSlots>& table,
                                         const std::filesystem::path& path) {
  char* copy = ::strdup(path.c_str());
  if (copy == nullptr) return kAtomicFileSignalSlots;
  for (std::size_t i = 0; i < table.size(); ++i) {
    char* expected = nullptr;
    if (table[i].compare_exchange_strong(expected, copy)) return i;
  }
  std::free(copy);
  return kAtomicFileSignalSlots;
}

// Frees the slot and marks it released, so that it is never freed twice.
void atomic_file_release_for_signals(std::array<std::atomic<char*>, kAtomicFileSignalSlots>& table, std::size_t& slot) {
  if (slot < table.size()) std::free(table[slot].exchange(nullptr));
  slot = kAtomicFileSignalSlots;
}

extern "C" void atomic_file_on_signal(int signal_number) {
  for (auto& slot : atomic_file_pending_files) {
    if (const char* path = slot.load()) ::unlink(path);
  }
  for (std::size_t i = atomic_file_pending_folders.size(); i-- > 0;) {
    if (const char* path = atomic_file_pending_folders[i].load()) ::rmdir(path);
  }
  ::_exit(128 + signal_number);
}

// ---- Naming and checking targets -------------------------------------------------------------

// Built by appending: GCC 12 warns falsely (-Wrestrict, bug 105329) on "..." + std::string&&.
std::string atomic_file_quoted(const std::filesystem::path& path) {
  std::string quoted(1, '\'');
  quoted += path.string();
  quoted += '\'';
  return quoted;
}

const char* atomic_file_kind(mode_t mode) {
  if (S_ISDIR(mode)) return "a directory";
  if (S_ISCHR(mode)) return "a character device";
  if (S_ISBLK(mode)) return "a block device";
  if (S_ISFIFO(mode)) return "a FIFO";
  if (S_ISSOCK(mode)) return "a socket";
  return "not a regular file";
}

// The file an output named `path` replaces: symbolic links followed (relative ones from the
// link's folder), the folder made absolute and canonical, so that two spellings of one file
// compare equal. `status` receives the target's stat when it exists.
std::filesystem::path atomic_file_resolve_target(const std::filesystem::path& path, std::optional<struct stat>& status) {
  if (path.empty() || !path.has_filename() || path.filename() == "." || path.filename() == "..")
    throw IoError("cannot write " + atomic_file_quoted(path) + ": it names a folder, not a file");
  std::filesystem::path current = path;
  for (int hops = 0;; ++hops) {
    struct stat link_status {};
    if (::lstat(current.c_str(), &link_status) != 0) {
      if (errno != ENOENT)
        throw IoError("cannot write " + atomic_file_quoted(path) + ": " + std::strerror(errno));
      status.reset();
      break;
    }
    if (!S_ISLNK(link_status.st_mode)) {
      status = link_status;
      break;
    }
    if (hops == 40) throw IoError("cannot write " + atomic_file_quoted(path) + ": too many levels of symbolic links");
    std::error_code ec;
    const std::filesystem::path link = std::filesystem::read_symlink(current, ec);
    if (ec) throw IoError("cannot write " + atomic_file_quoted(path) + ": " + ec.message());
    current = link.is_absolute() ? link : current.parent_path() / link;
  }
  if (status && !S_ISREG(status->st_mode)) {
    throw IoError("cannot write " + atomic_file_quoted(path) + ": it is " + atomic_file_kind(status->st_mode) +
                  "; volspline replaces only regular files");
  }
  std::error_code ec;
  const std::filesystem::path folder = current.parent_path().empty() ? std::filesystem::path(".") : current.parent_path();
  std::filesystem::path canonical_folder = std::filesystem::weakly_canonical(std::filesystem::absolute(folder), ec);
  if (ec) canonical_folder = std::filesystem::absolute(folder);
  return canonical_folder / current.filename();
}

// ---- Files open or pending in this process, to refuse two outputs naming one file ------------

struct AtomicFileClaim {
  const void* owner;
  std::filesystem::path target;
  std::filesystem::path as_given;
  std::optional<std::pair<dev_t, ino_t>> inode;
};
std::mutex atomic_file_claims_mutex;
std::vector<AtomicFileClaim> atomic_file_claims;

void atomic_file_claim(const void* owner, const std::filesystem::path& target, const std::filesystem::path& as_given,
                       const std::optional<struct stat>& status) {
  std::optional<std::pair<dev_t, ino_t>> inode;
  if (status) inode = std::pair(status->st_dev, status->st_ino);
  const std::lock_guard lock(atomic_file_claims_mutex);
  for (const auto& claim : atomic_file_claims) {
    if (claim.target == target || (inode && claim.inode == inode)) {
      throw InvalidInput("the same file is given for two outputs (" + atomic_file_quoted(claim.as_given) + " and " +
                         atomic_file_quoted(as_given) + "): give each output its own file");
    }
  }
  atomic_file_claims.push_back({owner, target, as_given, inode});
}

void atomic_file_unclaim(const void* owner) {
  const std::lock_guard lock(atomic_file_claims_mutex);
  std::erase_if(atomic_file_claims, [&](const AtomicFileClaim& claim) { return claim.owner == owner; });
}

void atomic_file_transfer_claim(const void* from, const void* to) {
  const std::lock_guard lock(atomic_file_claims_mutex);
  for (auto& claim : atomic_file_claims)
    if (claim.owner == from) claim.owner = to;
}

// A name ".NAME.tmp-XXXXXX" beside the target, created with O_EXCL by mkostemp: unique on the
// file system, whatever the process id (which is not unique across PID namespaces).
std::filesystem::path atomic_file_template(const std::filesystem::path& target, const char* kind) {
  std::string name = target.filename().string();
  if (name.size() > 200) name.resize(200);  // the suffix must fit in NAME_MAX
  return target.parent_path() / ("." + name + kind + "XXXXXX");
}

mode_t atomic_file_default_mode() {
  static const mode_t mode = [] {
    const mode_t mask = ::umask(022);
    ::umask(mask);
    return static_cast<mode_t>(0666 & ~mask);
  }();
  return mode;
}

// A hard link to the file `target` is about to replace, so that a transaction can put it back.
std::optional<std::filesystem::path> atomic_file_backup(const std::filesystem::path& target, std::size_t& slot) {
  static thread_local std::mt19937_64 random{std::random_device{}()};
  for (int attempt = 0; attempt < 100; ++attempt) {
    std::string name = target.filename().string();
    if (name.size() > 200) name.resize(200);
    const std::filesystem::path backup =
        target.parent_path() / ("." + name + ".bak-" + std::to_string(random() % 1000000000000ULL));
    if (::link(target.c_str(), backup.c_str()) == 0) {
      slot = atomic_file_hold_for_signals(atomic_file_pending_files, backup);
      return backup;
    }
    if (errno != EEXIST) break;  // no hard links here (or no permission): the rename goes ahead without one
  }
  slot = kAtomicFileSignalSlots;
  return std::nullopt;
}

}  // namespace

// Buffered writes to a file descriptor that remember why the first one failed. Outside the
// anonymous namespace because AtomicFile::Impl holds one (-Wsubobject-linkage).
class AtomicFileBuffer : public std::streambuf {
 public:
  explicit AtomicFileBuffer(int fd) : fd_(fd) { setp(buffer_.data(), buffer_.data() + buffer_.size()); }
  int error() const { return error_; }
  bool drain() {
    const char* p = pbase();
    while (p < pptr() && error_ == 0) {
      const ssize_t n = ::write(fd_, p, static_cast<std::size_t>(pptr() - p));
      if (n < 0) {
        if (errno == EINTR) continue;
        error_ = errno;
      } else {
        p += n;
      }
    }
    setp(buffer_.data(), buffer_.data() + buffer_.size());
    return error_ == 0;
  }

 protected:
  int_type overflow(int_type c) override {
    if (!drain()) return traits_type::eof();
    if (!traits_type::eq_int_type(c, traits_type::eof())) {
      *pptr() = traits_type::to_char_type(c);
      pbump(1);
    }
    return traits_type::not_eof(c);
  }
  int sync() override { return drain() ? 0 : -1; }

 private:
  int fd_;
  int error_ = 0;
  std::array<char, 1 << 16> buffer_{};
};

std::string write_failure_reason(int errno_value) {
  if (errno_value == ENOSPC) return "the disk is full (no space left on the device)";
  if (errno_value == EDQUOT) return "the disk quota is exceeded";
  if (errno_value == EFBIG) return "the file is too large for the file system";
  return std::strerror(errno_value);
}

// ---- OutputTransaction -----------------------------------------------------------------------

struct OutputTransaction::Entry {
  std::filesystem::path target, temporary;  // temporary is empty once renamed
  std::size_t temporary_slot = kAtomicFileSignalSlots;
  std::optional<std::filesystem::path> backup;
  std::size_t backup_slot = kAtomicFileSignalSlots;
  bool existed = false;
};

struct OutputTransaction::State {
  std::vector<Entry> pending, published;
  std::vector<std::filesystem::path> folders;
  std::vector<std::size_t> folder_slots;
  bool publish_each = false, finished = false;

  void publish(Entry& entry) {
    entry.existed = std::filesystem::exists(std::filesystem::symlink_status(entry.target));
    if (entry.existed) entry.backup = atomic_file_backup(entry.target, entry.backup_slot);
    std::error_code ec;
    std::filesystem::rename(entry.temporary, entry.target, ec);
    if (ec) {
      drop_backup(entry);
      remove_temporary(entry);
      throw IoError("cannot write " + atomic_file_quoted(entry.target) + ": " + ec.message());
    }
    atomic_file_release_for_signals(atomic_file_pending_files, entry.temporary_slot);
    entry.temporary.clear();
  }
  static void drop_backup(Entry& entry) {
    if (entry.backup) ::unlink(entry.backup->c_str());
    atomic_file_release_for_signals(atomic_file_pending_files, entry.backup_slot);
    entry.backup.reset();
  }
  static void remove_temporary(Entry& entry) {
    if (!entry.temporary.empty()) ::unlink(entry.temporary.c_str());
    atomic_file_release_for_signals(atomic_file_pending_files, entry.temporary_slot);
    entry.temporary.clear();
  }
  // Undoes published files, last first: the old file back from its link, or no file.
  void restore_published() {
    for (auto it = published.rbegin(); it != published.rend(); ++it) {
      if (it->backup) {
        std::error_code ec;
        std::filesystem::rename(*it->backup, it->target, ec);
        atomic_file_release_for_signals(atomic_file_pending_files, it->backup_slot);
        it->backup.reset();
      } else if (!it->existed) {
        ::unlink(it->target.c_str());
      }
    }
    published.clear();
  }
  void discard() {
    for (auto& entry : pending) remove_temporary(entry);
    pending.clear();
    restore_published();
    for (std::size_t i = folders.size(); i-- > 0;) {
      ::rmdir(folders[i].c_str());
      atomic_file_release_for_signals(atomic_file_pending_folders, folder_slots[i]);
    }
    folders.clear();
    folder_slots.clear();
  }
};

namespace {
std::atomic<OutputTransaction*> atomic_file_open_transaction{nullptr};
}

OutputTransaction::OutputTransaction() : state_(std::make_unique<State>()) {
  OutputTransaction* expected = nullptr;
  if (!atomic_file_open_transaction.compare_exchange_strong(expected, this))
    throw std::logic_error("an OutputTransaction is already open");
}

OutputTransaction::~OutputTransaction() {
  if (!state_->finished) state_->discard();
  atomic_file_unclaim(this);
  atomic_file_open_transaction.store(nullptr);
}

OutputTransaction* OutputTransaction::current() { return atomic_file_open_transaction.load(); }

void OutputTransaction::publish_each_file() { state_->publish_each = true; }

void OutputTransaction::adopt(Entry entry, const void* claim_owner) {
  if (state_->publish_each) {
    atomic_file_unclaim(claim_owner);
    state_->publish(entry);
    state_->published.push_back(std::move(entry));
  } else {
    atomic_file_transfer_claim(claim_owner, this);
    state_->pending.push_back(std::move(entry));
  }
}

void OutputTransaction::remember_folder(const std::filesystem::path& folder) {
  state_->folders.push_back(folder);
  state_->folder_slots.push_back(atomic_file_hold_for_signals(atomic_file_pending_folders, folder));
}

void OutputTransaction::commit() {
  State& s = *state_;
  while (!s.pending.empty()) {
    Entry entry = std::move(s.pending.front());
    s.pending.erase(s.pending.begin());
    try {
      s.publish(entry);
    } catch (const IoError& e) {
      s.pending.push_back(std::move(entry));
      s.discard();
      s.finished = true;
      throw IoError(std::string(e.what()) + " (no output was written: the files it replaced were restored)");
    }
    s.published.push_back(std::move(entry));
  }
  for (auto& entry : s.published) State::drop_backup(entry);
  s.published.clear();
  for (std::size_t& slot : s.folder_slots) atomic_file_release_for_signals(atomic_file_pending_folders, slot);
  s.folders.clear();
  s.folder_slots.clear();
  s.finished = true;
  atomic_file_unclaim(this);
}

void create_output_directories(const std::filesystem::path& folder) {
  std::vector<std::filesystem::path> missing;
  std::error_code ec;
  for (std::filesystem::path p = std::filesystem::absolute(folder, ec); !p.empty() && !std::filesystem::exists(p, ec);
       p = p.parent_path()) {
    missing.push_back(p);
    if (p == p.parent_path()) break;
  }
  std::filesystem::create_directories(folder, ec);
  if (ec || !std::filesystem::is_directory(folder))
    throw IoError("cannot create the output folder " + atomic_file_quoted(folder) + ": " +
                  (ec ? ec.message() : std::string("it exists and is not a folder")));
  if (OutputTransaction* transaction = OutputTransaction::current()) {
    // Outermost first, so that the transaction removes them innermost first.
    for (auto it = missing.rbegin(); it != missing.rend(); ++it) transaction->remember_folder(*it);
  }
}

// ---- AtomicFile --------------------------------------------------------------------------------

struct AtomicFile::Impl {
  std::filesystem::path path, target, temporary;
  std::size_t slot = kAtomicFileSignalSlots;
  int fd = -1;
  AtomicFileBuffer buffer;
  std::ostream out;
  bool committed = false;

  Impl(std::filesystem::path given, std::filesystem::path resolved, std::filesystem::path temp, std::size_t signal_slot, int descriptor)
      : path(std::move(given)), target(std::move(resolved)), temporary(std::move(temp)), slot(signal_slot), fd(descriptor),
        buffer(descriptor), out(&buffer) {}
};

AtomicFile::AtomicFile(std::filesystem::path path, bool /*binary: POSIX files make no difference*/) {
  std::optional<struct stat> status;
  const std::filesystem::path target = atomic_file_resolve_target(path, status);
  std::string name = atomic_file_template(target, ".tmp-").string();
  const int fd = ::mkostemp(name.data(), O_CLOEXEC);
  if (fd < 0) throw IoError("cannot write " + atomic_file_quoted(path) + ": " + write_failure_reason(errno));
  const std::size_t slot = atomic_file_hold_for_signals(atomic_file_pending_files, name);
  ::fchmod(fd, status ? (status->st_mode & 07777) : atomic_file_default_mode());
  impl_ = std::make_unique<Impl>(std::move(path), target, name, slot, fd);
  try {
    atomic_file_claim(impl_.get(), target, impl_->path, status);
  } catch (...) {
    ::close(impl_->fd);
    ::unlink(impl_->temporary.c_str());
    atomic_file_release_for_signals(atomic_file_pending_files, impl_->slot);
    throw;
  }
}

AtomicFile::~AtomicFile() {
  if (!impl_->committed) {
    if (impl_->fd >= 0) ::close(impl_->fd);
    ::unlink(impl_->temporary.c_str());
    atomic_file_release_for_signals(atomic_file_pending_files, impl_->slot);
    atomic_file_unclaim(impl_.get());
  }
}

std::ostream& AtomicFile::stream() { return impl_->out; }

void AtomicFile::commit() {
  Impl& f = *impl_;
  f.out.flush();
  const bool drained = f.buffer.drain();
  const int write_error = f.buffer.error();
  const int closed = ::close(f.fd);
  const int close_error = errno;
  f.fd = -1;
  if (!drained || !f.out || write_error != 0)
    throw IoError("cannot write " + atomic_file_quoted(f.path) + ": " + write_failure_reason(write_error != 0 ? write_error : EIO));
  if (closed != 0) throw IoError("cannot write " + atomic_file_quoted(f.path) + ": " + write_failure_reason(close_error));
  if (OutputTransaction* transaction = OutputTransaction::current()) {
    // The transaction owns the temporary file (and its signal slot) from here on.
    OutputTransaction::Entry entry{f.target, f.temporary, f.slot, std::nullopt, kAtomicFileSignalSlots, false};
    f.slot = kAtomicFileSignalSlots;
    f.committed = true;
    transaction->adopt(std::move(entry), impl_.get());
    return;
  }
  std::error_code ec;
  std::filesystem::rename(f.temporary, f.target, ec);
  if (ec) throw IoError("cannot write " + atomic_file_quoted(f.path) + ": " + ec.message());
  atomic_file_release_for_signals(atomic_file_pending_files, f.slot);
  atomic_file_unclaim(impl_.get());
  f.committed = true;
}

void remove_temporary_files_on_signals() {
  struct sigaction action {};
  action.sa_handler = atomic_file_on_signal;
  sigemptyset(&action.sa_mask);
  sigaddset(&action.sa_mask, SIGINT);
  sigaddset(&action.sa_mask, SIGTERM);
  ::sigaction(SIGINT, &action, nullptr);
  ::sigaction(SIGTERM, &action, nullptr);
}

void write_file_atomically(const std::filesystem::path& path, std::string_view bytes) {
  AtomicFile file(path);
  file.stream().write(bytes.data(), static_cast<std::streamsize>(bytes.size()));
  file.commit();
}

std::string read_file(const std::filesystem::path& path) { return read_file(path, input_file_limit()); }

std::string read_file(const std::filesystem::path& path, std::uint64_t max_bytes) {
  std::error_code ec;
  if (std::filesystem::is_directory(path, ec)) {
    throw IoError("cannot read '" + path.string() + "': it is a directory");
  }
  const int fd = ::open(path.c_str(), O_RDONLY | O_CLOEXEC);
  if (fd < 0) throw IoError("cannot read '" + path.string() + "': " + std::strerror(errno));
  struct stat status {};
  ::fstat(fd, &status);
  const auto too_large = [&](const std::string& what) {
    ::close(fd);
    return IoError("cannot read '" + path.string() + "': " + what + " the input limit of " + format_byte_count(max_bytes) + " (" +
                   memory_limit_hint() + ")");
  };
  if (S_ISREG(status.st_mode) && static_cast<std::uint64_t>(status.st_size) > max_bytes)
    throw too_large("it is " + format_byte_count(static_cast<std::uint64_t>(status.st_size)) + ", more than");
  // Pipes and devices have no size: read up to the limit and refuse what goes beyond it.
  std::string contents;
  if (S_ISREG(status.st_mode)) contents.reserve(static_cast<std::size_t>(status.st_size));
  std::array<char, 1 << 16> chunk{};
  for (;;) {
    const ssize_t n = ::read(fd, chunk.data(), chunk.size());
    if (n < 0) {
      if (errno == EINTR) continue;
      const int error = errno;
      ::close(fd);
      throw IoError("cannot read '" + path.string() + "': " + std::strerror(error));
    }
    if (n == 0) break;
    if (contents.size() + static_cast<std::size_t>(n) > max_bytes)
      throw too_large(S_ISREG(status.st_mode) ? "it grew beyond" : "it is not a regular file and gave more than");
    contents.append(chunk.data(), static_cast<std::size_t>(n));
  }
  ::close(fd);
  return contents;
}

}  // namespace volspline
