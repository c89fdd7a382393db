#pragma once
// The off-curve path: a lane the fast path left undecided is answered `off_curve` without the
// SVD where geometry alone proves that answer (docs/fast-path.md, "Off the curve, by distance").
//
// The SVD path answers off_curve, at the nearest point of the segment, exactly when none of its
// candidates lies within the tolerance; every candidate is a point of the curve, on the segment
// or on its extension. So where the certified search (stationary_points.hpp) proves the nearest
// point of the segment farther than the tolerance, and extension_clear (extension.hpp) proves the
// same of every point beyond the segment, the SVD path could only answer off_curve at that same
// nearest point: this stage gives that answer with path `nearest`, its residual, and no singular
// values (the distance decided, not the gap). A lane either proof fails for goes on to the SVD
// path, as before.
#include <cstddef>

#include "bezinv/invert.hpp"
#include "bezinv/tolerances.hpp"
#include "pipeline/stage_clock.hpp"
#include "pipeline/workspace.hpp"
#include "plan_data.hpp"

namespace bezinv::detail {

// Points farther than this (normalized units: the curve's size is ~1) are left to the SVD path,
// which looks at them from a stand-in on their ray (refine.hpp, kFarEqualDistances).
inline constexpr double kOffCurvePathMaxCoordinate = 1e6;

// The radius both proofs hold for: a little above the tolerance, since a distance computed at any t
// is within ~n eps of the true one (normalized coordinates), far below kIsolationMargin.
inline double off_curve_radius(double tolerance) { return tolerance * (1 + kIsolationMargin) + kIsolationMargin; }

// For every active lane it has not looked at before (w.off_curve_tried, which it sets): the fast
// path calls it for the lanes it would leave, before its own per-lane loop, and invert_batch for
// whatever the fast path left after. Lane l's answer goes to rows[l].
void off_curve_path(const PlanData& plan, const InvertOptions& options, std::size_t count, BatchWorkspace& w,
                    LaneRows rows, StageClock& clock);

}  // namespace bezinv::detail
