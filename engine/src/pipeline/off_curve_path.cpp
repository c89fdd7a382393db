#include "pipeline/off_curve_path.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>

#include "bezinv/kernels/batch.hpp"
#include "bezinv/tolerances.hpp"
#include "extension.hpp"
#include "pipeline/candidate.hpp"
#include "pipeline/projection.hpp"
#include "refine.hpp"
#include "stationary_points.hpp"

namespace bezinv::detail {

void off_curve_path(const PlanData& plan, const InvertOptions& options, std::size_t count, BatchWorkspace& w,
                    LaneRows rows, StageClock& clock) {
  // Points on the curve have all left the batch by now (the common case): nothing to do.
  std::uint8_t any_active = 0;
  for (std::size_t l = 0; l < count; ++l) any_active |= w.active[l];
  if (!any_active) return clock.lap(&StageSeconds::off_curve);
  const bool projection = projects_off_curve(plan, options);
  if (projection) projection_path(plan, options, count, w, rows);

  const double radius = off_curve_radius(normalized_tolerance(plan, options));

  // 1. A start per lane, compacted: where the fast path's refinement ended on the segment (a
  //    local minimum of the distance, often the nearest; its t and distance are the Newton
  //    kernels' already, refine_grouped), else near the nearest sample (those lanes after, for
  //    Newton).
  std::array<std::uint8_t, kBatchLanes> lane_of, newton_lane_of;
  std::array<double, kBatchLanes> u, v, t, distance;
  std::size_t m = 0, newton = 0;
  for (std::size_t l = 0; l < count; ++l) {
    if (!w.active[l] || w.off_curve_tried[l] ||
        !(std::max(std::abs(w.u[l]), std::abs(w.v[l])) <= kOffCurvePathMaxCoordinate))
      continue;
    w.off_curve_tried[l] = 1;
    if (w.t_refined[l] >= 0.0 && w.t_refined[l] <= 1.0 && std::isfinite(w.distance[l])) {
      lane_of[m] = static_cast<std::uint8_t>(l);
      u[m] = w.u[l], v[m] = w.v[l], t[m] = w.t_refined[l], distance[m] = w.distance[l];
      ++m;
    } else {
      newton_lane_of[newton++] = static_cast<std::uint8_t>(l);
    }
  }
  const std::size_t newton_from = m;
  for (std::size_t k = 0; k < newton; ++k) {
    const std::size_t l = newton_lane_of[k];
    lane_of[m] = static_cast<std::uint8_t>(l);
    u[m] = w.u[l], v[m] = w.v[l];
    ++m;
  }
  if (m == 0) return clock.lap(&StageSeconds::off_curve);
  // The others' starts: the nearest of every fourth of the plan's samples, moved to the vertex of
  // the parabola through the squared distances there (nearest_sample).
  const kernels::Implementation& kernel = kernels::active_implementation();
  if (newton > 0)
    kernel.nearest_sample(plan.nearest_samples.data(), static_cast<int>(plan.nearest_samples.size() / 2) - 1,
                          kNearestSamplesPerDegree / 4, newton, u.data() + newton_from, v.data() + newton_from,
                          t.data() + newton_from);

  // 2. Newton from the starts, lane-batched (nearest_newton: Horner's jets, fused, the descent
  //    test in the next jet). Its bits need not be the scalar refinement's: the answer is what
  //    the proofs below make of it.
  if (m > newton_from)
    kernel.nearest_newton(kernel_curve(plan, /*horner=*/true), kNearestNewtonSettings, m - newton_from,
                          u.data() + newton_from, v.data() + newton_from, t.data() + newton_from,
                          distance.data() + newton_from);

  // 3. Per lane, the proofs: the refined start as the certified search's hint (usually the
  //    nearest point already: the isolation certificate proves it at once near one branch, the
  //    search over the pieces elsewhere), then the extension.
  const ExtensionGrid* grid = extension_grid(plan, m);
  std::array<std::uint8_t, kBatchLanes> stationary;
  stationary_point_lanes(plan, m, u.data(), v.data(), t.data(), distance.data(), stationary.data());
  for (std::size_t k = 0; k < m; ++k) {
    const NearestOnSegment nearest = certified_nearest_on_segment(plan, u[k], v[k], t[k], distance[k], stationary[k]);
    if (!nearest.certified || !(nearest.distance > radius) || !extension_clear(plan, u[k], v[k], radius, grid)) continue;
    const std::size_t l = lane_of[k];
    w.active[l] = 0;
    PointResult& r = rows[l];
    r.t = nearest.t;
    r.residual = nearest.distance * plan.scale;
    r.status = Status::off_curve;
    r.path = Path::nearest;
    r.sigma_min = r.sigma_next = PointResult::nan;
    if (projection) project_off_curve(plan, u[k], v[k], radius, r);
  }
  clock.lap(&StageSeconds::off_curve);
}

}  // namespace bezinv::detail
