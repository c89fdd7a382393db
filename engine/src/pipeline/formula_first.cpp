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

// w.u, w.v, w.t_algebraic, w.t_refined and w.distance of every lane, distance NaN where the lane
// is not answered here (+inf where the first Newton iteration leaves it): by the formula_newton
// kernel for a conic or a cubic, else by the kernels it fuses, one after the other (the formula
// path of a curve's own formula, degree 4 and up: its N / M and the Newton iterations cost more
// than the passes between them).
void settle_lanes(const PlanData& plan, const Point* points, std::size_t count, double tolerance, BatchWorkspace& w,
                  StageClock& clock) {
  const kernels::Implementation& kernel = kernels::active_implementation();
  const kernels::PlaneFormula formula = plane_formula(fast_path_formula(plan));
  const kernels::NewtonSettings settings = on_curve_newton_settings(/*formula=*/true);
  if (plan.degree >= kernels::kFormulaNewtonMinDegree && plan.degree <= kernels::kFormulaNewtonMaxDegree) {
    static_assert(sizeof(Point) == 2 * sizeof(double));
    kernel.formula_newton(formula, kernel_curve(plan), settings, point_frame(plan),
                          far_boxes_certificate(plan, tolerance), tolerance, count, &points[0].x,
                          {.u = w.u.data(),
                           .v = w.v.data(),
                           .t_formula = w.t_algebraic.data(),
                           .t = w.t_refined.data(),
                           .distance = w.distance.data()});
    clock.lap(&StageSeconds::kernel);
    return;
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
  constexpr double kLeft = std::numeric_limits<double>::infinity();  // left by the first iteration
  for (std::size_t l = 0; l < count; ++l)
    if (!(w.certified[l] && w.distance[l] <= tolerance) && w.distance[l] != kLeft) w.distance[l] = PointResult::nan;
}

}  // namespace

FormulaLeft formula_first(const PlanData& plan, const Point* points, PointResult* results, std::size_t count,
                          const InvertOptions& options, BatchWorkspace& w, StageClock& clock) {
  const double tolerance = normalized_tolerance(plan, options);
  settle_lanes(plan, points, count, tolerance, w, clock);
  // The lanes it leaves (NaN or +inf) and those it settles, without a branch per lane: in a batch
  // of both kinds, on the curve and off it, that branch would be mispredicted at every change.
  FormulaLeft left;
  LaneSet settled;
  std::size_t m = 0;
  for (std::size_t i = 0; 64 * i < count; ++i) {
    std::uint64_t settled_word = 0, newton_word = 0;  // in registers, stored once
    const std::size_t end = std::min(count, 64 * (i + 1));
    for (std::size_t l = 64 * i; l < end; ++l) {
      const double distance = w.distance[l];
      const bool leaves = !(distance <= tolerance);
      left.lane_of[m] = static_cast<std::uint8_t>(l);  // kept where it leaves
      m += leaves;
      settled_word |= std::uint64_t{!leaves} << (l % 64);
      newton_word |= std::uint64_t{distance == std::numeric_limits<double>::infinity()} << (l % 64);
    }
    settled.set_word(i, settled_word);
    left.newton_left.set_word(i, newton_word);
  }
  left.count = m;
  settled.for_each([&](std::size_t l) {
    PointResult& r = results[l];
    r = PointResult{};
    answer_fast(plan, w.t_refined[l], w.distance[l], PointResult::nan, PointResult::nan, r, Path::formula);
  });
  clock.lap(&StageSeconds::decide);
  return left;
}

}  // namespace bezinv::detail
