#include "pipeline/seed_retry.hpp"

#include <algorithm>
#include <cmath>

#include "bezinv/kernels/batch.hpp"
#include "isolation.hpp"
#include "pipeline/candidate.hpp"
#include "pipeline/decide.hpp"
#include "pipeline/fast_path.hpp"
#include "pipeline/form_b.hpp"
#include "pipeline/svd_queue.hpp"

namespace bezinv::detail {

SeedRetryQueue& seed_retry_queue() {
  thread_local SeedRetryQueue queue;
  return queue;
}

void flush_seed_retry_queue(const PlanData& plan, const InvertOptions& options, StageSeconds* stages) {
  SeedRetryQueue& queue = seed_retry_queue();
  if (queue.size == 0) return;
  StageClock clock(stages);
  const int n = plan.degree, nn = n * n;
  const double tolerance = normalized_tolerance(plan, options);
  const kernels::Implementation& kernel = kernels::active_implementation();
  BatchWorkspace& w = batch_workspace();
  const std::size_t lanes = queue.size;
  queue.size = 0;
  for (std::size_t first = 0; first < lanes; first += kBatchLanes) {
    const std::size_t m = std::min(kBatchLanes, lanes - first);
    for (std::size_t k = 0; k < m; ++k) {
      w.u[k] = queue.u[first + k], w.v[k] = queue.v[first + k];
      w.active[k] = 1;
      w.gap_lane_of[k] = static_cast<std::uint8_t>(k);
    }
    full_kernel(plan, m, w, kSeedRetryIterations);
    std::array<double, kBatchLanes> t;
    kernel.bernstein_parameter(n, m, kBatchLanes, w.gap_z.data(), t.data());
    clock.lap(&StageSeconds::kernel);
    // As the fast path's two passes decide a lane whose seed settled: the isolation certificate
    // first (no gap in the row), then the gap.
    for (std::size_t k = 0; k < m; ++k) {
      if (!(w.defect[k] <= kFastPathMaxDefect) || !std::isfinite(t[k])) continue;
      const Candidate c = settle(plan, w.u[k], w.v[k], t[k], Path::bezout_lu, tolerance, true);
      if (c.on_segment && isolated(plan, w.u[k], w.v[k], c.t, c.distance, tolerance)) {
        w.active[k] = 0;
        answer_fast(plan, c.t, c.distance, w.estimate[k], PointResult::nan, *queue.target[first + k]);
      } else if (gap_decides(w, k)) {
        decide_with_gap(plan, w, k, c, tolerance, /*asked=*/true, *queue.target[first + k]);
      }
    }
    clock.lap(&StageSeconds::refine);
    // The others to the SVD path, B formed again (the same kernel, the same bits as the batch's)
    // in the workspace, whose B the SVD queue's flush leaves alone.
    std::array<double, kBatchLanes> u, v;
    std::array<PointResult*, kBatchLanes> target;
    std::size_t left = 0;
    for (std::size_t k = 0; k < m; ++k)
      if (w.active[k]) u[left] = w.u[k], v[left] = w.v[k], target[left++] = queue.target[first + k];
    if (left == 0) continue;
    form_compacted_b(plan, u.data(), v.data(), left, w.B.data());
    SvdQueue& svd = svd_queue();
    for (std::size_t j = 0; j < left; ++j) {
      if (svd.size == kBatchLanes) flush_svd_queue(plan, options, stages);
      svd.push(nn, w.B.data(), j, u[j], v[j], target[j]);
    }
    clock.lap(&StageSeconds::decide);
  }
}

}  // namespace bezinv::detail
