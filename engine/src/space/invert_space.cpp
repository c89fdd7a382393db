#include "space/invert_space.hpp"

#include <algorithm>
#include <chrono>
#include <functional>
#include <mutex>
#include <cmath>
#include <vector>

#include "pipeline/schedule.hpp"
#include "space/space_curve.hpp"

namespace bezinv::detail {

void invert_space_curve(const PlanData& plan, std::span<const Point> points, std::span<const double> z,
                        std::span<PointResult> results, const InvertOptions& options, StageSeconds* stages) {
  const SpaceData& space = *plan.space;
  const std::size_t count = points.size();
  // Seconds of work of steps 1 and 3, summed over the ranges (threads) that did them.
  std::mutex clock_mutex;
  auto timed = [&](const std::function<void(std::size_t, std::size_t)>& body) {
    return [&, body](std::size_t begin, std::size_t end) {
      if (!stages) return body(begin, end);
      const auto start = std::chrono::steady_clock::now();
      body(begin, end);
      const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
      const std::lock_guard<std::mutex> lock(clock_mutex);
      stages->space += seconds;
    };
  };
  // 1. The projected points, u = a . (P - c), v = b . (P - c) (NaN where a coordinate is not
  //    finite: the plane engine answers those invalid_input).
  std::vector<Point> projected(count);
  for_each_range(count, options, timed([&](std::size_t begin, std::size_t end) {
    for (std::size_t i = begin; i < end; ++i) {
      const double p[3] = {points[i].x, points[i].y, z[i]};
      if (!(std::isfinite(p[0]) && std::isfinite(p[1]) && std::isfinite(p[2]))) {
        projected[i] = {PointResult::nan, PointResult::nan};
        continue;
      }
      double u = 0, v = 0;
      for (int k = 0; k < 3; ++k) {
        u += space.a[k] * (p[k] - space.centre[k]);
        v += space.b[k] * (p[k] - space.centre[k]);
      }
      projected[i] = {u, v};
    }
  }));
  // 2. The plane engine at the same tolerance in input units (relative to the space curve's box).
  //    Projected rows are checked in space, so an off_curve row is the nearest point's there.
  InvertOptions plane = options;
  plane.off_curve = OffCurve::nearest;
  if (plan.diagonal > 0 && std::isfinite(plan.diagonal) && std::isfinite(space.diagonal))
    plane.relative_tolerance = options.relative_tolerance * (space.diagonal / plan.diagonal);
  invert_curve(plan, projected, results, plane, stages);
  // 3. Every answer in space.
  const double tolerance = std::max(options.relative_tolerance * (space.diagonal * space.inverse_scale),
                                    space.normalized_resolution);
  for_each_range(count, options, timed([&](std::size_t begin, std::size_t end) {
    for (std::size_t i = begin; i < end; ++i)
      space_answer(space, space_normalize(space, points[i].x, points[i].y, z[i]), tolerance, options, results[i]);
  }));
}

}  // namespace bezinv::detail
