#pragma once
// Where the time of an inversion goes (`bezinv profile`): the same inversion as bezinv/invert.hpp,
// timed stage by stage. The stages are the pipeline's (docs/README.md, "How a point flows").
#include <span>

#include "bezinv/invert.hpp"

namespace bezinv {

// Seconds of work spent in each stage of the pipeline, summed over threads.
struct StageSeconds {
  double form_b = 0;    // normalize the points, form B from the plan's matrices (below degree 8)
  double kernel = 0;    // null vectors or singular values and vectors of B (from degree 8 forming B too);
                        // a conic's or cubic's formula path whole (normalizing, N / M, Newton, the
                        // certificate: one kernel, formula_newton), its rows in decide
  double read_out = 0;  // algebraic t from the null vector
  double refine = 0;    // Newton to full precision, and the residual
  double off_curve = 0; // off-curve points answered by distance alone (nearest point, clearance)
  double decide = 0;    // status, and the rare paths (double point, Sylvester, nearest point)
  double space = 0;     // space curves: projecting the points, checking and refining each answer in space
};

// invert(plan, points, results, options), adding the time of each stage to `stages`. The answers
// are the same; the clocks cost a little time.
void invert(const InversionPlan& plan, std::span<const Point> points, std::span<PointResult> results,
            const InvertOptions& options, StageSeconds& stages);
// The same for a space curve's points.
void invert(const InversionPlan& plan, std::span<const Point3> points, std::span<PointResult> results,
            const InvertOptions& options, StageSeconds& stages);

}  // namespace bezinv
