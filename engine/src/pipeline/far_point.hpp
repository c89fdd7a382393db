#pragma once
// A finite point so far from the curve that its normalized coordinates or its Bezout matrix
// overflow (beyond ~1e150 times the curve's size): answered off_curve from its direction.
#include "bezinv/invert.hpp"
#include "plan_data.hpp"

namespace bezinv::detail {

// off_curve at the point of the segment nearest to `point`: from that far, to within the curve's
// size over the distance, the point of the segment farthest along the point's direction from the
// centre, i.e. the nearest point to a stand-in on that ray at kFarStandIn (normalized units),
// where nothing overflows.
void answer_far_point(const PlanData& plan, const Point& point, PointResult& r);

}  // namespace bezinv::detail
