// POINTS.csv -> PointRow chunks (format in bezinv/io.hpp), and open_points, which picks the reader.
//
// This path has to keep up with millions of rows and must not hold a whole file: the file is read
// in blocks, lines and fields are string_views into the current block (no per-row allocation),
// numbers go through std::from_chars, and the curve of the previous row is remembered (point files
// are usually grouped by curve).
#include <algorithm>
#include <cerrno>
#include <charconv>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <memory>
#include <string>
#include <string_view>
#include <system_error>
#include <unordered_map>
#include <vector>

#include "bezinv/io.hpp"
#include "io_npy.hpp"
#include "io_point_readers.hpp"

namespace bezinv {
namespace {

using namespace detail;  // the per-row reasons

// Bytes read from the file at a time: large enough that the syscalls do not show, small enough
// to stay in L2/L3 while the lines are parsed.
constexpr std::size_t kReadBytes = std::size_t{1} << 22;

[[noreturn]] void fail(const std::string& path, std::size_t line, const std::string& problem) {
  throw InputError(path + ":" + std::to_string(line) + ": " + problem);
}

bool is_blank(char c) { return c == ' ' || c == '\t'; }

std::string_view trimmed(std::string_view field) {
  while (!field.empty() && is_blank(field.front())) field.remove_prefix(1);
  while (!field.empty() && is_blank(field.back())) field.remove_suffix(1);
  return field;
}

bool all_blank(std::string_view line) { return trimmed(line).empty(); }

// A line quoted in an error message: one line, bounded length, control characters shown as '?'.
std::string excerpt(std::string_view line) {
  constexpr std::size_t kMax = 60;
  std::string out(line.substr(0, kMax));
  for (char& c : out)
    if (static_cast<unsigned char>(c) < 0x20) c = '?';
  if (line.size() > kMax) out += "...";
  return "'" + out + "'";
}

enum class Parsed { ok, not_a_number, not_finite };

// A coordinate: decimal or scientific, optional sign, surrounding blanks already trimmed.
Parsed parse_coordinate(std::string_view field, double& value) {
  // from_chars refuses a leading '+', which spreadsheets and printf("%+g") write.
  if (field.size() > 1 && field.front() == '+' && field[1] != '-' && field[1] != '+') field.remove_prefix(1);
  const char* const end = field.data() + field.size();
  const auto [stop, error] = std::from_chars(field.data(), end, value, std::chars_format::general);
  if (error == std::errc::invalid_argument || stop != end) return Parsed::not_a_number;
  if (error == std::errc::result_out_of_range) {
    // Either overflow (1e999: not finite) or underflow (1e-400: a finite number that rounds to
    // 0 or a subnormal). from_chars reports both alike and leaves value unset; strtod tells them
    // apart. Rare, so the copy does not matter.
    const std::string copy(field);
    value = std::strtod(copy.c_str(), nullptr);
    return std::isfinite(value) ? Parsed::ok : Parsed::not_finite;
  }
  // from_chars accepts "nan", "inf", "infinity": numbers, but no place on a curve.
  return std::isfinite(value) ? Parsed::ok : Parsed::not_finite;
}

// Maps the curve field to an index into the curve list: first as an id, then as a 0-based index.
class CurveLookup {
 public:
  explicit CurveLookup(const std::vector<Curve>& curves) : count_(curves.size()) {
    index_of_id_.reserve(curves.size());
    // emplace keeps the first of equal ids (read_curves_json refuses duplicates anyway).
    for (std::size_t i = 0; i < curves.size(); ++i) index_of_id_.emplace(curves[i].id, static_cast<int>(i));
  }

  // Curve index, or -1 with *reason set.
  int find(std::string_view field, const char*& reason) {
    if (has_last_ && field == last_field_) {
      reason = last_reason_;
      return last_curve_;
    }
    last_curve_ = resolve(field, last_reason_);
    last_field_ = field;  // a copy: the block the field lies in is about to be replaced
    has_last_ = true;
    reason = last_reason_;
    return last_curve_;
  }

 private:
  int resolve(std::string_view field, const char*& reason) const {
    reason = "";
    if (const auto it = index_of_id_.find(field); it != index_of_id_.end()) return it->second;
    if (field.empty()) {
      reason = kMissingCurve;
      return -1;
    }
    const bool negative = field.front() == '-';
    const std::string_view digits = negative ? field.substr(1) : field;
    const bool integer = !digits.empty() && std::all_of(digits.begin(), digits.end(),
                                                        [](char c) { return c >= '0' && c <= '9'; });
    if (!integer) {
      reason = kUnknownCurveId;
      return -1;
    }
    if (negative) {
      reason = kNegativeCurveIndex;
      return -1;
    }
    std::size_t index = 0;
    const auto [stop, error] = std::from_chars(digits.data(), digits.data() + digits.size(), index);
    // An index too large for size_t is past the end of any list.
    if (error != std::errc() || index >= count_) {
      reason = kCurveIndexPastEnd;
      return -1;
    }
    return static_cast<int>(index);
  }

  std::unordered_map<std::string_view, int> index_of_id_;
  std::size_t count_;
  bool has_last_ = false;
  std::string last_field_;
  int last_curve_ = -1;
  const char* last_reason_ = "";
};


class CsvPointReader final : public PointReader {
 public:
  CsvPointReader(const std::string& path, const std::vector<Curve>& curves) : path_(path), lookup_(curves) {
    file_ = std::fopen(path.c_str(), "rb");
    if (file_ == nullptr) throw InputError(path + ": cannot read: " + std::strerror(errno));
    // file_size, not fseek/ftell: on ext4 a directory seeks to LLONG_MAX. 0 (unknown) for a pipe.
    std::error_code no_size;
    if (std::filesystem::is_regular_file(path, no_size)) {
      const std::uintmax_t size = std::filesystem::file_size(path, no_size);
      if (!no_size) progress_.bytes_total = size;
    }
    while (buffer_.size() < 3 && !at_end_) fill();
    if (std::string_view(buffer_).starts_with("\xEF\xBB\xBF")) position_ = 3;  // UTF-8 BOM (spreadsheet exports)
    read_header();
  }
  ~CsvPointReader() override { std::fclose(file_); }
  CsvPointReader(const CsvPointReader&) = delete;
  CsvPointReader& operator=(const CsvPointReader&) = delete;

  std::size_t read(std::span<PointRow> rows) override {
    std::size_t count = 0;
    std::string_view line;
    while (count < rows.size() && next_line(line)) {
      ++line_number_;
      // Blank lines at the very end (an editor's extra newline) are not rows; a blank line with
      // data after it is, and is refused for its field count when that data comes.
      if (all_blank(line)) {
        if (first_blank_line_ == 0) first_blank_line_ = line_number_;
        continue;
      }
      if (first_blank_line_ != 0) fail(path_, first_blank_line_, "expected 3 fields (curve,x,y), found 1 (blank line)");
      rows[count++] = parse_row(line);
    }
    progress_.points += count;
    return count;
  }

  ReadProgress progress() const override { return progress_; }

 private:
  // Appends the next block of the file to what is left of the current one.
  void fill() {
    buffer_.erase(0, position_);
    position_ = 0;
    const std::size_t kept = buffer_.size();
    buffer_.resize(kept + kReadBytes);
    const std::size_t got = std::fread(buffer_.data() + kept, 1, kReadBytes, file_);
    buffer_.resize(kept + got);
    // fread on a directory opens fine and fails here with EISDIR.
    if (std::ferror(file_)) throw InputError(path_ + ": cannot read: " + std::strerror(errno));
    progress_.bytes += got;
    at_end_ = got < kReadBytes && std::feof(file_);
  }

  // The next line, CR of a CRLF ending removed; false at the end of the file. The view lasts
  // until the next call.
  bool next_line(std::string_view& line) {
    while (true) {
      const char* start = buffer_.data() + position_;
      const std::size_t remaining = buffer_.size() - position_;
      std::size_t length = remaining;
      if (const void* newline = std::memchr(start, '\n', remaining)) {
        length = static_cast<std::size_t>(static_cast<const char*>(newline) - start);
        position_ += length + 1;
      } else if (at_end_) {
        if (remaining == 0) return false;
        position_ += remaining;  // the last line, without a final newline
      } else {
        fill();
        continue;
      }
      if (length > 0 && start[length - 1] == '\r') --length;
      line = {start, length};
      return true;
    }
  }

  void read_header() {
    std::string_view line;
    const bool has_line = next_line(line);
    line_number_ = 1;
    const std::string header(has_line ? line : std::string_view());
    if (all_blank(header)) {
      // Nothing but blank lines is an empty file; a blank line before data is a missing header.
      while (next_line(line))
        if (!all_blank(line)) fail(path_, 1, "header must be 'curve,x,y', found " + excerpt(header));
      fail(path_, 1, "empty file (expected the header 'curve,x,y')");
    }
    std::string_view columns[3];
    std::size_t count = 0;
    std::size_t start = 0;
    bool too_many = false;
    const std::string_view text(header);
    while (true) {
      const std::size_t comma = text.find(',', start);
      const std::string_view column =
          trimmed(text.substr(start, comma == std::string_view::npos ? std::string_view::npos : comma - start));
      if (count < 3) columns[count] = column;
      else too_many = true;
      ++count;
      if (comma == std::string_view::npos) break;
      start = comma + 1;
    }
    if (too_many || count != 3 || columns[0] != "curve" || columns[1] != "x" || columns[2] != "y")
      fail(path_, 1, "header must be 'curve,x,y', found " + excerpt(header));
  }

  PointRow parse_row(std::string_view line) {
    const std::size_t comma1 = line.find(',');
    const std::size_t comma2 = comma1 == std::string_view::npos ? comma1 : line.find(',', comma1 + 1);
    if (comma2 == std::string_view::npos || line.find(',', comma2 + 1) != std::string_view::npos) {
      const std::size_t fields = 1 + static_cast<std::size_t>(std::count(line.begin(), line.end(), ','));
      fail(path_, line_number_, "expected 3 fields (curve,x,y), found " + std::to_string(fields) + ": " + excerpt(line));
    }

    PointRow row;
    const char* reason = "";
    row.curve = lookup_.find(trimmed(line.substr(0, comma1)), reason);

    const Parsed x = parse_coordinate(trimmed(line.substr(comma1 + 1, comma2 - comma1 - 1)), row.point.x);
    const Parsed y = parse_coordinate(trimmed(line.substr(comma2 + 1)), row.point.y);
    // The first problem in column order is the one reported.
    if (row.curve < 0) {
      row.reason = reason;
    } else if (x != Parsed::ok) {
      row.reason = x == Parsed::not_a_number ? kXNotANumber : kXNotFinite;
    } else if (y != Parsed::ok) {
      row.reason = y == Parsed::not_a_number ? kYNotANumber : kYNotFinite;
    }
    if (x == Parsed::not_a_number) row.point.x = PointResult::nan;
    if (y == Parsed::not_a_number) row.point.y = PointResult::nan;
    if (*row.reason != '\0') row.curve = -1;
    return row;
  }

  std::string path_;
  std::FILE* file_ = nullptr;
  std::string buffer_;
  std::size_t position_ = 0;  // first unread byte of buffer_
  bool at_end_ = false;
  std::size_t line_number_ = 0;
  std::size_t first_blank_line_ = 0;  // of the blank lines since the last row; 0: none
  CurveLookup lookup_;
  ReadProgress progress_;
};

}  // namespace

namespace detail {

std::unique_ptr<PointReader> open_points_csv(const std::string& path, const std::vector<Curve>& curves) {
  return std::make_unique<CsvPointReader>(path, curves);
}

}  // namespace detail

std::unique_ptr<PointReader> open_points(const std::string& path, const std::vector<Curve>& curves,
                                         const CurveSelection& selection) {
  if (has_npy_extension(path)) return open_points_npy(path, curves, selection);
  if (!selection.curve.empty() || !selection.index_path.empty())
    throw InputError(path + ": --curve and --curve-index are for .npy points; a CSV names each point's curve "
                            "in its 'curve' column");
  return open_points_csv(path, curves);
}

std::vector<PointRow> read_points_csv(const std::string& path, const std::vector<Curve>& curves) {
  const std::unique_ptr<PointReader> reader = open_points_csv(path, curves);
  std::vector<PointRow> rows;
  constexpr std::size_t kStep = 1 << 16;
  while (true) {
    const std::size_t had = rows.size();
    rows.resize(had + kStep);
    const std::size_t got = reader->read(std::span(rows).subspan(had));
    rows.resize(had + got);
    if (got < kStep) return rows;
  }
}

}  // namespace bezinv
