#include "pipeline/formula_first.hpp"

#include <cmath>

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

// w.t_refined and w.distance of every lane, distance NaN where the lane is not answered here:
// by the formula_newton kernel for a conic or a cubic, else by the kernels it fuses, one after
// the other (the formula path of a curve's own formula, degree 4 and up: its N / M and the Newton
// iterations cost more than the passes between them).
void settle_lanes(const PlanData& plan, const Point* points, std::size_t count, double tolerance, BatchWorkspace& w,
                  StageClock& clock) {
  const kernels::Implementation& kernel = kernels::active_implementation();
  const kernels::PlaneFormula formula = plane_formula(fast_path_formula(plan));
  const kernels::NewtonSettings settings = on_curve_newton_settings(/*formula=*/true);
  if (plan.degree >= kernels::kFormulaNewtonMinDegree && plan.degree <= kernels::kFormulaNewtonMaxDegree) {
    static_assert(sizeof(Point) == 2 * sizeof(double));
    kernel.formula_newton(formula, kernel_curve(plan), settings, point_frame(plan),
                          far_boxes_certificate(plan, tolerance), tolerance, count, &points[0].x, w.t_refined.data(),
                          w.distance.data());
    clock.lap(&StageSeconds::kernel);
    return;
  }
  normalize_batch(plan, points, count, w);
  clock.lap(&StageSeconds::form_b);
  // N / M is NaN where a coordinate is not finite (so a lane admit() would refuse never gets a
  // t), near a base point and far out; the Newton kernel leaves a NaN t (and a t off [0, 1])
  // unsettled, distance NaN, and a lane off the curve with distance +inf: none is answered here.
  kernel.formula_parameter(formula, count, w.u.data(), w.v.data(), w.t_refined.data());
  clock.lap(&StageSeconds::kernel);
  kernel.rational_newton(kernel_curve(plan), settings, count, w.u.data(), w.v.data(), w.t_refined.data(),
                         w.distance.data());
  clock.lap(&StageSeconds::refine);
  isolated_by_far_boxes(plan, w.t_refined.data(), w.distance.data(), tolerance, count, w.certified.data());
  for (std::size_t l = 0; l < count; ++l)
    if (!(w.certified[l] && w.distance[l] <= tolerance)) w.distance[l] = PointResult::nan;
}

}  // namespace

std::size_t formula_first(const PlanData& plan, const Point* points, PointResult* results, std::size_t count,
                          const InvertOptions& options, BatchWorkspace& w, StageClock& clock,
                          std::array<std::uint8_t, kBatchLanes>& left_of) {
  settle_lanes(plan, points, count, normalized_tolerance(plan, options), w, clock);
  std::size_t left = 0;
  for (std::size_t l = 0; l < count; ++l) {
    if (std::isnan(w.distance[l])) {
      left_of[left++] = static_cast<std::uint8_t>(l);
      continue;
    }
    PointResult& r = results[l];
    r = PointResult{};
    answer_fast(plan, w.t_refined[l], w.distance[l], PointResult::nan, PointResult::nan, r, Path::formula);
  }
  clock.lap(&StageSeconds::decide);
  return left;
}

}  // namespace bezinv::detail
