#pragma once
// The two PointReader implementations behind open_points (engine internal).
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "bezinv/io.hpp"

namespace bezinv::detail {

// Per-row reasons: static text, carried into OUT.csv's reason column (no commas).
inline constexpr const char* kUnknownCurveId = "unknown curve id";
inline constexpr const char* kMissingCurve = "missing curve id";
inline constexpr const char* kCurveIndexPastEnd = "curve index past the end";
inline constexpr const char* kNegativeCurveIndex = "negative curve index";
inline constexpr const char* kXNotANumber = "x is not a number";
inline constexpr const char* kYNotANumber = "y is not a number";
inline constexpr const char* kXNotFinite = "x is not finite";
inline constexpr const char* kYNotFinite = "y is not finite";
inline constexpr const char* kZNotANumber = "z is not a number";
inline constexpr const char* kZNotFinite = "z is not finite";
inline constexpr const char* kZMissing = "no z for a point of a space curve";
inline constexpr const char* kZForPlaneCurve = "z given for a point of a plane curve";

// A row of x, y (, z) doubles (`width` of them) and its curve made into a PointRow, checked as the
// rows of a .npy or an array are: a non-finite coordinate, or a row whose width is not its curve's
// dimension (space[c]: curve c is a space curve), is invalid_input with its reason. `curve` < 0
// comes with its reason already.
inline void make_point_row(PointRow& row, const double* xyz, std::size_t width, int curve, const char* reason,
                           const std::vector<bool>& space) {
  row.point = {xyz[0], xyz[1]};
  row.z = width == 3 ? xyz[2] : PointResult::nan;
  row.reason = reason;
  row.curve = curve;
  if (curve < 0) return;
  if (!std::isfinite(row.point.x)) row.reason = kXNotFinite;
  else if (!std::isfinite(row.point.y)) row.reason = kYNotFinite;
  else if ((width == 3) != space[static_cast<std::size_t>(curve)]) row.reason = width == 3 ? kZForPlaneCurve : kZMissing;
  else if (width == 3 && !std::isfinite(row.z)) row.reason = kZNotFinite;
  if (*row.reason != '\0') row.curve = -1;
}

// A row's 0-based curve index (--curve-index): the curve, or -1 and the reason.
inline int curve_from_index(std::int64_t index, std::size_t curve_count, const char*& reason) {
  if (index < 0) {
    reason = kNegativeCurveIndex;
    return -1;
  }
  if (static_cast<std::uint64_t>(index) >= curve_count) {
    reason = kCurveIndexPastEnd;
    return -1;
  }
  reason = "";
  return static_cast<int>(index);
}

// The curve of --curve: an id first, then a 0-based index (as in POINTS.csv). Throws InputError
// naming `path` and `option` (the name the caller gave the selection).
int selected_curve(const std::string& path, const std::vector<Curve>& curves, const std::string& selection,
                   const char* option = "--curve");
// One curve for every row: the rows' `width` must be its dimension. Throws InputError naming `where`.
void check_width(const std::string& where, const std::string& shape, std::size_t width, const Curve& curve);

std::unique_ptr<PointReader> open_points_csv(const std::string& path, const std::vector<Curve>& curves);
std::unique_ptr<PointReader> open_points_npy(const std::string& path, const std::vector<Curve>& curves,
                                             const CurveSelection& selection);

}  // namespace bezinv::detail
