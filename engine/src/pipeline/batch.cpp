#include "pipeline/batch.hpp"

#include <array>

#include "pipeline/fast_path.hpp"
#include "pipeline/off_curve_path.hpp"
#include "pipeline/form_b.hpp"
#include "pipeline/formula_path.hpp"
#include "pipeline/pair_check.hpp"
#include "pipeline/seed_retry.hpp"
#include "pipeline/stage_clock.hpp"
#include "pipeline/svd_path.hpp"
#include "pipeline/svd_queue.hpp"
#include "pipeline/workspace.hpp"

namespace bezinv::detail {
namespace {

// One batch through the stages, but for the lanes left waiting in this thread's queues.
// Returns whether it left lanes in the seed retry's queue.
bool invert_batch_lanes(const PlanData& plan, const Point* points, PointResult* results, std::size_t count,
                        const InvertOptions& options, StageSeconds* stages) {
  BatchWorkspace& w = batch_workspace();
  const int n = plan.degree, nn = n * n;
  const std::size_t stride = kBatchLanes;
  StageClock clock(stages);

  const bool fast = takes_fast_path(plan, options);
  const bool formed_b = forms_b_late(plan, options);
  form_batch(plan, points, results, count, /*form=*/n >= 2 && !formed_b, w);
  clock.lap(&StageSeconds::form_b);

  if (fast) {
    fast_path(plan, points, results, count, options, w, clock);
    off_curve_path(plan, options, count, w, results, clock);
  } else if (reports_formula_unrefined(plan, options)) {
    formula_unrefined(plan, options, count, w, results);
    clock.lap(&StageSeconds::refine);
  }

  // The SVD path for the lanes still undecided, compacted to the front of the batch (in order, so
  // moving lane lane_of[k] >= k down to k never overwrites a lane still to be moved).
  // A lane whose seed fell short waits for the seed retry instead (seed_retry.hpp).
  const bool retries = fast && n >= 3;
  bool retried = false;
  std::size_t m = 0;
  for (std::size_t l = 0; l < count; ++l) {
    if (!w.active[l]) continue;
    if (retries && retries_seed(w, l)) {
      seed_retry_queue().push(w.u[l], w.v[l], &results[l]);
      retried = true;
      continue;
    }
    if (m != l) {
      if (!formed_b)
        for (int i = 0; i < nn; ++i) w.B[i * stride + m] = w.B[i * stride + l];
      w.u[m] = w.u[l];
      w.v[m] = w.v[l];
    }
    w.lane_of[m++] = static_cast<std::uint8_t>(l);
  }
  if (formed_b && m > 0) form_compacted_b(plan, w.u.data(), w.v.data(), m, w.B.data());

  if (m == 0) {
    clock.lap(&StageSeconds::decide);  // the routing above is the decide stage's
    return retried;
  }
  SvdQueue& queue = svd_queue();
  if (m >= kSvdGroupLanes || queue.size + m > kBatchLanes) {  // enough for a group: here and now
    std::array<PointResult*, kBatchLanes> target;
    for (std::size_t k = 0; k < m; ++k) target[k] = &results[w.lane_of[k]];
    svd_path(plan, w.B.data(), w.u.data(), w.v.data(), target.data(), m, options, w, clock);
    return retried;
  }
  for (std::size_t k = 0; k < m; ++k) queue.push(nn, w.B.data(), k, w.u[k], w.v[k], &results[w.lane_of[k]]);
  clock.lap(&StageSeconds::decide);
  if (queue.size >= kSvdGroupLanes) flush_svd_queue(plan, options, stages);
  return retried;
}

}  // namespace

// One batch, with this thread's pair-check queue around it: flushed first if the batch's lanes
// might not fit in it, and after once enough roots wait to fill a SIMD group (both outside
// invert_batch_lanes, whose workspace the SVD path also uses).
void invert_batch(const PlanData& plan, const Point* points, PointResult* results, std::size_t count,
                  const InvertOptions& options, StageSeconds* stages) {
  PairCheckQueue& pairs = pair_check_queue();
  if (pairs.lanes + count > kPairCheckLanes) flush_pair_check_queue(plan, options, stages);
  if (invert_batch_lanes(plan, points, results, count, options, stages) &&
      seed_retry_queue().size >= kSeedRetryFlushLanes)
    flush_seed_retry_queue(plan, options, stages);
  if (pairs.near + pairs.far >= kPairCheckFlushRoots) {
    flush_pair_check_queue(plan, options, stages);
    if (svd_queue().size >= kSvdGroupLanes) flush_svd_queue(plan, options, stages);
  }
}


void flush_queues(const PlanData& plan, const InvertOptions& options, StageSeconds* stages) {
  flush_seed_retry_queue(plan, options, stages);
  flush_pair_check_queue(plan, options, stages);
  flush_svd_queue(plan, options, stages);
}

QueueScope::~QueueScope() {
  seed_retry_queue().size = 0;
  svd_queue().size = 0;
  PairCheckQueue& pairs = pair_check_queue();
  pairs.lanes = pairs.near = pairs.far = 0;
}

}  // namespace bezinv::detail
