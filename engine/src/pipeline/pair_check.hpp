#pragma once
// The fast path's second-parameter check (docs/fast-path.md, "The pair check"): where the sigma_{n-1}
// estimate is small, a lane not certified isolated looks for a second parameter in span{z, second}.
// Its roots wait in a per-thread queue until they fill a SIMD group of the Newton kernel; a lane
// whose root refines onto the segment at a distinct parameter goes to the SVD path (double points
// are always answered there), and so does a lane whose other root (the one farther from its t)
// walks back to its t: the plane then missed the second parameter the small estimate announced
// (two parameters close together, near a cusp), which the SVD path finds. The others are answered
// on the fast path. No lane's answer depends
// on the others in the queue, so neither the batch nor the thread count changes it.
#include <array>
#include <cstddef>
#include <cstdint>

#include "bezinv/profile.hpp"
#include "plan_data.hpp"
#include "pipeline/candidate.hpp"
#include "pipeline/workspace.hpp"

namespace bezinv::detail {

// The queue is flushed once this many roots wait (a SIMD group's worth). Speed only.
inline constexpr std::size_t kPairCheckFlushRoots = 16;
// Room for a whole batch besides the fewer than kPairCheckFlushRoots lanes left waiting.
inline constexpr std::size_t kPairCheckLanes = 2 * kBatchLanes;

struct PairCheckQueue {
  // Lane k: its point, its answer if no second parameter is found (t, distance, the two sigma
  // estimates), and where the answer goes.
  std::array<double, kPairCheckLanes> u, v, t, distance, sigma_min, sigma_next;
  std::array<PointResult*, kPairCheckLanes> target;
  std::array<std::uint8_t, kPairCheckLanes> second_found;
  std::size_t lanes = 0;
  // The roots (two per lane at most): those near their lane's t from the front, the others from
  // the back, so that the kernel's SIMD groups hold roots of similar work.
  std::array<double, 2 * kPairCheckLanes> root_t, root_u, root_v, root_distance;
  std::array<std::uint8_t, 2 * kPairCheckLanes> root_lane;
  std::array<std::uint8_t, 2 * kPairCheckLanes> root_other;  // the root farther from the lane's t
  std::size_t near = 0, far = 0;
};

// This thread's queue.
PairCheckQueue& pair_check_queue();

// The parameters whose Bernstein vector lies in span{z, second} of batch lane l (at most two; how
// many, as parameters_from_null_space).
int null_space_roots(int n, const BatchWorkspace& w, std::size_t l, double roots[2]);

// Queues lane l's roots (but z's own, see kSameRoot) with the lane's answer-if-alone. False,
// queueing nothing, when the lane has no root to check.
bool queue_second_parameters(int n, const BatchWorkspace& w, std::size_t l, const Candidate& c, PointResult* target);

// Runs the check for every waiting lane: answered on the fast path, or handed to the SVD queue.
void flush_pair_check_queue(const PlanData& plan, const InvertOptions& options, StageSeconds* stages);

}  // namespace bezinv::detail
