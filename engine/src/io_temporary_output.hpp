#pragma once
// The temporary file an output is written to before it replaces the target (engine internal).
//
// Written beside the target and renamed over it at the end: rename within one directory is atomic
// on POSIX, so a reader (or a failed run) never sees half a file.
#include <atomic>
#include <cerrno>
#include <cstdio>
#include <cstring>
#include <string>
#include <string_view>

#include <unistd.h>  // getpid: a temporary name no other process will pick

#include "bezinv/io.hpp"

namespace bezinv::detail {

[[noreturn]] inline void fail_to_write(const std::string& path, int error) {
  throw InputError(path + ": cannot write: " + std::strerror(error));
}

// Removed again unless commit() renamed it over the target.
class TemporaryOutput {
 public:
  explicit TemporaryOutput(const std::string& target) : target_(target) {
    static std::atomic<unsigned> counter{0};
    // "x": fail if the name exists, so two writers (threads or processes) never share one file.
    for (int attempt = 0; attempt < 100 && file_ == nullptr; ++attempt) {
      name_ = target + ".tmp." + std::to_string(::getpid()) + "." + std::to_string(counter++);
      file_ = std::fopen(name_.c_str(), "wbx");
      if (file_ == nullptr && errno != EEXIST) break;
    }
    if (file_ == nullptr) fail_to_write(target_, errno);
  }
  TemporaryOutput(const TemporaryOutput&) = delete;
  TemporaryOutput& operator=(const TemporaryOutput&) = delete;
  ~TemporaryOutput() {
    if (file_ != nullptr) std::fclose(file_);
    if (!committed_) std::remove(name_.c_str());
  }

  void write(std::string_view bytes) {
    if (std::fwrite(bytes.data(), 1, bytes.size(), file_) != bytes.size()) fail_to_write(target_, errno);
  }

  // Overwrites bytes already written at `offset` (the .npy header's row count), then carries on
  // at the end.
  void rewrite(long offset, std::string_view bytes) {
    if (std::fseek(file_, offset, SEEK_SET) != 0) fail_to_write(target_, errno);
    write(bytes);
    if (std::fseek(file_, 0, SEEK_END) != 0) fail_to_write(target_, errno);
  }

  void commit() {
    std::FILE* file = file_;
    file_ = nullptr;
    // fclose flushes: a full disk shows up here, not earlier.
    if (std::fclose(file) != 0) fail_to_write(target_, errno);
    if (std::rename(name_.c_str(), target_.c_str()) != 0) fail_to_write(target_, errno);
    committed_ = true;
  }

 private:
  std::string target_;
  std::string name_;
  std::FILE* file_ = nullptr;
  bool committed_ = false;
};

}  // namespace bezinv::detail
