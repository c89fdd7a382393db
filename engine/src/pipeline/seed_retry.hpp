#pragma once
// The seed retry (docs/fast-path.md, "Seeds that fall short"): a lane near the curve whose seed
// did not settle within its two solves, and which the off-curve path cannot answer (it is within
// the tolerance), went to the SVD path. At high degree B's second smallest singular value can be
// small without a second parameter (sigma_n / sigma_{n-1} ~ 0.1 for a point 1e-6 of the diagonal
// off the curve): inverse iteration then converges slowly, and the full kernel with
// kSeedRetryIterations solves settles most such lanes, which decide_with_gap then decides as the
// gap pass decides it. The lanes are few (0.2-0.5% at degrees 12-20), so they wait in a per-thread
// queue until they fill the kernel's SIMD groups; the lanes the retry does not settle go on to
// the SVD path through its queue. No lane's answer depends on the others in the queue.
#include <array>
#include <cstddef>

#include "bezinv/profile.hpp"
#include "bezinv/tolerances.hpp"
#include "plan_data.hpp"
#include "pipeline/stage_clock.hpp"
#include "pipeline/workspace.hpp"

namespace bezinv::detail {

// Up to this defect an unsettled seed is retried: beyond, z is no start at all (B has no gap at
// the point; the off-curve path or the SVD path answers it).
inline constexpr double kSeedRetryMaxDefect = 0.1;
// The retry's solves: three more than the full kernel's at sigma_n / sigma_{n-1} = 0.1 take the
// chord from 1e-3 to 1e-6.
inline constexpr int kSeedRetryIterations = 6;
// The queue is run once it holds this many lanes (the kernel's SIMD group at n = 9..24). Speed only.
inline constexpr std::size_t kSeedRetryFlushLanes = 16;
// Room for a whole batch besides the fewer than kSeedRetryFlushLanes lanes left waiting.
inline constexpr std::size_t kSeedRetryLanes = 2 * kBatchLanes;

struct SeedRetryQueue {
  std::array<double, kSeedRetryLanes> u, v;
  std::array<PointResult*, kSeedRetryLanes> target;  // where lane k's answer goes
  std::size_t size = 0;

  void push(double lane_u, double lane_v, PointResult* answer) {
    u[size] = lane_u;
    v[size] = lane_v;
    target[size++] = answer;
  }
};

// This thread's queue.
SeedRetryQueue& seed_retry_queue();

// Whether active lane l of a batch the fast path took (degree 3 and above: degree 2's lanes had
// the full kernel) waits for the retry: no degree drop at its point, and a seed defect in
// (kFastPathMaxDefect, kSeedRetryMaxDefect].
inline bool retries_seed(const BatchWorkspace& w, std::size_t l) {
  return !w.drops[l] && w.defect[l] > kFastPathMaxDefect && w.defect[l] <= kSeedRetryMaxDefect;
}

// Runs the waiting lanes, kBatchLanes at a time, in the batch workspace (free between batches):
// answered here or handed to the SVD queue.
void flush_seed_retry_queue(const PlanData& plan, const InvertOptions& options, StageSeconds* stages);

}  // namespace bezinv::detail
