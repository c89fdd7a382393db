// std::span<const PointResult> -> OUT.csv (format in bezinv/io.hpp).
//
// Written to a temporary file beside the target and renamed over it at the end: rename within one
// directory is atomic on POSIX, so a reader (or a failed run) never sees half a file.
#include <atomic>
#include <cerrno>
#include <charconv>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <string>
#include <string_view>

#include <unistd.h>  // getpid: a temporary name no other process will pick

#include "bezinv/io.hpp"

namespace bezinv {
namespace {

constexpr std::string_view kHeader = "t,status,residual,t2,sigma_min,sigma_next,path,reason\n";

// Output is handed to the file in blocks of about this size.
constexpr std::size_t kBlockBytes = std::size_t{1} << 20;

[[noreturn]] void fail_to_write(const std::string& path, int error) {
  throw InputError(path + ": cannot write: " + std::strerror(error));
}

// The temporary file: removed again unless commit() renamed it over the target.
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

// %.17g: enough digits that strtod gives back the same double. NaN (absent) is written "nan"
// whatever its sign bit, so readers need to know one spelling.
void append_number(std::string& out, double value) {
  if (std::isnan(value)) {
    out += "nan";
    return;
  }
  char digits[32];
  const auto [end, error] = std::to_chars(digits, digits + sizeof digits, value, std::chars_format::general, 17);
  (void)error;  // 32 bytes hold any %.17g double ("-1.2345678901234567e-308" is 24)
  out.append(digits, end);
}

// Reasons are static text without commas; should one ever gain a comma, quote or line break,
// RFC 4180 quoting keeps the row's column count right.
void append_text_field(std::string& out, const char* text) {
  if (text == nullptr) return;
  const std::string_view field(text);
  if (field.find_first_of(",\"\r\n") == std::string_view::npos) {
    out += field;
    return;
  }
  out += '"';
  for (char c : field) {
    if (c == '"') out += '"';
    out += c;
  }
  out += '"';
}

}  // namespace

void write_results_csv(const std::string& path, std::span<const PointResult> results) {
  TemporaryOutput output(path);
  std::string block;
  block.reserve(kBlockBytes + 1024);
  block += kHeader;
  for (const PointResult& result : results) {
    append_number(block, result.t);
    block += ',';
    block += to_string(result.status);
    block += ',';
    append_number(block, result.residual);
    block += ',';
    append_number(block, result.t2);
    block += ',';
    append_number(block, result.sigma_min);
    block += ',';
    append_number(block, result.sigma_next);
    block += ',';
    block += to_string(result.path);
    block += ',';
    append_text_field(block, result.reason);
    block += '\n';
    if (block.size() >= kBlockBytes) {
      output.write(block);
      block.clear();
    }
  }
  output.write(block);
  output.commit();
}

}  // namespace bezinv
