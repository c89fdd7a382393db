#include "space/invert_space.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <mutex>
#include <vector>

#include "pipeline/schedule.hpp"
#include "space/space_curve.hpp"

namespace bezinv::detail {

void invert_space_curve(const PlanData& plan, std::span<const Point> points, std::span<const double> z,
                        std::span<PointResult> results, const InvertOptions& options, StageSeconds* stages) {
  const SpaceData& space = *plan.space;
  // The plane engine at the same tolerance in input units (relative to the space curve's box).
  // Its rows are checked in space, so an off_curve row is the nearest point's there.
  InvertOptions plane = options;
  plane.off_curve = OffCurve::nearest;
  plane.threads = 1;  // each block on the thread that projects and checks it
  if (plan.diagonal > 0 && std::isfinite(plan.diagonal) && std::isfinite(space.diagonal))
    plane.relative_tolerance = options.relative_tolerance * (space.diagonal / plan.diagonal);
  const double tolerance = std::max(options.relative_tolerance * (space.diagonal * space.inverse_scale),
                                    space.normalized_resolution);
  // Blocks of points, each projected, inverted in the plane and checked in space by one thread, so
  // that its points and results stay in cache between the three steps.
  constexpr std::size_t kBlock = 4096;
  const std::size_t count = points.size(), blocks = (count + kBlock - 1) / kBlock;
  std::mutex clock_mutex;
  for_each_range(
      blocks, options,
      [&](std::size_t first_block, std::size_t last_block) {
        thread_local std::vector<Point> projected;
        projected.resize(kBlock);
        StageSeconds local;
        double space_seconds = 0;
        for (std::size_t block = first_block; block < last_block; ++block) {
          const std::size_t begin = block * kBlock, end = std::min(count, begin + kBlock), size = end - begin;
          auto start = std::chrono::steady_clock::now();
          // 1. u = a . (P - c), v = b . (P - c) (NaN where a coordinate is not finite: the plane
          //    engine answers those invalid_input).
          for (std::size_t i = begin; i < end; ++i) {
            const double p[3] = {points[i].x, points[i].y, z[i]};
            Point& q = projected[i - begin];
            if (!(std::isfinite(p[0]) && std::isfinite(p[1]) && std::isfinite(p[2]))) {
              q = {PointResult::nan, PointResult::nan};
              continue;
            }
            q = {0, 0};
            for (int k = 0; k < 3; ++k) {
              q.x += space.a[k] * (p[k] - space.centre[k]);
              q.y += space.b[k] * (p[k] - space.centre[k]);
            }
          }
          if (stages) space_seconds += std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
          // 2. The plane engine.
          invert_curve(plan, std::span<const Point>(projected.data(), size), results.subspan(begin, size), plane,
                       stages ? &local : nullptr);
          // 3. Every answer in space.
          start = std::chrono::steady_clock::now();
          for (std::size_t i = begin; i < end; ++i)
            space_answer(space, space_normalize(space, points[i].x, points[i].y, z[i]), tolerance, options, results[i]);
          if (stages) space_seconds += std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
        }
        if (!stages) return;
        const std::lock_guard<std::mutex> lock(clock_mutex);
        stages->form_b += local.form_b; stages->kernel += local.kernel; stages->read_out += local.read_out;
        stages->refine += local.refine; stages->off_curve += local.off_curve; stages->decide += local.decide;
        stages->space += space_seconds;
      },
      1);
}

}  // namespace bezinv::detail
