#pragma once
// The fast path (docs/fast-path.md): with refinement on and degree >= 2, a null vector of B by
// inverse iteration instead of an SVD, read out and refined lane-batched; a lane is answered here
// only where the SVD path could not answer it differently, and every other lane stays active for
// the SVD path.
//   degree 2        the full kernel (pivoted LU, the sigma_{n-1} estimate) for every lane;
//   degree >= 3     pass 1, the seed kernel (L D L^T without pivoting, no gap): a lane refined onto
//                   the segment that the isolation certificate covers is answered;
//                   pass 2, the gap pass: the lanes the geometry alone does not settle (on the
//                   segment but not certified, or off the curve and proved the nearest point)
//                   go through the full kernel and decide_with_gap.
#include <cstddef>
#include <cstdint>

#include "bezinv/invert.hpp"
#include "bezinv/kernels/batch.hpp"
#include "plan_data.hpp"
#include "pipeline/stage_clock.hpp"
#include "pipeline/workspace.hpp"

namespace bezinv::detail {

// From this degree the seed kernel forms each lane's B in registers from the plan instead of
// reading the batch's (bezout_null_vector_seed, the same bits as bezout_matrix): above it a
// batch's B no longer fits in L1. Speed only (docs/fast-path.md, "Forming B in the seed").
inline constexpr int kFormedBMinDegree = 8;

// Whether a batch of this plan takes the fast path. Not on a straight line: B vanishes at its
// points, and the kernel's estimates, relative to ||B||, would read rounding as evidence.
inline bool takes_fast_path(const PlanData& plan, const InvertOptions& options) {
  return options.fast_path && options.refine && plan.degree >= 2 && plan.degree <= kFastPathMaxDegree &&
         !plan.straight_line;
}

// Whether the fast path forms B itself (the batch's w.B is then not formed in stage 1).
inline bool forms_b_in_seed(const PlanData& plan, const InvertOptions& options) {
  return takes_fast_path(plan, options) && plan.degree >= kFormedBMinDegree;
}

// Whether the formed seed leaves the lanes far from the segment (segment_far) unseeded: not where
// the tolerance reaches a quarter of that distance (a point within it is better seeded).
inline bool skips_far_seeds(const PlanData& plan, double tolerance) {
  return !plan.segment_far_near.empty() && tolerance <= 0.25 * plan.segment_far_reach;
}

// The batch's lanes far from the segment (segment_far, all lanes), as bits, where skips_far_seeds
// holds and the caller has told them already (by_kind.hpp); else not known, and formed_seed tells
// them itself.
struct FarLanes {
  bool known = false;
  LaneSet lanes;
};

// Whether stage 1 leaves the batch's B unformed: the seed forms it, or the formula path needs it
// for few lanes (formula_path.hpp). The lanes that reach the SVD path then form theirs.
bool forms_b_late(const PlanData& plan, const InvertOptions& options);

// Stage 2 and the read-out for the batch's active lanes: w.t_algebraic (NaN where the seed did
// not settle), w.defect and w.estimate per lane (with degree 2's w.z and sigma_next).
// formula_given (the formula path): w.t_algebraic holds N / M for every lane already
// (formula_first left it there).
void fast_path_seed(const PlanData& plan, const Point* points, LaneRows rows, std::size_t count,
                    const InvertOptions& options, BatchWorkspace& w, StageClock& clock, FarLanes far = {},
                    bool formula_given = false);

// Stages 3-4, the refinement and the decisions it allows, for w's lanes 0..count as
// fast_path_seed left them (or as by_kind.hpp's far queue puts them back); lane l's answer goes to
// rows[l]. newton_left: formula lanes whose first rational_newton iteration, from t_algebraic,
// formula_first ran already, and which it left to the off-curve kernels (their first distance
// beyond the leave distance): they join those kernels' lanes as if the refinement had left them.
void fast_path_decide(const PlanData& plan, LaneRows rows, std::size_t count, const InvertOptions& options,
                      BatchWorkspace& w, StageClock& clock, LaneSet newton_left = {});

// The full kernel (pivoted LU, `iterations` solves: kernels::kNullVectorIterations in pass 2, more
// for the seed retry; the sigma_{n-1} estimate) for the lanes
// w.gap_lane_of[0..waiting), compacted, B formed for them from (w.u, w.v); its z,
// defect and estimates put back in their lanes.
void full_kernel(const PlanData& plan, std::size_t waiting, BatchWorkspace& w, int iterations);

// The Newton settings of the refinement's lanes near the curve (rational_newton): kNewtonSettings,
// and on the formula path a larger last step (kFormulaNewtonFinalStep) and a first distance beyond
// which a lane is left to nearest_newton (refine_grouped in fast_path.cpp says why).
kernels::NewtonSettings on_curve_newton_settings(bool formula);

// Whether the full kernel's results for lane l may decide it with its gap (decide_with_gap).
inline bool gap_decides(const BatchWorkspace& w, std::size_t l) {
  return w.defect[l] <= kFastPathMaxDefect && w.estimate[kBatchLanes + l] >= kFastPathMinGap;
}

}  // namespace bezinv::detail
