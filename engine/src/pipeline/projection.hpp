#pragma once
// Off-curve rows by the inversion formula's projection (OffCurve::projection, Wang & Joe Sect. 4):
// t = N(P0)/M(P0) in place of the nearest point of the segment. The status is decided as with
// OffCurve::nearest, so no status changes; only an off_curve row's t, residual and path do.
//
// What the projection saves is the search for the nearest point. An off-curve lane whose fast-path
// refinement ended at a local minimum of the distance on the segment needs only the proof that the
// whole curve stays farther than the tolerance: the isolation certificate at that minimum (a
// single stationary point around it, every other piece's box beyond the tolerance) and the
// extension's clearance. The nearest-point mode asks more of the same certificate (every other box
// beyond the point's own distance, so the local minimum is the global one), and searches where that
// fails; at noise well above the tolerance it often fails.
#include <cstddef>

#include "bezinv/invert.hpp"
#include "pipeline/stage_clock.hpp"
#include "pipeline/workspace.hpp"
#include "plan_data.hpp"

namespace bezinv::detail {

// Whether off_curve rows of this plan are answered by projection: asked for, and the plan has an
// inversion formula (formula_path_data).
bool projects_off_curve(const PlanData& plan, const InvertOptions& options);

// An off_curve answer r for the plan-normalized point (u0, v0) becomes the projection where the
// formula is valid at the point: t = N/M, residual |P(t) - P0|, path projection, no sigma columns.
// Elsewhere (near the formula's base points, a far point) r stays as it is. So it does where the
// projected point is within `beyond`, the distance that decided off_curve (the tolerance): without
// refinement the status is decided at the algebraic t, and the projection can land nearer, within
// the tolerance; an off_curve row's residual must stay beyond it.
void project_off_curve(const PlanData& plan, double u0, double v0, double beyond, PointResult& r);

// The off-curve path's quick proof for projection (see above), before the nearest-point search:
// every active lane whose refinement ended on the segment farther than the tolerance, and whose
// proof holds, is answered off_curve by projection and leaves the batch.
void projection_path(const PlanData& plan, const InvertOptions& options, std::size_t count, BatchWorkspace& w,
                     LaneRows rows);

}  // namespace bezinv::detail
