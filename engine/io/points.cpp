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
#include "io/npy.hpp"
#include "io/point_readers.hpp"
#include "quote.hpp"
#include "io/read_points_csv.hpp"

namespace bezinv {
namespace {

using namespace detail;  // the per-row reasons

// Bytes read from the file at a time: large enough that the syscalls do not show, small enough
// to stay in L2/L3 while the lines are parsed.
constexpr std::size_t kReadBytes = std::size_t{1} << 22;
// ... but no more than a regular file has left, rounded up to this: a small file gets a small
// buffer (a 4 MiB one, zeroed, for a 100-byte file is what reading it costs).
constexpr std::size_t kMinReadBytes = std::size_t{1} << 16;
// The longest line read. A row is three short fields; a longer line is not a points file (a binary
// file, one without line breaks such as /dev/zero), and holding it would grow memory without end.
constexpr std::size_t kMaxLineBytes = std::size_t{1} << 20;

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
    for (const Curve& c : curves) space_.push_back(c.dimension() == 3);
    // emplace keeps the first of equal ids (read_curves_json refuses duplicates anyway).
    for (std::size_t i = 0; i < curves.size(); ++i) index_of_id_.emplace(curves[i].id, static_cast<int>(i));
  }

  // Whether curve i (an index find returned) is a space curve, whose points need z.
  bool is_space(int curve) const { return space_[static_cast<std::size_t>(curve)]; }

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
  std::vector<bool> space_;  // curve i is a space curve (its points need z)
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
    // A constructor that throws runs no destructor: the file is closed here, or every refused
    // file would keep its descriptor (a library user reading many files runs out of them).
    try {
      // file_size, not fseek/ftell: on ext4 a directory seeks to LLONG_MAX. 0 (unknown) for a pipe.
      std::error_code no_size;
      if (std::filesystem::is_regular_file(path, no_size)) {
        const std::uintmax_t size = std::filesystem::file_size(path, no_size);
        if (!no_size) progress_.bytes_total = size;
      }
      while (buffer_.size() < 3 && !at_end_) fill();
      if (std::string_view(buffer_).starts_with("\xEF\xBB\xBF")) position_ = 3;  // UTF-8 BOM (spreadsheet exports)
      read_header();
    } catch (...) {
      std::fclose(file_);
      throw;
    }
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
      if (first_blank_line_ != 0)
        fail(path_, first_blank_line_, "expected " + expected_fields() + ", found 1 (blank line)");
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
    // At least a byte past a regular file's size, so its end is seen in the same read (and a file
    // that grew since it was measured is read on).
    const std::uint64_t left = progress_.bytes_total > progress_.bytes ? progress_.bytes_total - progress_.bytes : 0;
    const std::size_t step = progress_.bytes_total == 0
                                 ? kReadBytes
                                 : static_cast<std::size_t>(std::clamp<std::uint64_t>(left + 1, kMinReadBytes, kReadBytes));
    buffer_.resize(kept + step);
    const std::size_t got = std::fread(buffer_.data() + kept, 1, step, file_);
    buffer_.resize(kept + got);
    // fread on a directory opens fine and fails here with EISDIR.
    if (std::ferror(file_)) throw InputError(path_ + ": cannot read: " + std::strerror(errno));
    progress_.bytes += got;
    at_end_ = got < step && std::feof(file_);
  }

  // The next line, CR of a CRLF ending removed; false at the end of the file. The view lasts
  // until the next call. A line longer than kMaxLineBytes (not counting its CR LF) is an
  // InputError for line line_number_ + 1: the callers count a line once they have it.
  bool next_line(std::string_view& line) {
    while (true) {
      const char* start = buffer_.data() + position_;
      const std::size_t remaining = buffer_.size() - position_;
      // A line at the limit and its CR LF fit in the window; no newline in a full window is
      // already too long, so the buffer never holds much more than one limit of a line.
      const std::size_t window = std::min(remaining, kMaxLineBytes + 2);
      const void* newline = std::memchr(start, '\n', window);
      std::size_t length = remaining;
      if (newline != nullptr) {
        length = static_cast<std::size_t>(static_cast<const char*>(newline) - start);
        position_ += length + 1;
      } else if (window == kMaxLineBytes + 2) {
        too_long();
      } else if (at_end_) {
        if (remaining == 0) return false;
        position_ += remaining;  // the last line, without a final newline
      } else {
        fill();
        continue;
      }
      if (length > 0 && start[length - 1] == '\r') --length;
      if (length > kMaxLineBytes) too_long();
      line = {start, length};
      return true;
    }
  }

  [[noreturn]] void too_long() const {
    fail(path_, line_number_ + 1, "line longer than " + std::to_string(kMaxLineBytes) +
                                      " bytes (the limit for a line of POINTS.csv)");
  }

  void read_header() {
    std::string_view line;
    const bool has_line = next_line(line);
    line_number_ = 1;
    const std::string header(has_line ? line : std::string_view());
    if (all_blank(header)) {
      // Nothing but blank lines is an empty file; a blank line before data is a missing header.
      while (next_line(line)) {
        ++line_number_;
        if (!all_blank(line)) fail(path_, 1, "header must be 'curve,x,y', found " + quoted_excerpt(header));
      }
      fail(path_, 1, "empty file (expected the header 'curve,x,y')");
    }
    const std::size_t count = split(header);
    if ((count != 3 && count != 4) || fields_[0] != "curve" || fields_[1] != "x" || fields_[2] != "y" ||
        (count == 4 && fields_[3] != "z"))
      fail(path_, 1, "header must be 'curve,x,y' or 'curve,x,y,z', found " + quoted_excerpt(header));
    columns_ = count;
  }

  std::string expected_fields() const {
    return columns_ == 4 ? "4 fields (curve,x,y,z)" : "3 fields (curve,x,y)";
  }

  // Splits a line into fields_ (the first three; views into the line or into unquoted_, valid
  // until the next call) and returns how many fields it has. RFC 4180 quoting: a field in double
  // quotes may hold commas, and "" inside it stands for one quote. Blanks around a field are
  // dropped, inside quotes too (no id or number begins or ends with one). A quoted field must
  // close on its line: line breaks inside quotes are refused, as rows are one line each here.
  std::size_t split(std::string_view line) {
    if (std::memchr(line.data(), '"', line.size()) == nullptr) {
      // The common case, without quotes: no copies.
      std::size_t count = 0, start = 0;
      while (true) {
        const std::size_t comma = line.find(',', start);
        if (count < 4) fields_[count] = trimmed(line.substr(start, comma == std::string_view::npos ? comma : comma - start));
        ++count;
        if (comma == std::string_view::npos) return count;
        start = comma + 1;
      }
    }
    std::size_t count = 0, i = 0;
    while (true) {
      while (i < line.size() && is_blank(line[i])) ++i;
      std::string_view field;
      if (i < line.size() && line[i] == '"') {
        const std::size_t open = i++;
        std::string& text = unquoted_[std::min<std::size_t>(count, 4)];
        text.clear();
        bool closed = false;
        while (!closed) {
          const std::size_t quote = line.find('"', i);
          if (quote == std::string_view::npos) break;
          text.append(line.substr(i, quote - i));
          if (quote + 1 < line.size() && line[quote + 1] == '"') {
            text += '"';
            i = quote + 2;
          } else {
            i = quote + 1;
            closed = true;
          }
        }
        if (!closed)
          fail(path_, line_number_, "field " + std::to_string(count + 1) + ": the quote opened at " +
                                        quoted_excerpt(line.substr(open)) +
                                        " does not close on its line (a quoted field may not hold a line break)");
        while (i < line.size() && is_blank(line[i])) ++i;
        if (i < line.size() && line[i] != ',')
          fail(path_, line_number_, "field " + std::to_string(count + 1) + ": text after the closing quote: " +
                                        quoted_excerpt(line.substr(i, line.find(',', i) - i)));
        field = trimmed(text);
      } else {
        const std::size_t comma = line.find(',', i);
        field = trimmed(line.substr(i, comma == std::string_view::npos ? comma : comma - i));
        i = comma == std::string_view::npos ? line.size() : comma;
      }
      if (count < 4) fields_[count] = field;
      ++count;
      if (i >= line.size()) return count;
      ++i;  // the comma
    }
  }

  PointRow parse_row(std::string_view line) {
    const std::size_t count = split(line);
    if (count != columns_)
      fail(path_, line_number_, "expected " + expected_fields() + ", found " + std::to_string(count) + ": " + quoted_excerpt(line));

    PointRow row;
    const char* reason = "";
    row.curve = lookup_.find(fields_[0], reason);

    const Parsed x = parse_coordinate(fields_[1], row.point.x);
    const Parsed y = parse_coordinate(fields_[2], row.point.y);
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
    // z: given for a space curve's point, empty (or no column) for a plane curve's.
    const bool has_z = columns_ == 4 && !fields_[3].empty();
    if (has_z) {
      const Parsed z = parse_coordinate(fields_[3], row.z);
      if (z == Parsed::not_a_number) row.z = PointResult::nan;
      if (*row.reason == '\0' && z != Parsed::ok) row.reason = z == Parsed::not_a_number ? kZNotANumber : kZNotFinite;
    }
    if (*row.reason == '\0' && row.curve >= 0) {
      const bool space = lookup_.is_space(row.curve);
      if (space && !has_z) row.reason = kZMissing;
      if (!space && has_z) row.reason = kZForPlaneCurve;
    }
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
  std::size_t columns_ = 3;             // 3 (curve,x,y) or 4 (curve,x,y,z), from the header
  std::string_view fields_[4];          // of the line last split
  std::string unquoted_[5];             // quoted fields without their quotes; [4]: fields past the fourth
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
  if (selection.begin != 0 || selection.end != UINT64_MAX)
    throw InputError(path + ": --rows is for .npy points (a CSV's rows are not found without reading it all)");
  return open_points_csv(path, curves);
}

std::vector<PointRow> detail::read_points_csv(const std::string& path, const std::vector<Curve>& curves) {
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
