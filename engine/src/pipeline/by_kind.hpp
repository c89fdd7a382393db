#pragma once
// Lanes by kind before the seed (docs/fast-path.md, "Mixed batches"). Far from a high-degree
// curve, some lanes are known to be off it before the seed: the formed seed does not seed the
// lanes far from the segment (skips_far_seeds, segment_far), so in a batch of both its SIMD groups
// hold only the near lanes, part full (at degree 16 a seeded lane cost 30% more in a batch half far
// than in one all near). Where a batch holds both, its far lanes go to a per-thread far queue,
// with what an unseeded lane gets (t NaN, defect and estimate +inf, as formed_seed leaves them),
// and its near lanes to a per-thread seed queue; each queue, once it holds a batch's worth, goes
// on as a batch of one kind (the far queue's from the refinement on, the seed queue's from the
// seed). No lane's answer depends on the others in its batch or its queue.
//
// On the formula path, formula_first (formula_first.hpp) sorts a batch the same way: the lanes it
// settles (on the curve) answer there, and the others go, with what it found for them, to a
// per-thread stages queue, which goes through the stages once it holds a batch's worth. In a
// batch of both kinds, the lanes it leaves would otherwise run as a batch part full: every SIMD
// group and every stage's loop of it run for half the lanes they hold in a batch off the curve.
#include <array>
#include <cstddef>
#include <cstdint>

#include "bezinv/invert.hpp"
#include "plan_data.hpp"
#include "pipeline/fast_path.hpp"
#include "pipeline/formula_first.hpp"
#include "pipeline/workspace.hpp"

namespace bezinv::detail {

// Room for the fewer than kBatchLanes lanes left waiting and the at most kBatchLanes a batch adds.
inline constexpr std::size_t kSortedQueueLanes = 2 * kBatchLanes;

// Lanes waiting for their seed: the point as given (a lane whose B overflows answers from it) and
// as normalized.
struct SeedQueue {
  std::array<double, kSortedQueueLanes> u, v;
  std::array<Point, kSortedQueueLanes> point;
  std::array<PointResult*, kSortedQueueLanes> target;  // where lane k's answer goes
  std::size_t size = 0;
};

// Lanes far from the segment, waiting for the stages after the seed (which they skip).
struct FarQueue {
  std::array<double, kSortedQueueLanes> u, v;
  std::array<PointResult*, kSortedQueueLanes> target;
  std::size_t size = 0;
};

// Lanes formula_first left, waiting for the stages: the point as given and as normalized, N / M,
// and whether its first Newton iteration leaves it where its start is N / M in [0, 1]
// (FormulaLeft::first_iteration_leaves).
struct StagesQueue {
  std::array<double, kSortedQueueLanes> u, v, t;
  std::array<Point, kSortedQueueLanes> point;
  std::array<PointResult*, kSortedQueueLanes> target;
  std::array<std::uint8_t, kSortedQueueLanes> first_iteration_leaves;
  std::size_t size = 0;
};

// This thread's queues.
SeedQueue& seed_queue();
FarQueue& far_queue();
StagesQueue& stages_queue();

// Whether this plan's batches may set their far lanes aside: the fast path's two passes seeded from
// B (degree 3 and above; not the formula path, whose lanes are not seeded from B). Whether the
// plan's formed seed skips far lanes at all, far_lanes tells.
bool sets_far_lanes_aside(const PlanData& plan, const InvertOptions& options);

// The batch's lanes 0..count far from the segment, where the plan's formed seed leaves such lanes
// unseeded (skips_far_seeds, tolerance normalized); not known elsewhere.
FarLanes far_lanes(const PlanData& plan, double tolerance, std::size_t count, const BatchWorkspace& w);

// Where the batch's active lanes are both far and near (far known): the far ones go to the far
// queue, the near ones to the seed queue; lane l answers in rows[l]. Returns whether they left
// (none stays in the batch).
bool set_aside_far(FarLanes far, const Point* points, LaneRows rows, std::size_t count,
                   const BatchWorkspace& w);

// Puts the lanes formula_first left of a batch (its points, consecutive rows, and w as
// formula_first left it) in the stages queue; where it did not keep their points normalized and
// N / M (left.given), computes them (PlanData::normalize and formula_parameter: the same bits).
void queue_for_stages(const PlanData& plan, const Point* points, PointResult* rows, const FormulaLeft& left,
                      const BatchWorkspace& w);

// Takes the stages queue's last m lanes (m <= kBatchLanes) out of it into w's lanes 0..m (u, v,
// and N / M in t_algebraic): their points and rows are the queue's, from stages_queue().point[size]
// and .target[size] on (size as it is then), until lanes are queued again. Returns their
// first_iteration_leaves.
LaneSet take_from_stages_queue(std::size_t m, BatchWorkspace& w);

// Puts the seed queue's first m lanes (m <= kBatchLanes) into w's lanes 0..m as active lanes, their
// points in `points` and rows in `rows`, and moves the rest of the queue to its front.
void take_from_seed_queue(std::size_t m, BatchWorkspace& w, std::array<Point, kBatchLanes>& points,
                          std::array<PointResult*, kBatchLanes>& rows);

// Puts the far queue's first m lanes (m <= kBatchLanes) into w's lanes 0..m as active lanes with an
// unseeded lane's t, defect and estimate, their rows in `rows`, and moves the rest to its front.
void take_from_far_queue(std::size_t m, BatchWorkspace& w, std::array<PointResult*, kBatchLanes>& rows);

}  // namespace bezinv::detail
