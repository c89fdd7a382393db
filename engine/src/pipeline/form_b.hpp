#pragma once
// Stage 1: the points normalized, admitted (decide.hpp's admit) and their Bezout matrices formed,
// B = B0 - u0 Bx - v0 By (+ u0 v0 Bxy for separate denominators), lane by lane by a kernel.
#include <cstddef>

#include "bezinv/invert.hpp"
#include "plan_data.hpp"
#include "pipeline/workspace.hpp"

namespace bezinv::detail {

// The batch's points normalized into w.u, w.v (PlanData::normalize), in a loop of the arithmetic
// alone, so that it vectorizes.
void normalize_batch(const PlanData& plan, const Point* points, std::size_t count, BatchWorkspace& w);

// Admits the batch's points (decide.hpp's admit), normalized in w.u, w.v: w.active; a lane
// refused gets u = v = 0 and its answer in rows[l].
void admit_batch(const PlanData& plan, const Point* points, LaneRows rows, std::size_t count, BatchWorkspace& w);

// Normalizes and admits the batch's points into w (u, v, active); with `form`, also forms every
// active lane's B into w.B (lower triangle; an inactive lane gets the identity, so the kernels see
// only finite, harmless matrices). A lane whose B overflows is answered by answer_far_point.
void form_batch(const PlanData& plan, const Point* points, LaneRows rows, std::size_t count, bool form,
                BatchWorkspace& w);

// A lane whose Bezout matrix overflowed (poison[l] not 0: an entry is not finite) is a point too
// far to form B for: answered off_curve by answer_far_point, it leaves the pipeline.
void mark_overflowing_b(const PlanData& plan, const Point* points, const double* poison, std::size_t count,
                        BatchWorkspace& w, LaneRows rows);

// The kernels' Bxy: null for one denominator, where Bxy = Bez(W, W) = 0 and B is affine in (u, v),
// so that they skip the term and give bezout_at's bits, which skips it too.
inline const double* bilinear_coefficients(const PlanData& plan) {
  return plan.common_denominator ? nullptr : plan.Bxy.data();
}

// B of the points (u[k], v[k]), k < m, into lanes 0..m-1 of B (stride kBatchLanes), as stage 1
// forms it, for lanes gathered from a batch (the gap pass, the SVD path); their
// B did not overflow (such a lane left the pipeline when its B was first formed).
void form_compacted_b(const PlanData& plan, const double* u, const double* v, std::size_t m, double* B);

}  // namespace bezinv::detail
