#pragma once
// A fresh directory for tests that write files and read them back (the I/O tests and the
// end-to-end tests of the `bezinv` command).
#include <filesystem>
#include <fstream>
#include <ios>
#include <random>
#include <sstream>
#include <string>
#include <string_view>
#include <system_error>

namespace bezinv::test_support {

// A fresh directory under the system temp directory, removed with everything in it afterwards.
// The prefix names the suite that made it, for whoever finds one left behind by a crash.
class ScratchDirectory {
 public:
  explicit ScratchDirectory(const std::string& prefix) {
    std::random_device entropy;
    root_ = std::filesystem::temp_directory_path() / (prefix + std::to_string(entropy()) + std::to_string(entropy()));
    std::filesystem::create_directories(root_);
  }
  ~ScratchDirectory() {
    std::error_code ignored;
    std::filesystem::remove_all(root_, ignored);
  }
  ScratchDirectory(const ScratchDirectory&) = delete;
  ScratchDirectory& operator=(const ScratchDirectory&) = delete;

  std::string path(const std::string& name) const { return (root_ / name).string(); }
  const std::filesystem::path& root() const { return root_; }

  std::string write(const std::string& name, std::string_view contents) const {
    std::ofstream out(root_ / name, std::ios::binary);
    out.write(contents.data(), static_cast<std::streamsize>(contents.size()));
    return path(name);
  }

 private:
  std::filesystem::path root_;
};

// The whole file, byte for byte ("" if it cannot be opened).
inline std::string read_file(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  std::ostringstream text;
  text << in.rdbuf();
  return text.str();
}

}  // namespace bezinv::test_support
