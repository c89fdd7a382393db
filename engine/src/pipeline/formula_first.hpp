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
// point, a base point near, off the curve, not certified) goes through the stages as before,
// gathered into a batch of its own; a lane's answer depends on its point alone, not on its batch.
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

// Answers the lanes of points[0..count) it settles (each row written whole: ok, path formula,
// sigma columns NaN, as the stages' first pass answers them). Returns how many lanes it leaves,
// their indices in left_of[0..left), in order; their rows are untouched. Uses w's u, v,
// t_algebraic, t_refined, distance and certified. Its stages go to the clock as the stages'
// would: normalizing to form_b, N / M to kernel, Newton to refine, the certificate and the rows
// to decide.
std::size_t formula_first(const PlanData& plan, const Point* points, PointResult* results, std::size_t count,
                          const InvertOptions& options, BatchWorkspace& w, StageClock& clock,
                          std::array<std::uint8_t, kBatchLanes>& left_of);

}  // namespace bezinv::detail
