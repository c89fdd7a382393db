#include "pipeline/formula_first.hpp"

#include "bezinv/kernels/batch.hpp"
#include "isolation.hpp"
#include "pipeline/candidate.hpp"
#include "pipeline/decide.hpp"
#include "pipeline/fast_path.hpp"
#include "pipeline/formula_path.hpp"
#include "refine.hpp"

namespace bezinv::detail {

bool takes_formula_first(const PlanData& plan, const InvertOptions& options) {
  return plan.usable && takes_formula_path(plan, options);
}

std::size_t formula_first(const PlanData& plan, const Point* points, PointResult* results, std::size_t count,
                          const InvertOptions& options, BatchWorkspace& w, StageClock& clock,
                          std::array<std::uint8_t, kBatchLanes>& left_of) {
  const kernels::Implementation& kernel = kernels::active_implementation();
  const double tolerance = normalized_tolerance(plan, options);
  for (std::size_t l = 0; l < count; ++l) {  // the arithmetic alone, so that it vectorizes
    const auto uv = plan.normalize(points[l].x, points[l].y);
    w.u[l] = uv[0];
    w.v[l] = uv[1];
  }
  clock.lap(&StageSeconds::form_b);
  // N / M is NaN where a coordinate is not finite (so a lane admit() would refuse never gets a
  // t), near a base point and far out; the Newton kernel leaves a NaN t (and a t off [0, 1])
  // unsettled, distance NaN, and a lane off the curve with distance +inf: none is answered here.
  kernel.formula_parameter(plane_formula(fast_path_formula(plan)), count, w.u.data(), w.v.data(),
                           w.t_algebraic.data());
  clock.lap(&StageSeconds::kernel);
  std::copy_n(w.t_algebraic.begin(), count, w.t_refined.begin());
  clock.lap(&StageSeconds::read_out);
  kernel.rational_newton(kernel_curve(plan), on_curve_newton_settings(/*formula=*/true), count, w.u.data(),
                         w.v.data(), w.t_refined.data(), w.distance.data());
  clock.lap(&StageSeconds::refine);
  isolated_by_far_boxes(plan, w.t_refined.data(), w.distance.data(), tolerance, count, w.certified.data());
  std::size_t left = 0;
  for (std::size_t l = 0; l < count; ++l) {
    if (w.certified[l] && w.distance[l] <= tolerance) {
      PointResult& r = results[l];
      r = PointResult{};
      answer_fast(plan, w.t_refined[l], w.distance[l], PointResult::nan, PointResult::nan, r, Path::formula);
    } else {
      left_of[left++] = static_cast<std::uint8_t>(l);
    }
  }
  clock.lap(&StageSeconds::decide);
  return left;
}

}  // namespace bezinv::detail
