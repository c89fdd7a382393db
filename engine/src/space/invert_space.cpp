#include "space/invert_space.hpp"

#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <mutex>
#include <span>
#include <vector>

#include "bezinv/kernels/batch.hpp"
#include "pipeline/schedule.hpp"
#include "bezinv/tolerances.hpp"
#include "space/space_curve.hpp"

namespace bezinv::detail {
namespace {

// The answer to a finite point the plane engine could not take (its projection overflowed): the
// nearest point of the segment in space, by the search of space_answer where the normalized point
// is finite, else (it is farther than the largest double in the curve's own units too) from its
// direction, as the plane's answer_far_point: the nearest point to a stand-in on its ray from the
// centre at kFarStandIn, in coordinates scaled by a power of two so nothing overflows.
void answer_overflowing_point(const SpaceData& space, const std::array<double, 3>& given,
                              const std::array<double, 3>& normalized, double tolerance, PointResult& r) {
  r = PointResult{};
  r.status = Status::off_curve;
  if (std::isfinite(normalized[0]) && std::isfinite(normalized[1]) && std::isfinite(normalized[2])) {
    InvertOptions search;  // refine on: space_answer searches for the nearest point of an off_curve row
    space_answer(space, normalized, tolerance, search, r);
    return;
  }
  const double largest = std::max({std::abs(given[0]), std::abs(given[1]), std::abs(given[2])});
  const double centre = std::max({std::abs(space.centre[0]), std::abs(space.centre[1]), std::abs(space.centre[2]), 1.0});
  const int e = std::max(std::ilogb(largest), std::ilogb(centre));
  std::array<double, 3> direction;
  for (int k = 0; k < 3; ++k) direction[k] = std::ldexp(given[k], -e) - std::ldexp(space.centre[k], -e);
  const double length = std::hypot(direction[0], direction[1], direction[2]);
  for (double& d : direction) d *= kFarStandIn / length;
  r.path = Path::nearest;
  r.t = space_nearest(space, direction).t;
  // |P(t) - P0| in input units, halved first so the differences do not overflow.
  const auto p = space.curve.point3(r.t);
  r.residual = 2 * std::hypot(0.5 * p[0] - 0.5 * given[0], 0.5 * p[1] - 0.5 * given[1], 0.5 * p[2] - 0.5 * given[2]);
}

// Step 3 of invert_space_curve for one block: every plane answer checked in space.
//
// The common row -- ok in the plane, refined -- is checked lane by lane (Implementation::space_check:
// space_refine's first test, the same doubles, so the same answer). What that does not settle
// within the tolerance, and every other row, goes through space_answer one by one.
void check_in_space(const SpaceData& space, std::span<const Point> points, std::span<const double> z, double tolerance,
                    const InvertOptions& options, std::span<PointResult> results) {
  const std::size_t count = points.size();
  thread_local std::vector<double> t, x, y, zs, distance;
  thread_local std::vector<std::size_t> rows;
  t.clear(), x.clear(), y.clear(), zs.clear(), rows.clear();
  if (options.refine) {
    for (std::size_t i = 0; i < count; ++i) {
      if (results[i].status != Status::ok) continue;
      const std::array<double, 3> point = space_normalize(space, points[i].x, points[i].y, z[i]);
      rows.push_back(i);
      t.push_back(results[i].t), x.push_back(point[0]), y.push_back(point[1]), zs.push_back(point[2]);
    }
  }
  distance.resize(rows.size());
  if (!rows.empty())
    kernels::active_implementation().space_check(
        {space.degree, space.first_order_width == 8 ? 1 : 3, space.first_order_forward.data(),
         space.first_order_backward.data()},
        rows.size(), t.data(), x.data(), y.data(), zs.data(), distance.data());
  std::size_t next = 0;  // the next checked row
  for (std::size_t i = 0; i < count; ++i) {
    PointResult& r = results[i];
    if (next < rows.size() && rows[next] == i) {
      const double d = distance[next++];
      if (d <= tolerance) {  // space_answer's accept of space_refine's answer (t in [0, 1] stays)
        r.residual = d * space.scale;
        continue;
      }
    }
    const std::array<double, 3> point = space_normalize(space, points[i].x, points[i].y, z[i]);
    // A finite point whose projection overflowed (more than the largest double from the centre,
    // for a curve near the end of the double range) came back invalid_input from the plane
    // engine. It is not: it gets the nearest point of the segment in space, as a point the plane
    // puts off the curve does.
    if (r.status == Status::invalid_input && std::isfinite(points[i].x) && std::isfinite(points[i].y) &&
        std::isfinite(z[i])) {
      answer_overflowing_point(space, {points[i].x, points[i].y, z[i]}, point, tolerance, r);
      continue;
    }
    space_answer(space, point, tolerance, options, r);
  }
}

}  // namespace

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
          check_in_space(space, points.subspan(begin, size), z.subspan(begin, size), tolerance, options,
                         results.subspan(begin, size));
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
