#pragma once
// The pipeline's driver: one batch of points of one curve through its stages (docs/README.md):
//   0. formula    a conic's or cubic's formula path, its common case in one pass: the lanes it
//                 answers leave here, the others go on gathered (formula_first.hpp)
//   1. form B     normalize and admit the points, form B (form_b.hpp)
//   2-4. fast path  null vector by inverse iteration, read-out, refinement, and the answers it
//                 may give (fast_path.hpp); from degree 15, a batch's lanes far from the segment
//                 and near it sorted before the seed, each through a per-thread queue (by_kind.hpp)
//   2-4. seed retry the lanes near the curve whose seed fell short, through a per-thread queue
//                 (seed_retry.hpp)
//   2-5. SVD path  for the lanes still undecided, here or through the per-thread queue
//                 (svd_path.hpp, svd_queue.hpp)
// and the rare paths from decide.hpp (pair, Sylvester, nearest). invert_point is a batch of one,
// so there is one code path.
#include <cstddef>

#include "bezinv/profile.hpp"
#include "plan_data.hpp"

namespace bezinv::detail {

// One batch (count <= kBatchLanes), with this thread's queues around it: some lanes may be left
// waiting in them (flush_queues answers them).
void invert_batch(const PlanData& plan, const Point* points, PointResult* results, std::size_t count,
                  const InvertOptions& options, StageSeconds* stages);

// invert_batch without formula_first: every lane through the stages. formula_first must give each
// lane it answers this very row (tests/engine/formula_first_test.cpp).
void invert_batch_by_stages(const PlanData& plan, const Point* points, PointResult* results, std::size_t count,
                            const InvertOptions& options);

// Answers every lane waiting in this thread's queues: the seed queue and the far queue first, the
// seed retry next (it may hand lanes to the SVD queue), then the SVD queue. Called at the end of
// each range of batches, so a queue never outlives the plan it was filled for.
void flush_queues(const PlanData& plan, const InvertOptions& options, StageSeconds* stages);

// Empties this thread's queues when it goes out of scope: after the last flush they are empty
// anyway; if an exception (bad_alloc) cut the work short, the waiting lanes point into the
// caller's results and must not be run by a later call.
struct QueueScope {
  QueueScope() = default;
  QueueScope(const QueueScope&) = delete;
  QueueScope& operator=(const QueueScope&) = delete;
  ~QueueScope();
};

}  // namespace bezinv::detail
