#pragma once
// Lanes by kind (docs/fast-path.md, "Mixed batches"). After the seed a batch's lanes are of two
// kinds: on the curve (B's sigma_min estimate at rounding level, kOnCurveEstimate) and off it.
// The stages after the seed take a shortcut for a batch of one kind (the refinement in place, the
// off-curve path not entered) and, for a batch of both, pay a compaction and a second set of
// loops: such a batch cost 6-9% more than its lanes in batches of one kind each, however the
// kinds were arranged in it. The kind is known only from the seed, so the points cannot be sorted
// before it; the lanes are sorted after it instead. Where a batch holds both kinds, the lanes of
// the kind fewer in it leave, with what the seed gave them, for a per-thread queue of their kind,
// and so do the others unless they nearly fill the batch; a queue that holds a batch's worth of lanes goes
// through the same stages as a batch of that one kind.
// Far from a high-degree curve, some lanes are known to be off the curve before the seed: the
// formed seed does not seed those far from the segment (skips_far_seeds), so its SIMD groups hold
// only a batch's near lanes, part full (at degree 16, 30% more per seeded lane in a batch half
// far). Where a batch holds both, its far lanes go to the off-curve queue at once, with what an
// unseeded lane gets, and its near lanes to a seed queue, seeded once it holds a batch's worth.
// No lane's answer depends on the others in its batch or its queue.
#include <array>
#include <cstddef>

#include "bezinv/invert.hpp"
#include "plan_data.hpp"
#include "pipeline/fast_path.hpp"
#include "pipeline/workspace.hpp"

namespace bezinv::detail {

// Room for the fewer than kBatchLanes lanes left waiting and the fewer than kBatchLanes a batch
// adds (sort_by_kind writes one slot past those it adds).
inline constexpr std::size_t kKindQueueLanes = 2 * kBatchLanes;
// Where a batch holds at most this many lanes of one kind, only those leave (the others stay in a
// batch nearly full); above it, both kinds leave, so that every batch after the seed is full:
// a SIMD group runs whole whatever its lanes, so a batch half full of one kind costs nearly as
// much as a full one. Speed only.
inline constexpr std::size_t kKindStaysAbove = kBatchLanes / 8;

// A kind's lanes, as the seed left them (fast_path_seed): all that fast_path_decide reads.
struct KindQueue {
  std::array<double, kKindQueueLanes> u, v, t_algebraic, defect, estimate;
  std::array<PointResult*, kKindQueueLanes> target;  // where lane k's answer goes
  std::size_t size = 0;
};

enum class LaneKind { on_curve = 0, off_curve = 1 };

// This thread's queue of that kind.
KindQueue& kind_queue(LaneKind kind);

// Lanes waiting for their seed: the point as given (a lane whose B overflows answers from it) and
// as normalized.
struct SeedQueue {
  std::array<double, kKindQueueLanes> u, v;
  std::array<Point, kKindQueueLanes> point;
  std::array<PointResult*, kKindQueueLanes> target;
  std::size_t size = 0;
};

// This thread's seed queue.
SeedQueue& seed_queue();

// The batch's lanes 0..count far from the segment, where the plan's formed seed leaves such lanes
// unseeded (skips_far_seeds, tolerance normalized); not known elsewhere.
FarLanes far_lanes(const PlanData& plan, double tolerance, std::size_t count, const BatchWorkspace& w);

// Where the batch's active lanes are both far and near (far known): the far ones go to the
// off-curve queue, t NaN and defect and estimate +inf (as formed_seed leaves them), the near ones
// to the seed queue; lane l answers in results[l]. Returns whether they left (none stays).
bool set_aside_far(FarLanes far, const Point* points, PointResult* results, std::size_t count,
                   const BatchWorkspace& w);

// Puts the seed queue's first m lanes (m <= kBatchLanes) into w's lanes 0..m as active lanes, their
// points in `points` and rows in `rows`, and moves the rest of the queue to its front.
void take_from_seed_queue(std::size_t m, BatchWorkspace& w, std::array<Point, kBatchLanes>& points,
                          std::array<PointResult*, kBatchLanes>& rows);

// Whether this plan's batches are sorted by kind: the fast path's two passes seeded from B
// (degree 3 and above; not the formula path, whose lanes have no estimate to tell their kind by,
// nor degree 2, whose decisions use more of the seed's outputs than the queue keeps).
bool sorts_by_kind(const PlanData& plan, const InvertOptions& options);

// Where the batch's active lanes 0..count are of both kinds, they go to their kind's queue, but
// for those of one kind that stay: a kind with more than kBatchLanes - kKindStaysAbove lanes in
// the batch, or one whose queue can fill the batch with them (its first lanes then join them).
// Those are compacted to w's lanes 0..kept, rows[k] where kept lane k answers (lanes no longer
// active are dropped). Lane l of the batch answers in batch_rows[l].
struct KindSort {
  bool moved = false;      // lanes left or moved: the kept ones answer in `rows`; else the batch is as it was
  std::size_t kept = 0;    // w's lanes 0..kept go on (0: every lane left)
  bool on_curve = false;   // every one's estimate is at most kOnCurveEstimate (fast_path_decide's hint)
};
KindSort sort_by_kind(std::size_t count, LaneRows batch_rows, BatchWorkspace& w,
                      std::array<PointResult*, kBatchLanes>& rows);

// sort_by_kind past its first test, for a batch whose estimates are of both kinds.
KindSort sort_mixed_batch(std::size_t count, LaneRows batch_rows, BatchWorkspace& w,
                          std::array<PointResult*, kBatchLanes>& rows);

// Most batches are of one kind: told first, inline, over the estimates alone, with four
// independent sums (one would chain every lane's add to the last). A lane no longer active counts
// as its estimate says; sort_mixed_batch tells exactly.
inline KindSort sort_by_kind(std::size_t count, LaneRows batch_rows, BatchWorkspace& w,
                             std::array<PointResult*, kBatchLanes>& rows) {
  std::array<std::size_t, 4> above{};
  std::size_t l = 0;
  for (; l + 4 <= count; l += 4)
    for (std::size_t j = 0; j < 4; ++j) above[j] += w.estimate[l + j] > kOnCurveEstimate;
  for (; l < count; ++l) above[0] += w.estimate[l] > kOnCurveEstimate;
  const std::size_t off_estimates = above[0] + above[1] + above[2] + above[3];
  if (off_estimates == 0 || off_estimates == count) return {.kept = count, .on_curve = off_estimates == 0};
  return sort_mixed_batch(count, batch_rows, w, rows);
}

// Puts the queue's first m lanes into w's lanes first_lane..first_lane + m (at most kBatchLanes) as
// active lanes, their rows in `rows`, and moves the rest of the queue to its front.
void take_from_queue(KindQueue& queue, std::size_t m, BatchWorkspace& w, std::array<PointResult*, kBatchLanes>& rows,
                     std::size_t first_lane = 0);

}  // namespace bezinv::detail
