#include "pipeline/by_kind.hpp"

#include <algorithm>
#include <bit>
#include <cstdint>
#include <limits>

#include "isolation.hpp"
#include "pipeline/fast_path.hpp"
#include "pipeline/formula_path.hpp"

namespace bezinv::detail {

KindQueue& kind_queue(LaneKind kind) {
  thread_local std::array<KindQueue, 2> queues;
  return queues[static_cast<std::size_t>(kind)];
}

SeedQueue& seed_queue() {
  thread_local SeedQueue queue;
  return queue;
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
  KindQueue& off = kind_queue(LaneKind::off_curve);
  const double inf = std::numeric_limits<double>::infinity();
  std::size_t k = off.size;
  for (; far != 0; far &= far - 1, ++k) {
    const std::size_t l = static_cast<std::size_t>(std::countr_zero(far));
    off.u[k] = w.u[l], off.v[k] = w.v[l], off.t_algebraic[k] = PointResult::nan;
    off.defect[k] = off.estimate[k] = inf;
    off.target[k] = &results[l];
  }
  off.size = k;
  SeedQueue& seeds = seed_queue();
  k = seeds.size;
  for (; near != 0; near &= near - 1, ++k) {
    const std::size_t l = static_cast<std::size_t>(std::countr_zero(near));
    seeds.u[k] = w.u[l], seeds.v[k] = w.v[l], seeds.point[k] = points[l];
    seeds.target[k] = &results[l];
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

bool sorts_by_kind(const PlanData& plan, const InvertOptions& options) {
  return takes_fast_path(plan, options) && plan.degree >= 3 && !takes_formula_path(plan, options);
}

namespace {

// As refine_grouped groups it (a seed that did not settle has an infinite estimate: off).
LaneKind kind_of(const BatchWorkspace& w, std::size_t l) {
  return w.estimate[l] > kOnCurveEstimate ? LaneKind::off_curve : LaneKind::on_curve;
}

}  // namespace

KindSort sort_mixed_batch(std::size_t count, LaneRows batch_rows, BatchWorkspace& w,
                          std::array<PointResult*, kBatchLanes>& rows) {
  static_assert(kBatchLanes == 64, "a batch's lanes as the bits of one word");
  // The lanes of each kind as bits: the loops below visit the set bits alone, without a branch
  // per lane (the kinds are often mixed at random).
  std::uint64_t on = 0, off = 0;
  for (std::size_t l = 0; l < count; ++l) {
    const std::uint64_t is_off = kind_of(w, l) == LaneKind::off_curve, active = w.active[l];
    on |= (active & (is_off ^ 1)) << l;
    off |= (active & is_off) << l;
  }
  if (on == 0 || off == 0) return {.kept = count};  // inactive lanes made it look mixed
  const std::size_t on_lanes = static_cast<std::size_t>(std::popcount(on));
  const std::size_t off_lanes = static_cast<std::size_t>(std::popcount(off));
  // Which lanes stay, compacted. Few of one kind: the others, in a batch nearly as full (only
  // those few go). Else a kind whose queue holds enough to fill the batch with its lanes, the kind
  // more numerous in the batch first: its lanes stay and the queue's first ones join them, so
  // that they skip the queue's two copies. Else none: every lane leaves.
  std::uint64_t stays = 0;
  KindQueue* joins = nullptr;
  bool on_curve = false;
  const bool more_on = on_lanes > off_lanes;
  if (std::min(on_lanes, off_lanes) <= kKindStaysAbove) {
    std::uint64_t& many = more_on ? on : off;
    on_curve = more_on;
    stays = many;
    many = 0;
  } else {
    for (const LaneKind kind : {more_on ? LaneKind::on_curve : LaneKind::off_curve,
                                more_on ? LaneKind::off_curve : LaneKind::on_curve}) {
      std::uint64_t& lanes = kind == LaneKind::on_curve ? on : off;
      KindQueue& queue = kind_queue(kind);
      if (queue.size + static_cast<std::size_t>(std::popcount(lanes)) < kBatchLanes) continue;
      on_curve = kind == LaneKind::on_curve;
      stays = lanes;
      lanes = 0;
      joins = &queue;
      break;
    }
  }
  const auto leave = [&](std::uint64_t lanes, KindQueue& queue) {
    std::size_t k = queue.size;
    for (; lanes != 0; lanes &= lanes - 1, ++k) {
      const std::size_t l = static_cast<std::size_t>(std::countr_zero(lanes));
      queue.u[k] = w.u[l], queue.v[k] = w.v[l], queue.t_algebraic[k] = w.t_algebraic[l];
      queue.defect[k] = w.defect[l], queue.estimate[k] = w.estimate[l];
      queue.target[k] = &batch_rows[l];
    }
    queue.size = k;
  };
  leave(on, kind_queue(LaneKind::on_curve));
  leave(off, kind_queue(LaneKind::off_curve));
  // In order, so moving lane l >= k down to k never overwrites a lane still to be moved.
  std::size_t kept = 0;
  for (; stays != 0; stays &= stays - 1, ++kept) {
    const std::size_t l = static_cast<std::size_t>(std::countr_zero(stays));
    w.u[kept] = w.u[l], w.v[kept] = w.v[l], w.t_algebraic[kept] = w.t_algebraic[l];
    w.defect[kept] = w.defect[l], w.estimate[kept] = w.estimate[l];
    w.active[kept] = 1;
    rows[kept] = &batch_rows[l];
  }
  if (joins != nullptr) {
    take_from_queue(*joins, kBatchLanes - kept, w, rows, kept);
    kept = kBatchLanes;
  }
  return {.moved = true, .kept = kept, .on_curve = on_curve};
}

void take_from_queue(KindQueue& queue, std::size_t m, BatchWorkspace& w, std::array<PointResult*, kBatchLanes>& rows,
                     std::size_t first_lane) {
  for (std::size_t k = 0; k < m; ++k) {
    const std::size_t l = first_lane + k;
    w.u[l] = queue.u[k], w.v[l] = queue.v[k];
    w.t_algebraic[l] = queue.t_algebraic[k], w.defect[l] = queue.defect[k], w.estimate[l] = queue.estimate[k];
    w.active[l] = 1;
    rows[l] = queue.target[k];
  }
  const std::size_t rest = queue.size - m;
  for (std::size_t k = 0; k < rest; ++k) {
    queue.u[k] = queue.u[m + k], queue.v[k] = queue.v[m + k];
    queue.t_algebraic[k] = queue.t_algebraic[m + k], queue.defect[k] = queue.defect[m + k];
    queue.estimate[k] = queue.estimate[m + k];
    queue.target[k] = queue.target[m + k];
  }
  queue.size = rest;
}

}  // namespace bezinv::detail
