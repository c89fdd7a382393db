#pragma once
// The points of one NURBS or composite curve: each inverted on every span (at the whole curve's
// tolerance), the spans' answers then combined into the whole curve's (whole_curve_answer.hpp).
#include <span>

#include "bezinv/invert.hpp"
#include "bezinv/profile.hpp"
#include "plan_data.hpp"

namespace bezinv::detail {

// plan.piecewise must be set; points[i] = (x, y) and, for a space curve, z[i] of the i-th point.
void invert_piecewise(const PlanData& plan, std::span<const Point> points, std::span<const double> z,
                      std::span<PointResult> results, const InvertOptions& options, StageSeconds* stages);

}  // namespace bezinv::detail
