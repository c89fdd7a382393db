// The .npy container: reading and writing the preamble (format in io/npy.hpp). Only the subset
// numpy's own np.save writes is parsed: a dict of string keys whose values are strings, True/False,
// tuples of integers, or a list (a structured dtype, kept as raw text for the error message).
#include "io/npy.hpp"

#include <algorithm>
#include <cctype>
#include <cerrno>
#include <charconv>
#include <cstring>
#include <string>

#include "bezinv/io.hpp"
#include "quote.hpp"

namespace bezinv::detail {
namespace {

constexpr std::string_view kMagic = "\x93NUMPY";
// np.save aligns the data to 64 bytes; so do we.
constexpr std::size_t kAlignment = 64;
// The longest header dict read: numpy's own default (np.load's max_header_size); a length field
// beyond it is refused before anything is allocated for it.
constexpr std::uint32_t kMaxHeaderBytes = 10000;

// Recursive descent over the header dict; `fail_npy_header` names the file.
class HeaderParser {
 public:
  HeaderParser(std::string_view text, const std::string& path) : text_(text), path_(path) {}

  NpyHeader parse() {
    NpyHeader header;
    bool has_descr = false, has_order = false, has_shape = false;
    expect('{');
    while (true) {
      skip_blanks();
      if (peek() == '}') break;
      const std::string key = string_literal();
      expect(':');
      skip_blanks();
      if (key == "descr") {
        has_descr = true;
        header.descr = peek() == '[' ? raw_bracketed() : quoted(string_literal());
      } else if (key == "fortran_order") {
        has_order = true;
        header.fortran_order = boolean();
      } else if (key == "shape") {
        has_shape = true;
        header.shape = integer_tuple();
      } else {
        fail_npy_header(path_, "unexpected key " + quoted_excerpt(key));
      }
      skip_blanks();
      if (peek() == ',') {
        ++position_;
        continue;
      }
      skip_blanks();
      if (peek() != '}') malformed("',' or '}'");
    }
    ++position_;
    // np.save pads the dict with spaces and ends it with a newline; anything else after the '}'
    // is not a header numpy wrote, and not part of the array either.
    const std::string_view rest = text_.substr(position_);
    if (rest.find_first_not_of(" \n") != std::string_view::npos)
      fail_npy_header(path_, "text after the dict: " + quoted_excerpt(rest) + " (only spaces and a newline may follow its '}')");
    if (!has_descr) fail_npy_header(path_, "missing 'descr'");
    if (!has_order) fail_npy_header(path_, "missing 'fortran_order'");
    if (!has_shape) fail_npy_header(path_, "missing 'shape'");
    return header;
  }

 private:
  // As Python prints a string. (Appending, not "'" + s + "'": GCC 12 warns -Wrestrict on that.)
  static std::string quoted(const std::string& text) {
    std::string out(1, '\'');
    out.append(text);
    out.push_back('\'');
    return out;
  }
  char peek() const { return position_ < text_.size() ? text_[position_] : '\0'; }
  void skip_blanks() {
    while (position_ < text_.size() && std::isspace(static_cast<unsigned char>(text_[position_]))) ++position_;
  }
  [[noreturn]] void malformed(const std::string& expected) {
    fail_npy_header(path_, "malformed dict: expected " + expected + " at character " + std::to_string(position_));
  }
  void expect(char c) {
    skip_blanks();
    if (peek() != c) malformed(std::string("'") + c + "'");
    ++position_;
  }
  std::string string_literal() {
    skip_blanks();
    const char quote = peek();
    if (quote != '\'' && quote != '"') malformed("a quoted string");
    const std::size_t end = text_.find(quote, position_ + 1);
    if (end == std::string_view::npos) malformed("a closing quote");
    std::string value(text_.substr(position_ + 1, end - position_ - 1));
    position_ = end + 1;
    return value;
  }
  bool boolean() {
    if (text_.substr(position_).starts_with("True")) {
      position_ += 4;
      return true;
    }
    if (text_.substr(position_).starts_with("False")) {
      position_ += 5;
      return false;
    }
    malformed("True or False");
  }
  std::vector<std::uint64_t> integer_tuple() {
    expect('(');
    std::vector<std::uint64_t> values;
    while (true) {
      skip_blanks();
      if (peek() == ')') break;
      std::uint64_t value = 0;
      const char* begin = text_.data() + position_;
      const auto [stop, error] = std::from_chars(begin, text_.data() + text_.size(), value);
      if (error != std::errc()) malformed("a non-negative integer in 'shape'");
      position_ += static_cast<std::size_t>(stop - begin);
      if (peek() == 'L') ++position_;  // Python 2's long suffix
      values.push_back(value);
      skip_blanks();
      if (peek() == ',') ++position_;
      else if (peek() != ')') malformed("',' or ')' in 'shape'");
    }
    ++position_;
    return values;
  }
  std::string raw_bracketed() {
    int depth = 0;
    const std::size_t start = position_;
    for (; position_ < text_.size(); ++position_) {
      if (text_[position_] == '[') ++depth;
      if (text_[position_] == ']' && --depth == 0) {
        ++position_;
        return std::string(text_.substr(start, position_ - start));
      }
    }
    malformed("a closing ']'");
  }

  std::string_view text_;
  const std::string& path_;
  std::size_t position_ = 0;
};

std::uint32_t little_endian(const unsigned char* bytes, int count) {
  std::uint32_t value = 0;
  for (int i = count - 1; i >= 0; --i) value = value << 8 | bytes[i];
  return value;
}

}  // namespace

bool has_npy_extension(const std::string& path) {
  if (path.size() < 4) return false;
  std::string tail = path.substr(path.size() - 4);
  std::transform(tail.begin(), tail.end(), tail.begin(), [](unsigned char c) { return std::tolower(c); });
  return tail == ".npy";
}

NpyHeader read_npy_header(std::FILE* file, const std::string& path) {
  unsigned char start[12];
  const std::size_t got = std::fread(start, 1, 10, file);
  if (std::ferror(file)) throw InputError(path + ": cannot read: " + std::strerror(errno));
  if (got < 8 || std::memcmp(start, kMagic.data(), kMagic.size()) != 0)
    throw InputError(path + ": not a .npy file (no \\x93NUMPY magic at the start)");
  const int major = start[6], minor = start[7];
  if (major < 1 || major > 3) fail_npy_header(path, "unsupported format version " + std::to_string(major) + "." + std::to_string(minor));
  // Version 1.0: a 2-byte header length; 2.0 and 3.0 (UTF-8 header): 4 bytes.
  const int length_bytes = major == 1 ? 2 : 4;
  if (got < 10 || (length_bytes == 4 && std::fread(start + 10, 1, 2, file) != 2)) fail_npy_header(path, "truncated");
  const std::uint32_t length = little_endian(start + 8, length_bytes);
  if (length > kMaxHeaderBytes)
    fail_npy_header(path, "length " + std::to_string(length) + " bytes is more than the " + std::to_string(kMaxHeaderBytes) +
                   " numpy reads (np.load's max_header_size)");
  std::string text(length, '\0');
  if (std::fread(text.data(), 1, length, file) != length) fail_npy_header(path, "truncated (the dict is shorter than its length)");
  NpyHeader header = HeaderParser(text, path).parse();
  header.data_offset = 8 + static_cast<std::uint64_t>(length_bytes) + length;
  return header;
}

std::string shape_text(const std::vector<std::uint64_t>& shape) {
  std::string text = "(";
  for (std::size_t i = 0; i < shape.size(); ++i) text += (i ? ", " : "") + std::to_string(shape[i]);
  return text + (shape.size() == 1 ? ",)" : ")");
}

std::string npy_preamble(std::string_view descr, std::uint64_t rows) {
  std::string dict = "{'descr': " + std::string(descr) + ", 'fortran_order': False, 'shape': (" +
                     std::to_string(rows) + ",), }";
  // Room for the largest count (20 digits), so the length is the same for every count.
  const std::size_t widest = dict.size() - std::to_string(rows).size() + 20;
  const std::size_t total = (10 + widest + 1 + kAlignment - 1) / kAlignment * kAlignment;
  dict.append(total - 10 - dict.size() - 1, ' ');
  dict += '\n';
  const std::size_t length = dict.size();  // < 65536: a version 1.0 length fits
  std::string preamble(kMagic);
  preamble += '\x01';
  preamble += '\x00';
  preamble += static_cast<char>(length & 0xff);
  preamble += static_cast<char>(length >> 8);
  return preamble + dict;
}

void read_npy_data(std::FILE* file, const std::string& path, void* into, std::size_t bytes) {
  const std::size_t got = std::fread(into, 1, bytes, file);
  if (got == bytes) return;
  if (std::ferror(file)) throw InputError(path + ": cannot read: " + std::strerror(errno));
  throw InputError(path + ": data: truncated: the file ends before the array does");
}

void fail_npy_header(const std::string& path, const std::string& problem) {
  throw InputError(path + ": header: " + problem);
}

}  // namespace bezinv::detail
