#pragma once
// The two PointReader implementations behind open_points (engine internal).
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

std::unique_ptr<PointReader> open_points_csv(const std::string& path, const std::vector<Curve>& curves);
std::unique_ptr<PointReader> open_points_npy(const std::string& path, const std::vector<Curve>& curves,
                                             const CurveSelection& selection);

}  // namespace bezinv::detail
