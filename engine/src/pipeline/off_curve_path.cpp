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
namespace {

// Starts for Newton towards the nearest points of (u[l], v[l]), l < count: the nearest of every
// `stride`-th sample of the curve (plan.nearest_samples), moved to the vertex of the parabola
// through the squared distances of it and its two neighbours (kept within one spacing of it).
// Sample by sample over all lanes at once, so that the inner loop vectorizes; the first of equally
// near samples is kept, as a search point by point would.
void nearest_samples(const PlanData& plan, const double* u, const double* v, std::size_t count, int stride, double* t) {
  const double* p = plan.nearest_samples.data();
  const int last = static_cast<int>(plan.nearest_samples.size() / 2) - 1;
  std::array<double, kBatchLanes> best, at;
  best.fill(std::numeric_limits<double>::infinity());
  at.fill(0.0);
  for (int k = 0; k <= last; k += stride) {
    const double x = p[2 * k], y = p[2 * k + 1], sample = k;
    for (std::size_t l = 0; l < count; ++l) {
      // (Both selects branch-free, so that GCC vectorizes: at[l] and the sample are whole numbers,
      // exact in the sum.)
      const double dx = x - u[l], dy = y - v[l], d2 = dx * dx + dy * dy, nearest = best[l], a = at[l];
      at[l] = a + (d2 < nearest) * (sample - a);
      best[l] = d2 < nearest ? d2 : nearest;
    }
  }
  const auto distance2 = [&](int k, std::size_t l) {
    const double dx = p[2 * k] - u[l], dy = p[2 * k + 1] - v[l];
    return dx * dx + dy * dy;
  };
  for (std::size_t l = 0; l < count; ++l) {
    const int k = static_cast<int>(at[l]);
    t[l] = static_cast<double>(k) / last;
    if (k >= stride && k + stride <= last) {
      const double before = distance2(k - stride, l), after = distance2(k + stride, l);
      const double curvature = before - 2 * best[l] + after;
      if (curvature > 0) t[l] += std::clamp(0.5 * (before - after) / curvature, -1.0, 1.0) * stride / last;
    }
  }
}

// BM_KernelRationalNewton (bench/kernels_bench.cpp), off-curve starts, Horner's over de
// Casteljau's: 0.84 at degree 3, 0.96-0.99 at 4, 1.10 at 5 and 1.47 at 8 (AVX-512), 1.64 at 5
// and 1.95 at 8 (AVX2).
constexpr int kHornerNewtonMinDegree = 5;

}  // namespace

void off_curve_path(const PlanData& plan, const InvertOptions& options, std::size_t count, BatchWorkspace& w,
                    PointResult* results, StageClock& clock) {
  // Points on the curve have all left the batch by now (the common case): nothing to do.
  std::uint8_t any_active = 0;
  for (std::size_t l = 0; l < count; ++l) any_active |= w.active[l];
  if (!any_active) return clock.lap(&StageSeconds::off_curve);
  const bool projection = projects_off_curve(plan, options);
  if (projection) projection_path(plan, options, count, w, results);

  const double radius = off_curve_radius(normalized_tolerance(plan, options));

  // 1. A start per lane, compacted: where the fast path's refinement ended on the segment (a
  //    local minimum of the distance, often the nearest; its t and distance are
  //    refine_parameter's already), else near the nearest sample (those lanes after, for Newton).
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
  nearest_samples(plan, u.data() + newton_from, v.data() + newton_from, newton, kNearestSamplesPerDegree / 4,
                  t.data() + newton_from);

  // 2. Newton from the starts, lane-batched: refine_parameter's steps, on jets by Horner's rule
  //    from degree kHornerNewtonMinDegree on (O(n) where its de Casteljau is O(n^2); below, de
  //    Casteljau written out in registers is the faster). Their bits need not be the scalar
  //    code's: the answer is what the proofs below make of it.
  if (m > newton_from) {
    const kernels::RationalCurve curve = kernel_curve(plan, plan.degree >= kHornerNewtonMinDegree);
    kernels::active_implementation().rational_newton(curve, kNewtonSettings, m - newton_from, u.data() + newton_from,
                                                     v.data() + newton_from, t.data() + newton_from,
                                                     distance.data() + newton_from);
  }

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
    PointResult& r = results[l];
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
