#include "pipeline/by_kind.hpp"

#include <algorithm>
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

StagesQueue& stages_queue() {
  thread_local StagesQueue queue;
  return queue;
}

void queue_for_stages(const PlanData& plan, const Point* points, PointResult* rows, const FormulaLeft& left,
                      const BatchWorkspace& w) {
  StagesQueue& queue = stages_queue();
  const std::size_t first = queue.size, count = left.count;
  for (std::size_t k = 0; k < count; ++k) {
    const std::size_t l = left.lane_of[k], q = first + k;
    if (left.given) {
      queue.u[q] = w.u[l], queue.v[q] = w.v[l], queue.t[q] = w.t_algebraic[l];
    } else {  // (a lane or two of a batch on the curve, mostly)
      const auto uv = plan.normalize(points[l].x, points[l].y);
      queue.u[q] = uv[0], queue.v[q] = uv[1], queue.t[q] = formula_parameter(fast_path_formula(plan), uv[0], uv[1]);
    }
    queue.point[q] = points[l], queue.target[q] = &rows[l];
    queue.first_iteration_leaves[q] = left.first_iteration_leaves.has(l);
  }
  queue.size = first + count;
}

LaneSet take_from_stages_queue(std::size_t m, BatchWorkspace& w) {
  StagesQueue& queue = stages_queue();
  const std::size_t first = queue.size - m;
  std::copy_n(&queue.u[first], m, w.u.begin());
  std::copy_n(&queue.v[first], m, w.v.begin());
  std::copy_n(&queue.t[first], m, w.t_algebraic.begin());
  queue.size = first;
  return LaneSet::of_flags(m, &queue.first_iteration_leaves[first]);
}

bool sets_far_lanes_aside(const PlanData& plan, const InvertOptions& options) {
  return takes_fast_path(plan, options) && plan.degree >= 3 && !takes_formula_path(plan, options);
}

FarLanes far_lanes(const PlanData& plan, double tolerance, std::size_t count, const BatchWorkspace& w) {
  if (!skips_far_seeds(plan, tolerance)) return {};
  FarLanes far{.known = true, .lanes = {}};
  for (std::size_t l = 0; l < count; ++l) far.lanes.add(l, segment_far(plan, w.u[l], w.v[l]));
  return far;
}

bool set_aside_far(FarLanes far_from_segment, const Point* points, LaneRows rows, std::size_t count,
                   const BatchWorkspace& w) {
  if (!far_from_segment.known) return false;
  LaneSet active;
  for (std::size_t l = 0; l < count; ++l) active.add(l, w.active[l]);
  const LaneSet far = active.both(far_from_segment.lanes), near = active.without(far_from_segment.lanes);
  if (far.empty() || near.empty()) return false;
  FarQueue& far_lanes = far_queue();
  far.for_each([&](std::size_t l) {
    const std::size_t k = far_lanes.size++;
    far_lanes.u[k] = w.u[l], far_lanes.v[k] = w.v[l], far_lanes.target[k] = &rows[l];
  });
  SeedQueue& seeds = seed_queue();
  near.for_each([&](std::size_t l) {
    const std::size_t k = seeds.size++;
    seeds.u[k] = w.u[l], seeds.v[k] = w.v[l], seeds.point[k] = points[l], seeds.target[k] = &rows[l];
  });
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
