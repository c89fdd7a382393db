#pragma once
// Reading an input file in one piece, for the CURVES.json reader (engine internal).
#include <cerrno>
#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <string>
#include <system_error>

#include "bezinv/io.hpp"

namespace bezinv::detail {

// The whole file in one string; InputError "<path>: cannot read: <reason>" if it cannot be read,
// "<path>: ... more than <max_bytes> bytes ..." if it is larger than `max_bytes` (`format` names
// the format whose limit that is). A regular file is measured before anything is read; a pipe or
// a device (/dev/zero) is stopped once it has delivered more than max_bytes.
inline std::string read_whole_file(const std::string& path, std::uint64_t max_bytes, const char* format) {
  const std::string limit = std::to_string(max_bytes) + " bytes, the limit for " + format;
  std::FILE* file = std::fopen(path.c_str(), "rb");
  if (file == nullptr) throw InputError(path + ": cannot read: " + std::strerror(errno));
  std::string text;
  // One allocation for a regular file; pipes and the like grow as they go. The size comes from
  // file_size, not fseek/ftell: on ext4 a directory seeks to LLONG_MAX, and reserving that throws
  // std::length_error instead of the InputError below.
  std::error_code no_size;
  if (std::filesystem::is_regular_file(path, no_size)) {
    const std::uintmax_t size = std::filesystem::file_size(path, no_size);
    if (!no_size && size > max_bytes) {
      std::fclose(file);
      throw InputError(path + ": " + std::to_string(size) + " bytes, more than " + limit);
    }
    if (!no_size) text.reserve(static_cast<std::size_t>(size));
  }
  char chunk[1 << 16];
  std::size_t got = 0;
  while ((got = std::fread(chunk, 1, sizeof chunk, file)) > 0) {
    text.append(chunk, got);
    // A file that grew after it was measured, or one with no size.
    if (text.size() > max_bytes) {
      std::fclose(file);
      throw InputError(path + ": more than " + limit);
    }
  }
  // fread on a directory opens fine and fails here with EISDIR.
  const bool failed = std::ferror(file) != 0;
  const int error = errno;
  std::fclose(file);
  if (failed) throw InputError(path + ": cannot read: " + std::strerror(error));
  return text;
}

}  // namespace bezinv::detail
