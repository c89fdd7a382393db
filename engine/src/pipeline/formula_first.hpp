#pragma once
// The formula path's common case in one pass: a point on the curve, away from the formula's base
// points and from any other branch. The stages (form_batch, formula_or_seed, fast_path_decide) each
// loop over the batch and keep lane state for every case they handle; for a conic or a cubic,
// whose N / M costs a few operations, those loops and the row written twice (cleared by admit,
// then answered) cost more than the inversion itself. Here each lane is normalized, given
// t = N / M, refined (rational_newton's iterations, with the settings of fast_path_decide's
// on-curve lanes) and certified by the isolation certificate's first test (isolated_by_far_boxes)
// (for a conic or a cubic all in one kernel, formula_newton, which settles the lanes the first
// Newton iteration settles), and its row written once. Those are the very operations the stages
// make for such a lane, so its row has the same bits as theirs. Every other lane (a non-finite
// point, a base point near, off the curve, not certified) goes on through the stages, from what
// formula_first computed for it (its point normalized, N / M, and whether the first Newton
// iteration leaves it to the off-curve kernels): the stages take up each such lane where the same
// steps would have brought it, so it costs about what it would in a batch that skipped
// formula_first. A lane's answer depends on its point alone, not on its batch.
#include <array>
#include <cstddef>
#include <cstdint>

#include "bezinv/invert.hpp"
#include "plan_data.hpp"
#include "pipeline/stage_clock.hpp"
#include "pipeline/workspace.hpp"

namespace bezinv::detail {

// Whether a batch of this plan starts with formula_first: the formula path (takes_formula_path).
bool takes_formula_first(const PlanData& plan, const InvertOptions& options);

// The lanes formula_first leaves, and what it found for them.
struct FormulaLeft {
  std::size_t count = 0;                          // how many
  std::array<std::uint8_t, kBatchLanes> lane_of;  // which, lane_of[0..count), in order
  // Of the batch's lanes, those rational_newton's first iteration leaves to the off-curve kernels
  // (their first distance beyond the formula path's leave distance; w.distance +inf).
  LaneSet newton_left;
};

// Answers the lanes of points[0..count) it settles (each row written whole: ok, path formula,
// sigma columns NaN, as the stages' first pass answers them); their rows are untouched otherwise.
// For every lane, settled or not, it leaves in w the point normalized (u, v) and N / M
// (t_algebraic: NaN where the formula is not used), the bits form_batch and formula_or_seed would
// give; w.distance is +inf in the lanes of newton_left. Uses w's t_refined and certified too. Its
// stages go to the clock as the stages' would: normalizing to form_b, N / M to kernel, Newton to
// refine, the certificate and the rows to decide.
FormulaLeft formula_first(const PlanData& plan, const Point* points, PointResult* results, std::size_t count,
                          const InvertOptions& options, BatchWorkspace& w, StageClock& clock);

}  // namespace bezinv::detail
