// POINTS.csv -> std::vector<PointRow> (format in bezinv/io.hpp).
//
// This path has to keep up with millions of rows, so: the file is read in one piece, lines and
// fields are string_views into it (no per-row allocation), numbers go through std::from_chars,
// and the curve of the previous row is remembered (point files are usually grouped by curve).
#include <algorithm>
#include <charconv>
#include <cmath>
#include <cstdlib>
#include <cstring>
#include <string>
#include <string_view>
#include <system_error>
#include <unordered_map>
#include <vector>

#include "bezinv/io.hpp"
#include "io_whole_file.hpp"

namespace bezinv {
namespace {

// Per-row reasons: static text, carried into OUT.csv's reason column (no commas).
constexpr const char* kUnknownCurveId = "unknown curve id";
constexpr const char* kMissingCurve = "missing curve id";
constexpr const char* kCurveIndexPastEnd = "curve index past the end";
constexpr const char* kNegativeCurveIndex = "negative curve index";
constexpr const char* kXNotANumber = "x is not a number";
constexpr const char* kYNotANumber = "y is not a number";
constexpr const char* kXNotFinite = "x is not finite";
constexpr const char* kYNotFinite = "y is not finite";

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

// The next line of text from *position; CR of a CRLF ending removed. Advances past the '\n'.
std::string_view next_line(std::string_view text, std::size_t& position) {
  const char* start = text.data() + position;
  const std::size_t remaining = text.size() - position;
  const void* newline = std::memchr(start, '\n', remaining);
  std::size_t length = newline ? static_cast<std::size_t>(static_cast<const char*>(newline) - start) : remaining;
  position += newline ? length + 1 : length;
  if (length > 0 && start[length - 1] == '\r') --length;
  return {start, length};
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
    last_field_ = field;  // a view into the file text, which outlives the lookup
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
  std::string_view last_field_;
  int last_curve_ = -1;
  const char* last_reason_ = "";
};

}  // namespace

std::vector<PointRow> read_points_csv(const std::string& path, const std::vector<Curve>& curves) {
  const std::string text = detail::read_whole_file(path);
  std::string_view body(text);
  if (body.starts_with("\xEF\xBB\xBF")) body.remove_prefix(3);  // UTF-8 BOM (spreadsheet exports)

  // Blank lines at the very end (an editor's extra newline) are not rows; a blank line with
  // data after it is, and is refused below for its field count.
  std::size_t end = body.size();
  while (end > 0 && (is_blank(body[end - 1]) || body[end - 1] == '\n' || body[end - 1] == '\r')) --end;
  body = body.substr(0, end);
  if (body.empty()) fail(path, 1, "empty file (expected the header 'curve,x,y')");

  std::size_t position = 0;
  std::size_t line_number = 1;
  {
    const std::string_view header = next_line(body, position);
    std::string_view columns[3];
    std::size_t count = 0;
    std::size_t start = 0;
    bool too_many = false;
    while (true) {
      const std::size_t comma = header.find(',', start);
      const std::string_view column = trimmed(header.substr(start, comma == std::string_view::npos ? std::string_view::npos : comma - start));
      if (count < 3) columns[count] = column;
      else too_many = true;
      ++count;
      if (comma == std::string_view::npos) break;
      start = comma + 1;
    }
    if (too_many || count != 3 || columns[0] != "curve" || columns[1] != "x" || columns[2] != "y")
      fail(path, 1, "header must be 'curve,x,y', found " + excerpt(header));
  }

  const std::size_t newline_count = static_cast<std::size_t>(std::count(body.begin(), body.end(), '\n'));
  std::vector<PointRow> rows;
  rows.reserve(newline_count);  // lines after the header: newlines + 1 - 1

  CurveLookup lookup(curves);
  while (position < body.size()) {
    ++line_number;
    const std::string_view line = next_line(body, position);

    const std::size_t comma1 = line.find(',');
    const std::size_t comma2 = comma1 == std::string_view::npos ? comma1 : line.find(',', comma1 + 1);
    if (comma2 == std::string_view::npos || line.find(',', comma2 + 1) != std::string_view::npos) {
      const std::size_t fields = 1 + static_cast<std::size_t>(std::count(line.begin(), line.end(), ','));
      fail(path, line_number,
           "expected 3 fields (curve,x,y), found " + std::to_string(fields) +
               (all_blank(line) ? std::string(" (blank line)") : ": " + excerpt(line)));
    }

    PointRow row;
    const char* reason = "";
    row.curve = lookup.find(trimmed(line.substr(0, comma1)), reason);

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
    rows.push_back(row);
  }
  return rows;
}

}  // namespace bezinv
