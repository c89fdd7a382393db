#pragma once
// The lanes a batch leaves for the SVD path, when they are too few to fill a SIMD group of the
// Jacobi kernel, wait here per thread for the next batches' (docs/fast-path.md, "Queues"). No
// lane's answer depends on the others of its group.
#include <array>
#include <cstddef>

#include "bezinv/profile.hpp"
#include "plan_data.hpp"
#include "bezinv/tolerances.hpp"
#include "pipeline/workspace.hpp"

namespace bezinv::detail {

// A SIMD group of the batched Jacobi kernel: the queue runs once it holds this many lanes. Speed only.
inline constexpr std::size_t kSvdGroupLanes = 8;

struct SvdQueue {
  std::vector<double> B = std::vector<double>(static_cast<std::size_t>(kMaxDegree) * kMaxDegree * kBatchLanes);
  std::array<double, kBatchLanes> u, v;
  std::array<PointResult*, kBatchLanes> target;  // where lane k's answer goes
  std::size_t size = 0;

  // Appends lane `lane` of the n x n matrices `from` (lane-major, stride kBatchLanes); size < kBatchLanes.
  void push(int nn, const double* from, std::size_t lane, double lane_u, double lane_v, PointResult* answer) {
    for (int i = 0; i < nn; ++i) B[i * kBatchLanes + size] = from[i * kBatchLanes + lane];
    u[size] = lane_u;
    v[size] = lane_v;
    target[size++] = answer;
  }
};

// This thread's queue.
SvdQueue& svd_queue();

// Runs the lanes waiting in this thread's queue through the SVD path.
void flush_svd_queue(const PlanData& plan, const InvertOptions& options, StageSeconds* stages);

}  // namespace bezinv::detail
