#pragma once
// Where a row's status is decided. Every status and path a PointResult gets is set by one of the
// functions below, in the order a point meets them:
//   admit             stage 1: invalid_input (a non-finite coordinate), failed (an unusable
//                     curve), or off_curve for a point too far to form B for (far_point.hpp)
//   answer_fast       the fast path's ok (certified on the segment)
//   decide_with_gap   the fast path with the kernel's sigma_{n-1} estimate: answered here, or
//                     left to the SVD path
//   off_curve_path    off_curve by distance alone, without the SVD (off_curve_path.hpp)
//   decide            the SVD path: every status, from every candidate parameter
// The rules are in docs/accuracy-model.md (statuses) and docs/fast-path.md (when the fast path
// may answer: only where the SVD path would give the same answer).
#include <cstddef>

#include "bezinv/invert.hpp"
#include "plan_data.hpp"
#include "pipeline/candidate.hpp"
#include "pipeline/workspace.hpp"

namespace bezinv::detail {

// Stage 1 for one point, (u, v) its normalized coordinates: true when the point goes on through
// the pipeline; otherwise r holds its answer.
bool admit(const PlanData& plan, const Point& point, double u, double v, PointResult& r);

// The fast path's answer: status ok, path bezout_lu (or formula: the start was the formula's), the
// sigma columns from the kernel's estimates (NaN on the formula path).
// (Inline: formula_first writes a whole batch of them in one loop.)
inline void answer_fast(const PlanData& plan, double t, double distance, double sigma_min, double sigma_next,
                        PointResult& r, Path path = Path::bezout_lu) {
  r.t = t;
  r.residual = distance * plan.scale;
  r.status = Status::ok;
  r.path = path;
  r.sigma_min = sigma_min;
  r.sigma_next = sigma_next;
}

// The fast path's decision for lane l, refined to c, with the kernel's gap: answered here (ok)
// where the gap is above kFastPathGapRatio or the isolation certificate settles it, else left
// active (off the segment: to the off-curve path; else to the SVD path). `asked`: the isolation
// certificate was asked already (the gap pass) and refused the lane.
void decide_with_gap(const PlanData& plan, BatchWorkspace& w, std::size_t l, const Candidate& c,
                     double tolerance, bool asked, PointResult& result);

// The SVD path's decision for one point: `main` is the refined candidate from the null vector;
// sigma (n values, decreasing) and V (singular vector k at V[k n + r]) are the point's SVD of B.
void decide(const PlanData& plan, double u0, double v0, const Candidate& main, const double* sigma,
            const double* V, const InvertOptions& options, PointResult& r);

}  // namespace bezinv::detail
