#include "merge.hpp"

#include <algorithm>
#include <cctype>
#include <charconv>
#include <memory>
#include <cstdio>
#include <stdexcept>
#include <system_error>
#include <tuple>

#include "bezinv/io.hpp"

namespace bezinv::cli {
namespace {

bool parse_count(std::string_view text, std::uint64_t& value) {
  const auto [stop, error] = std::from_chars(text.data(), text.data() + text.size(), value);
  return error == std::errc() && stop == text.data() + text.size() && !text.empty();
}

// OUT's format is chosen by extension as bezinv invert chooses it (".npy" in any case).
bool names_npy(const std::string& path) {
  if (path.size() < 4) return false;
  std::string tail = path.substr(path.size() - 4);
  for (char& c : tail) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  return tail == ".npy";
}

std::string range_text(const MergePart& p) { return std::to_string(p.begin) + ":" + std::to_string(p.end); }

}  // namespace

std::pair<std::uint64_t, std::uint64_t> parse_row_range(const std::string& text) {
  const std::size_t colon = text.find(':');
  std::uint64_t begin = 0, end = 0;
  if (colon == std::string::npos || !parse_count(std::string_view(text).substr(0, colon), begin) ||
      !parse_count(std::string_view(text).substr(colon + 1), end) || begin > end)
    throw std::invalid_argument("'" + text + "': expected A:B, 0-based rows A to B - 1, A <= B");
  return {begin, end};
}

MergePart parse_merge_part(const std::string& text) {
  // A:B=PATH, split at the first '=' (a path may hold one; a range cannot).
  const std::size_t equals = text.find('=');
  MergePart part;
  try {
    if (equals == std::string::npos || equals + 1 == text.size()) throw std::invalid_argument("");
    std::tie(part.begin, part.end) = parse_row_range(text.substr(0, equals));
  } catch (const std::invalid_argument&) {
    throw std::invalid_argument("part '" + text + "': expected A:B=PATH (the --rows range the part was made with, "
                                "then its OUT.npy)");
  }
  part.path = text.substr(equals + 1);
  return part;
}

int run_merge(std::uint64_t rows, std::vector<MergePart> parts, const std::string& out_path) {
  if (!names_npy(out_path))
    throw InputError(out_path + ": --out of bezinv merge is a .npy (the parts carry no reason column for a CSV)");
  std::stable_sort(parts.begin(), parts.end(), [](const MergePart& a, const MergePart& b) { return a.begin < b.begin; });
  // Every row once, in order: the ranges tile [0, rows) -- each begins where the one before ended,
  // the first at 0, the last at or past the end -- and each file holds its range's rows.
  std::uint64_t next = 0;
  std::vector<std::unique_ptr<ResultReader>> readers;
  for (const MergePart& p : parts) {
    if (p.begin != next)
      throw InputError(p.path + ": rows " + range_text(p) + ": " +
                       (p.begin < next ? "overlaps the part before it" : "rows " + std::to_string(next) + " to " +
                                                                              std::to_string(p.begin) + " are in no part"));
    if (p.begin > 0 && p.begin >= rows)  // only the first part may start at the end (no rows at all)
      throw InputError(p.path + ": rows " + range_text(p) + ": past the " + std::to_string(rows) + " points");
    std::unique_ptr<ResultReader> reader = open_results_npy(p.path);
    const std::uint64_t expected = std::min(p.end, rows) - p.begin;
    if (reader->rows() != expected)
      throw InputError(p.path + ": " + std::to_string(reader->rows()) + " rows, but --rows " + range_text(p) + " of " +
                       std::to_string(rows) + " points gives " + std::to_string(expected));
    readers.push_back(std::move(reader));
    next = std::min(p.end, rows);
  }
  if (next != rows)
    throw InputError("rows " + std::to_string(next) + " to " + std::to_string(rows) + " are in no part");
  // The parts' optional columns are kept: all must have the same ones.
  const ResultColumns columns = readers.empty() ? ResultColumns{} : readers.front()->columns();
  for (std::size_t i = 1; i < readers.size(); ++i)
    if (readers[i]->columns().point != columns.point)
      throw InputError(parts[i].path + ": " + (columns.point ? "has no" : "has the") + " point columns (x_t,y_t,z_t), but " +
                       parts.front().path + (columns.point ? " has" : " has not") + ": make every part with the same --columns");
  const std::unique_ptr<ResultWriter> writer = open_results(out_path, 0, columns);
  std::vector<PointResult> chunk(std::size_t{1} << 16);
  std::vector<Point3> at(chunk.size());
  for (const auto& reader : readers)
    while (const std::size_t count = reader->read(chunk, at))
      writer->write_with_points(std::span<const PointResult>(chunk.data(), count), std::span<const Point3>(at.data(), count));
  writer->commit();
  return 0;
}

}  // namespace bezinv::cli
