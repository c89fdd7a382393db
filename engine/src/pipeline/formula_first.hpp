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
// point, a base point near, off the curve, not certified) goes on through the stages, which are
// given what formula_first computed for them (the point normalized, N / M) and told the lanes
// whose first Newton iteration it took and which that left to the off-curve kernels (off the
// curve by more than the leave distance, most lanes it leaves): they take none of those steps
// again. A lane's answer depends on its point alone, not on its batch.
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
  // Of the batch's lanes, those whose N / M is in [0, 1] and whose first rational_newton iteration
  // from it leaves them to the off-curve kernels (first distance beyond the formula path's leave
  // distance): the stages take N / M as their start where the lane is active (formula_first_left).
  LaneSet first_iteration_leaves;
  // Whether w holds every lane's point normalized (u, v) and N / M (t_algebraic).
  bool given = false;
};

// Answers the lanes of points[0..count) it settles (each row written whole: ok, path formula,
// sigma columns NaN, as the stages' first pass answers them); their rows are untouched otherwise.
// With `keep` (and always from degree 4), for every lane it leaves in w the point normalized (u, v)
// and N / M (t_algebraic: NaN where the formula is not used), the bits form_batch and
// formula_or_seed would give, so that the stages need not compute them again (FormulaLeft::given).
// Uses w's t_refined, distance and certified too. Its stages go to the clock as
// the stages' would: normalizing to form_b, N / M to kernel, Newton to refine, the certificate and
// the rows to decide.
FormulaLeft formula_first(const PlanData& plan, const Point* points, PointResult* results, std::size_t count,
                          const InvertOptions& options, BatchWorkspace& w, StageClock& clock, bool keep = true);

// The lanes of a batch formula_first left (their starts told by fast_path_seed since) that
// rational_newton's first iteration leaves: those of `first_iteration_leaves` (N / M in [0, 1])
// given t by the formula (from_formula: active, N / M finite).
LaneSet formula_first_left(LaneSet first_iteration_leaves, std::size_t count, const BatchWorkspace& w);

}  // namespace bezinv::detail
