#include "pipeline/formula_first.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include "bezinv/kernels/batch.hpp"
#include "isolation.hpp"
#include "pipeline/candidate.hpp"
#include "pipeline/decide.hpp"
#include "pipeline/fast_path.hpp"
#include "pipeline/form_b.hpp"
#include "pipeline/formula_path.hpp"
#include "refine.hpp"

namespace bezinv::detail {

bool takes_formula_first(const PlanData& plan, const InvertOptions& options) {
  // (Without the isolation certificate no lane could be answered here.)
  return plan.usable && !plan.isolation_monotone.empty() && takes_formula_path(plan, options);
}

namespace {

// The plan's normalization as the formula_newton kernel makes it (PlanData::normalize's bits).
kernels::PointFrame point_frame(const PlanData& plan) {
  return {.scale = plan.inverse_scale,
          .centre_x = plan.centre[0] * plan.inverse_scale,
          .centre_y = plan.centre[1] * plan.inverse_scale,
          .cos = plan.cos_rotation,
          .sin = plan.sin_rotation};
}

// Whether a conic's or cubic's formula path, all in the formula_newton kernel.
bool fused(const PlanData& plan) {
  return plan.degree >= kernels::kFormulaNewtonMinDegree && plan.degree <= kernels::kFormulaNewtonMaxDegree;
}

// w.u, w.v (the point normalized), w.t_algebraic (N / M), w.t_refined and w.distance of every
// lane (u, v and N / M only with `keep` where fused), t_refined NaN where the lane is not answered
// here; in `left` the lanes not answered, and in `leaves` those whose N / M is in [0, 1] and whose
// first rational_newton iteration from it leaves them (FormulaLeft): by the formula_newton kernel
// for a conic or a cubic, else by the kernels it fuses, one after the other (the formula path of a
// curve's own formula, degree 4 and up: its N / M and the Newton iterations cost more than the
// passes between them). Returns how many lanes it answers.
std::size_t settle_lanes(const PlanData& plan, const Point* points, std::size_t count, double tolerance,
                         BatchWorkspace& w, StageClock& clock, LaneSet& left, LaneSet& leaves, bool keep) {
  const kernels::Implementation& kernel = kernels::active_implementation();
  const kernels::PlaneFormula formula = plane_formula(fast_path_formula(plan));
  const kernels::NewtonSettings settings = on_curve_newton_settings(/*formula=*/true);
  if (fused(plan)) {
    static_assert(sizeof(Point) == 2 * sizeof(double));
    const kernels::FormulaStart on_the_way{w.u.data(), w.v.data(), w.t_algebraic.data()};
    const kernels::FormulaLanes lanes{left.words(), leaves.words()};
    const std::size_t settled_count = kernel.formula_newton(
        formula, kernel_curve(plan), settings, point_frame(plan), far_boxes_certificate(plan, tolerance), tolerance,
        count, &points[0].x, w.t_refined.data(), w.distance.data(), keep ? &on_the_way : nullptr, &lanes);
    clock.lap(&StageSeconds::kernel);
    return settled_count;
  }
  normalize_batch(plan, points, count, w);
  clock.lap(&StageSeconds::form_b);
  // N / M is NaN where a coordinate is not finite (so a lane admit() would refuse never gets a
  // t), near a base point and far out; the Newton kernel leaves a NaN t (and a t off [0, 1])
  // unsettled, distance NaN, and a lane off the curve with distance +inf: none is answered here.
  kernel.formula_parameter(formula, count, w.u.data(), w.v.data(), w.t_algebraic.data());
  std::copy_n(w.t_algebraic.begin(), count, w.t_refined.begin());
  clock.lap(&StageSeconds::kernel);
  kernel.rational_newton(kernel_curve(plan), settings, count, w.u.data(), w.v.data(), w.t_refined.data(),
                         w.distance.data());
  clock.lap(&StageSeconds::refine);
  isolated_by_far_boxes(plan, w.t_refined.data(), w.distance.data(), tolerance, count, w.certified.data());
  leaves = LaneSet::where(count, [&](std::size_t l) {
    const double t = w.t_algebraic[l];
    return (w.distance[l] == std::numeric_limits<double>::infinity()) & (t >= 0.0) & (t <= 1.0);
  });
  left = LaneSet::where(count, [&](std::size_t l) { return !(w.certified[l] && w.distance[l] <= tolerance); });
  left.for_each([&](std::size_t l) { w.t_refined[l] = PointResult::nan; });
  return count - left.size();
}

}  // namespace

FormulaLeft formula_first(const PlanData& plan, const Point* points, PointResult* results, std::size_t count,
                          const InvertOptions& options, BatchWorkspace& w, StageClock& clock, bool keep) {
  const double tolerance = normalized_tolerance(plan, options);
  FormulaLeft left;
  LaneSet not_settled;
  const std::size_t settled_count =
      settle_lanes(plan, points, count, tolerance, w, clock, not_settled, left.first_iteration_leaves, keep);
  left.given = keep || !fused(plan);
  auto answer = [&](std::size_t l) {
    PointResult& r = results[l];
    r = PointResult{};
    answer_fast(plan, w.t_refined[l], w.distance[l], PointResult::nan, PointResult::nan, r, Path::formula);
  };
  // A batch on the curve, every lane settled: one loop.
  if (settled_count == count) {
    for (std::size_t l = 0; l < count; ++l) answer(l);
    clock.lap(&StageSeconds::decide);
    return left;
  }
  // Else by the sets of lanes settle_lanes gives: in a batch of both kinds a branch per lane would
  // be mispredicted at every change of kind.
  LaneSet::first(count).without(not_settled).for_each(answer);
  not_settled.for_each([&](std::size_t l) { left.lane_of[left.count++] = static_cast<std::uint8_t>(l); });
  clock.lap(&StageSeconds::decide);
  return left;
}

LaneSet formula_first_left(LaneSet first_iteration_leaves, std::size_t count, const BatchWorkspace& w) {
  if (first_iteration_leaves.empty()) return {};
  // (Their N / M is in [0, 1]: from_formula, where the lane is active.)
  return first_iteration_leaves.both(LaneSet::of_flags(count, w.from_formula.data()));
}

}  // namespace bezinv::detail
