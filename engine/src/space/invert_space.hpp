#pragma once
// The points of one space curve (space_curve.hpp): projected on the plan's plane, inverted there by
// the plane engine, each answer then checked, refined and if need be replaced in space.
#include <span>

#include "bezinv/invert.hpp"
#include "bezinv/profile.hpp"
#include "plan_data.hpp"

namespace bezinv::detail {

// plan.space must be set; points[i] = (x, y) and z[i] of the i-th point.
void invert_space_curve(const PlanData& plan, std::span<const Point> points, std::span<const double> z,
                        std::span<PointResult> results, const InvertOptions& options, StageSeconds* stages);

}  // namespace bezinv::detail
