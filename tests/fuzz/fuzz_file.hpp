#pragma once
// The readers of POINTS take a path (and choose the format by its extension), so a fuzz input
// becomes a file: one per process in /dev/shm (memory, not disk) when there is one, rewritten for
// every input.
#include <unistd.h>

#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <string>
#include <vector>

namespace bezinv::fuzz {

// A path in a scratch directory, unique to this process, ending in `name`.
inline std::string scratch_path(const std::string& name) {
  std::error_code error;
  const std::filesystem::path directory =
      std::filesystem::is_directory("/dev/shm", error) ? std::filesystem::path("/dev/shm")
                                                       : std::filesystem::temp_directory_path();
  return (directory / ("bezinv-fuzz-" + std::to_string(::getpid()) + "-" + name)).string();
}

// Writes `size` bytes to `path`; a failure to write is the harness's, not the reader's: abort.
inline void write_bytes(const std::string& path, const std::uint8_t* data, std::size_t size) {
  std::FILE* file = std::fopen(path.c_str(), "wb");
  if (file == nullptr) std::abort();
  if (size > 0 && std::fwrite(data, 1, size, file) != size) std::abort();
  if (std::fclose(file) != 0) std::abort();
}

// Removes the scratch files at exit.
struct ScratchFiles {
  std::vector<std::string> paths;
  ~ScratchFiles() {
    for (const std::string& path : paths) std::remove(path.c_str());
  }
};

}  // namespace bezinv::fuzz
