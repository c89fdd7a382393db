// OutputTarget (io/output_target.hpp) and the signal handler that removes its temporary file.
#include "io/output_target.hpp"

#include <atomic>
#include <cerrno>
#include <csignal>
#include <cstring>
#include <filesystem>
#include <system_error>
#include <vector>

#include <fcntl.h>
#include <limits.h>  // PATH_MAX
#include <signal.h>
#include <sys/stat.h>
#include <unistd.h>

#include "bezinv/io.hpp"

namespace bezinv {
namespace detail {
namespace {

// ---- Temporary files for the signal handler ------------------------------------------------
// The handler may only call async-signal-safe functions: it reads paths copied beforehand into
// static buffers and unlink()s them. A slot is armed only once its path is complete.

constexpr int kTerminatingSignals[] = {SIGINT, SIGTERM, SIGHUP};
constexpr std::size_t kSlots = 16;  // temporaries open at once in one process; the CLI has one

struct Slot {
  std::atomic<bool> taken{false};
  std::atomic<bool> armed{false};
  char path[PATH_MAX];  // open() refuses longer paths, so every temporary fits
};
Slot g_slots[kSlots];

// While > 0 a temporary is being created or published: a signal then waits (g_pending_signal)
// until that is done, so it never leaves a temporary unregistered or OUT half copied.
std::atomic<int> g_deferring{0};
std::atomic<int> g_pending_signal{0};
static_assert(std::atomic<int>::is_always_lock_free && std::atomic<bool>::is_always_lock_free,
              "the signal handler needs lock-free atomics");

int register_temporary(const std::string& path) {
  if (path.size() >= PATH_MAX) return -1;
  for (std::size_t i = 0; i < kSlots; ++i) {
    bool expected = false;
    if (!g_slots[i].taken.compare_exchange_strong(expected, true)) continue;
    std::memcpy(g_slots[i].path, path.c_str(), path.size() + 1);
    g_slots[i].armed.store(true);
    return static_cast<int>(i);
  }
  return -1;  // more writers than slots: this temporary is only removed by its destructor
}

void unregister_temporary(int& slot) {
  if (slot < 0) return;
  g_slots[slot].armed.store(false);
  g_slots[slot].taken.store(false);
  slot = -1;
}

// Async-signal-safe: unlink, sigaction, raise. With the default disposition back, the raised
// signal ends the process as if bezinv had not handled it (the usual exit status for the shell).
void remove_temporaries_and_die(int signal_number) {
  for (Slot& slot : g_slots)
    if (slot.armed.load()) ::unlink(slot.path);
  struct sigaction default_action {};
  default_action.sa_handler = SIG_DFL;
  sigemptyset(&default_action.sa_mask);
  ::sigaction(signal_number, &default_action, nullptr);
  ::raise(signal_number);
}

void on_terminating_signal(int signal_number) {
  const int saved_errno = errno;
  if (g_deferring.load() > 0) {
    g_pending_signal.store(signal_number);
    // Either this check sees the section still open, or the section's end sees the pending
    // signal (both sides store, then load; sequentially consistent), so it is never lost.
    if (g_deferring.load() > 0 || g_pending_signal.exchange(0) == 0) {
      errno = saved_errno;
      return;
    }
  }
  remove_temporaries_and_die(signal_number);
  errno = saved_errno;
}

class DeferSignals {
 public:
  DeferSignals() { g_deferring.fetch_add(1); }
  ~DeferSignals() {
    if (g_deferring.fetch_sub(1) != 1) return;
    if (const int signal_number = g_pending_signal.exchange(0); signal_number != 0)
      remove_temporaries_and_die(signal_number);
  }
  DeferSignals(const DeferSignals&) = delete;
  DeferSignals& operator=(const DeferSignals&) = delete;
};

// ---- Paths ---------------------------------------------------------------------------------

[[noreturn]] void fail(const std::string& where, const std::string& what) { throw InputError(where + ": " + what); }

// The file a dangling symbolic link names (each hop relative to its link's directory), to be
// created there as a shell's `>` would.
std::string dangling_link_target(const std::string& path) {
  std::filesystem::path current = path;
  for (int hop = 0; hop < 40; ++hop) {  // Linux's own limit on links followed
    struct stat own {};
    if (::lstat(current.c_str(), &own) != 0 || !S_ISLNK(own.st_mode)) return current.string();
    std::error_code error;
    const std::filesystem::path next = std::filesystem::read_symlink(current, error);
    if (error) return current.string();
    current = next.is_absolute() ? next : current.parent_path() / next;
  }
  fail_to_write(path, ELOOP);
}

bool write_all(int fd, const char* bytes, std::size_t size, off_t offset) {
  while (size > 0) {
    const ssize_t wrote = ::pwrite(fd, bytes, size, offset);
    if (wrote < 0 && errno == EINTR) continue;
    if (wrote <= 0) return false;
    bytes += wrote;
    size -= static_cast<std::size_t>(wrote);
    offset += wrote;
  }
  return true;
}

}  // namespace

void fail_to_write(const std::string& path, int error) { fail(path, std::string("cannot write: ") + std::strerror(error)); }

OutputTarget::OutputTarget(const std::string& path, bool needs_seek) : path_(path), target_(path) {
  try {
    open(needs_seek);
  } catch (...) {
    discard();  // the destructor does not run for a constructor that throws
    throw;
  }
}

void OutputTarget::open(bool needs_seek) {
  const std::string path = path_;  // path_ gains the link target for messages below
  struct stat followed {};
  if (::stat(path.c_str(), &followed) != 0) {
    if (errno != ENOENT) fail_to_write(path_, errno);
    // Nothing there yet, or a dangling symbolic link (lstat succeeds where stat did not).
    target_ = dangling_link_target(path);
    if (target_ != path_) path_ += " (symbolic link to " + target_ + ")";
    kind_ = Kind::replace;
    open_temporary(false);
    return;
  }

  if (S_ISREG(followed.st_mode)) {
    struct stat own {};
    if (::lstat(path.c_str(), &own) == 0 && S_ISLNK(own.st_mode)) {
      std::error_code error;
      target_ = std::filesystem::canonical(path, error).string();
      if (error) fail_to_write(path_, error.value());
      path_ += " (symbolic link to " + target_ + ")";
    }
    if (followed.st_nlink > 1) {
      kind_ = Kind::in_place;
      // Opened now, not at commit: an OUT that cannot be written fails before any work is done.
      target_fd_ = ::open(target_.c_str(), O_WRONLY | O_CLOEXEC);
      if (target_fd_ < 0) fail_to_write(path_, errno);
    }
    open_temporary(true);
    return;
  }

  if (S_ISCHR(followed.st_mode) || S_ISFIFO(followed.st_mode)) {
    // Seeking is known to fail on a FIFO; check before opening it, which waits for a reader.
    if (needs_seek && S_ISFIFO(followed.st_mode))
      fail(path_, "cannot write a .npy to a FIFO (its header is completed at the end): write it to a file");
    kind_ = Kind::through;
    const int fd = ::open(path.c_str(), O_WRONLY | O_NOCTTY | O_CLOEXEC);
    if (fd < 0) fail_to_write(path_, errno);
    struct stat opened {};
    if (::fstat(fd, &opened) != 0 || !(S_ISCHR(opened.st_mode) || S_ISFIFO(opened.st_mode))) {
      ::close(fd);
      fail(path_, "cannot write: it was replaced while being opened");
    }
    if (needs_seek && ::lseek(fd, 0, SEEK_CUR) < 0) {
      ::close(fd);
      fail(path_, "cannot write a .npy to a device that cannot seek (its header is completed at the end): write it to a file");
    }
    file_ = ::fdopen(fd, "wb");
    if (file_ == nullptr) {
      const int error = errno;
      ::close(fd);
      fail_to_write(path_, error);
    }
    return;
  }

  if (S_ISDIR(followed.st_mode)) fail(path_, "cannot write: is a directory");
  fail(path_, "cannot write: not a regular file, FIFO or character device");
}

void OutputTarget::open_temporary(bool existing) {
  static std::atomic<unsigned> counter{0};
  // The file and its slot for the signal handler appear together.
  const DeferSignals defer;
  // O_EXCL: two writers (threads or processes) never share one file. Over an existing OUT the
  // temporary is private until commit gives it OUT's mode. O_RDWR: an in-place commit reads it back.
  int fd = -1;
  std::string name;
  for (int attempt = 0; attempt < 100 && fd < 0; ++attempt) {
    name = target_ + ".tmp." + std::to_string(::getpid()) + "." + std::to_string(counter++);
    fd = ::open(name.c_str(), O_RDWR | O_CREAT | O_EXCL | O_CLOEXEC, existing ? 0600 : 0666);
    if (fd < 0 && errno != EEXIST) break;
  }
  if (fd < 0) fail_to_write(path_, errno);
  temporary_ = name;
  signal_slot_ = register_temporary(temporary_);
  file_ = ::fdopen(fd, "wb");
  if (file_ == nullptr) {
    const int error = errno;
    ::close(fd);
    fail_to_write(path_, error);
  }
}

OutputTarget::~OutputTarget() { discard(); }

void OutputTarget::discard() {
  if (file_ != nullptr) std::fclose(file_);
  file_ = nullptr;
  if (target_fd_ >= 0) ::close(target_fd_);
  target_fd_ = -1;
  if (!committed_ && !temporary_.empty()) ::unlink(temporary_.c_str());
  unregister_temporary(signal_slot_);
}

void OutputTarget::write(std::string_view bytes) {
  if (std::fwrite(bytes.data(), 1, bytes.size(), file_) != bytes.size()) fail_to_write(path_, errno);
}

void OutputTarget::rewrite(long offset, std::string_view bytes) {
  if (std::fseek(file_, offset, SEEK_SET) != 0) fail_to_write(path_, errno);
  write(bytes);
  if (std::fseek(file_, 0, SEEK_END) != 0) fail_to_write(path_, errno);
}

void OutputTarget::commit() {
  if (kind_ == Kind::through) {
    std::FILE* file = file_;
    file_ = nullptr;
    if (std::fclose(file) != 0) fail_to_write(path_, errno);
    committed_ = true;
    return;
  }
  // fflush: a full disk shows up here, not earlier.
  if (std::fflush(file_) != 0) fail_to_write(path_, errno);
  if (kind_ == Kind::replace) replace_target();
  else copy_into_target();
}

void OutputTarget::replace_target() {
  const DeferSignals defer;
  const int fd = ::fileno(file_);
  // An existing OUT's mode and owner carry over to the file that replaces it (chown first: it
  // may clear set-id bits that chmod then restores). Only root can give a file to another user;
  // anyone may try to keep the group.
  struct stat old {};
  if (::stat(target_.c_str(), &old) == 0 && S_ISREG(old.st_mode)) {
    if (::geteuid() == 0) {
      if (::fchown(fd, old.st_uid, old.st_gid) != 0)
        fail(path_, std::string("cannot keep the owner of the existing file: ") + std::strerror(errno));
    } else {
      (void)::fchown(fd, static_cast<uid_t>(-1), old.st_gid);
    }
    if (::fchmod(fd, old.st_mode & 07777) != 0)
      fail(path_, std::string("cannot keep the mode of the existing file: ") + std::strerror(errno));
  }
  std::FILE* file = file_;
  file_ = nullptr;
  if (std::fclose(file) != 0) fail_to_write(path_, errno);
  if (std::rename(temporary_.c_str(), target_.c_str()) != 0) fail_to_write(path_, errno);
  committed_ = true;
  unregister_temporary(signal_slot_);
}

void OutputTarget::copy_into_target() {
  // A signal now would leave OUT half copied: it waits until the copy is done.
  const DeferSignals defer;
  const int from = ::fileno(file_);
  const off_t size = ::lseek(from, 0, SEEK_END);
  if (size < 0) fail_to_write(path_, errno);
#ifdef __linux__
  // Reserve the space first, so that a full disk fails here with OUT untouched. Filesystems
  // without fallocate just go on.
  if (size > 0 && ::fallocate(target_fd_, FALLOC_FL_KEEP_SIZE, 0, size) != 0 && errno != EOPNOTSUPP &&
      errno != ENOSYS)
    fail_to_write(path_, errno);
#endif
  std::vector<char> buffer(std::size_t{1} << 20);
  for (off_t offset = 0; offset < size;) {
    const ssize_t got = ::pread(from, buffer.data(), buffer.size(), offset);
    if (got < 0 && errno == EINTR) continue;
    if (got <= 0) fail_to_write(path_, got < 0 ? errno : EIO);
    if (!write_all(target_fd_, buffer.data(), static_cast<std::size_t>(got), offset)) fail_to_write(path_, errno);
    offset += got;
  }
  if (::ftruncate(target_fd_, size) != 0) fail_to_write(path_, errno);
  const int fd = target_fd_;
  target_fd_ = -1;
  if (::close(fd) != 0) fail_to_write(path_, errno);
  std::FILE* file = file_;
  file_ = nullptr;
  std::fclose(file);
  ::unlink(temporary_.c_str());
  committed_ = true;
  unregister_temporary(signal_slot_);
}

}  // namespace detail

void remove_temporary_outputs_on_signals() {
  for (const int signal_number : detail::kTerminatingSignals) {
    struct sigaction old {};
    if (::sigaction(signal_number, nullptr, &old) != 0) continue;
    // Ignored (nohup, a parent's choice): the signal is not meant to end this process.
    if ((old.sa_flags & SA_SIGINFO) == 0 && old.sa_handler == SIG_IGN) continue;
    struct sigaction action {};
    action.sa_handler = detail::on_terminating_signal;
    sigemptyset(&action.sa_mask);
    for (const int other : detail::kTerminatingSignals) sigaddset(&action.sa_mask, other);
    // SA_RESTART: a deferred signal must not turn a write in progress into EINTR.
    action.sa_flags = SA_RESTART;
    ::sigaction(signal_number, &action, nullptr);
  }
}

}  // namespace bezinv
