#pragma once
// The answer for a NURBS or composite curve from its spans' answers (docs/nurbs-and-composite.md).
//
// Each span was asked at the same distance tolerance. Then, in the whole curve's parameter:
//   - every span's on-segment parameter is a candidate (a span's double point gives two); two
//     candidates are one point unless the curve leaves the tolerance between them, along the curve
//     (or, on a closed curve, around through its ends): a point at a knot, on both spans that meet
//     there, is one point; a real crossing of two stretches is a double point (t < t2);
//   - with no candidate, the extension beyond the curve's ends (the first span's before s = 0, the
//     last span's past s = 1) gives outside_segment; an inner span's extension means nothing;
//   - otherwise off_curve at the nearest point of the whole curve: the nearest of the spans' nearest
//     points on their segments.
#include <array>
#include <span>

#include "bezinv/invert.hpp"
#include "piecewise/piecewise_plan.hpp"

namespace bezinv::detail {

// answers[k] is span k's answer to `point` (z = 0 for a plane curve).
PointResult whole_curve_answer(const PiecewiseData& curve, const std::array<double, 3>& point,
                               std::span<const PointResult> answers, const InvertOptions& options);

}  // namespace bezinv::detail
