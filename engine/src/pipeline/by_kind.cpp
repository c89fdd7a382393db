#include "pipeline/by_kind.hpp"

#include <bit>
#include <cstdint>
#include <limits>

#include "isolation.hpp"
#include "pipeline/formula_path.hpp"

namespace bezinv::detail {

SeedQueue& seed_queue() {
  thread_local SeedQueue queue;
  return queue;
}

FarQueue& far_queue() {
  thread_local FarQueue queue;
  return queue;
}

bool sets_far_lanes_aside(const PlanData& plan, const InvertOptions& options) {
  return takes_fast_path(plan, options) && plan.degree >= 3 && !takes_formula_path(plan, options);
}

FarLanes far_lanes(const PlanData& plan, double tolerance, std::size_t count, const BatchWorkspace& w) {
  static_assert(kBatchLanes == 64, "a batch's lanes as the bits of one word");
  if (!skips_far_seeds(plan, tolerance)) return {};
  FarLanes far{.known = true};
  for (std::size_t l = 0; l < count; ++l)
    far.bits |= static_cast<std::uint64_t>(segment_far(plan, w.u[l], w.v[l])) << l;
  return far;
}

bool set_aside_far(FarLanes far_from_segment, const Point* points, PointResult* results, std::size_t count,
                   const BatchWorkspace& w) {
  if (!far_from_segment.known) return false;
  std::uint64_t active = 0;
  for (std::size_t l = 0; l < count; ++l) active |= static_cast<std::uint64_t>(w.active[l]) << l;
  std::uint64_t far = far_from_segment.bits & active, near = active & ~far_from_segment.bits;
  if (far == 0 || near == 0) return false;
  // The set bits alone, in order, without a branch per lane (far and near often alternate).
  FarQueue& far_lanes = far_queue();
  std::size_t k = far_lanes.size;
  for (; far != 0; far &= far - 1, ++k) {
    const std::size_t l = static_cast<std::size_t>(std::countr_zero(far));
    far_lanes.u[k] = w.u[l], far_lanes.v[k] = w.v[l], far_lanes.target[k] = &results[l];
  }
  far_lanes.size = k;
  SeedQueue& seeds = seed_queue();
  k = seeds.size;
  for (; near != 0; near &= near - 1, ++k) {
    const std::size_t l = static_cast<std::size_t>(std::countr_zero(near));
    seeds.u[k] = w.u[l], seeds.v[k] = w.v[l], seeds.point[k] = points[l], seeds.target[k] = &results[l];
  }
  seeds.size = k;
  return true;
}

void take_from_seed_queue(std::size_t m, BatchWorkspace& w, std::array<Point, kBatchLanes>& points,
                          std::array<PointResult*, kBatchLanes>& rows) {
  SeedQueue& queue = seed_queue();
  for (std::size_t k = 0; k < m; ++k) {
    w.u[k] = queue.u[k], w.v[k] = queue.v[k], w.active[k] = 1;
    points[k] = queue.point[k];
    rows[k] = queue.target[k];
  }
  const std::size_t rest = queue.size - m;
  for (std::size_t k = 0; k < rest; ++k) {
    queue.u[k] = queue.u[m + k], queue.v[k] = queue.v[m + k];
    queue.point[k] = queue.point[m + k];
    queue.target[k] = queue.target[m + k];
  }
  queue.size = rest;
}

void take_from_far_queue(std::size_t m, BatchWorkspace& w, std::array<PointResult*, kBatchLanes>& rows) {
  FarQueue& queue = far_queue();
  const double inf = std::numeric_limits<double>::infinity();
  for (std::size_t k = 0; k < m; ++k) {
    w.u[k] = queue.u[k], w.v[k] = queue.v[k], w.active[k] = 1;
    w.t_algebraic[k] = PointResult::nan, w.defect[k] = w.estimate[k] = inf;
    rows[k] = queue.target[k];
  }
  const std::size_t rest = queue.size - m;
  for (std::size_t k = 0; k < rest; ++k) {
    queue.u[k] = queue.u[m + k], queue.v[k] = queue.v[m + k];
    queue.target[k] = queue.target[m + k];
  }
  queue.size = rest;
}

}  // namespace bezinv::detail
