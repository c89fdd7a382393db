#include "pipeline/batch.hpp"

#include <algorithm>
#include <array>

#include "pipeline/by_kind.hpp"
#include "pipeline/fast_path.hpp"
#include "pipeline/off_curve_path.hpp"
#include "pipeline/form_b.hpp"
#include "pipeline/formula_first.hpp"
#include "pipeline/formula_path.hpp"
#include "pipeline/seed_retry.hpp"
#include "pipeline/stage_clock.hpp"
#include "pipeline/svd_path.hpp"
#include "pipeline/svd_queue.hpp"
#include "pipeline/workspace.hpp"

namespace bezinv::detail {
namespace {

// The lanes w's lanes 0..count leave undecided, to the SVD path (lane l's answer goes to rows[l]);
// b_formed: w.B holds their B. Returns whether it left lanes in the seed retry's queue.
bool route_undecided(const PlanData& plan, LaneRows rows, std::size_t count, const InvertOptions& options,
                     BatchWorkspace& w, StageClock& clock, bool b_formed, StageSeconds* stages) {
  const int n = plan.degree, nn = n * n;
  const std::size_t stride = kBatchLanes;
  // The SVD path for the lanes still undecided, compacted to the front of the batch (in order, so
  // moving lane lane_of[k] >= k down to k never overwrites a lane still to be moved).
  // A lane whose seed fell short waits for the seed retry instead (seed_retry.hpp).
  const bool retries = takes_fast_path(plan, options) && n >= 3;
  bool retried = false;
  std::size_t m = 0;
  for (std::size_t l = 0; l < count; ++l) {
    if (!w.active[l]) continue;
    if (retries && retries_seed(w, l)) {
      seed_retry_queue().push(w.u[l], w.v[l], &rows[l]);
      retried = true;
      continue;
    }
    if (m != l) {
      if (b_formed)
        for (int i = 0; i < nn; ++i) w.B[i * stride + m] = w.B[i * stride + l];
      w.u[m] = w.u[l];
      w.v[m] = w.v[l];
    }
    w.lane_of[m++] = static_cast<std::uint8_t>(l);
  }
  if (!b_formed && m > 0) form_compacted_b(plan, w.u.data(), w.v.data(), m, w.B.data());

  if (m == 0) {
    clock.lap(&StageSeconds::decide);  // the routing above is the decide stage's
    return retried;
  }
  SvdQueue& queue = svd_queue();
  if (m >= kSvdGroupLanes || queue.size + m > kBatchLanes) {  // enough for a group: here and now
    std::array<PointResult*, kBatchLanes> target;
    for (std::size_t k = 0; k < m; ++k) target[k] = &rows[w.lane_of[k]];
    svd_path(plan, w.B.data(), w.u.data(), w.v.data(), target.data(), m, options, w, clock);
    return retried;
  }
  for (std::size_t k = 0; k < m; ++k) queue.push(nn, w.B.data(), k, w.u[k], w.v[k], &rows[w.lane_of[k]]);
  clock.lap(&StageSeconds::decide);
  if (queue.size >= kSvdGroupLanes) flush_svd_queue(plan, options, stages);
  return retried;
}

// The fast path's stages after the seed, then the SVD path's routing, for w's lanes 0..count
// (newton_left: fast_path_decide's).
bool decide_lanes(const PlanData& plan, LaneRows rows, std::size_t count, const InvertOptions& options,
                  BatchWorkspace& w, StageClock& clock, bool b_formed, StageSeconds* stages,
                  LaneSet newton_left = {}) {
  fast_path_decide(plan, rows, count, options, w, clock, newton_left);
  off_curve_path(plan, options, count, w, rows, clock);
  return route_undecided(plan, rows, count, options, w, clock, b_formed, stages);
}

// Lanes through the stages, but for those left waiting in this thread's queues (rows: consecutive
// for a batch, gathered for the lanes formula_first leaves). from_formula_first: the lanes are
// lanes formula_first left, these of them the lanes whose first Newton iteration it took
// (FormulaLeft); given: w holds their points normalized and N / M. Returns whether it left lanes
// in the seed retry's queue.
bool invert_lanes(const PlanData& plan, const Point* points, LaneRows rows, std::size_t count,
                  const InvertOptions& options, StageSeconds* stages, StageClock& clock,
                  const LaneSet* from_formula_first = nullptr, bool given = false) {
  BatchWorkspace& w = batch_workspace();
  const bool fast = takes_fast_path(plan, options);
  const bool formed_b = forms_b_late(plan, options);
  if (given)  // (the formula path: no B formed here)
    admit_batch(plan, points, rows, count, w);
  else
    form_batch(plan, points, rows, count, /*form=*/plan.degree >= 2 && !formed_b, w);
  clock.lap(&StageSeconds::form_b);
  if (!fast) {
    if (reports_formula_unrefined(plan, options)) {
      formula_unrefined(plan, options, count, w, rows);
      clock.lap(&StageSeconds::refine);
    }
    return route_undecided(plan, rows, count, options, w, clock, !formed_b, stages);
  }
  FarLanes far;
  if (sets_far_lanes_aside(plan, options)) {
    far = far_lanes(plan, normalized_tolerance(plan, options), count, w);
    if (set_aside_far(far, points, rows, count, w)) {
      clock.lap(&StageSeconds::read_out);
      return false;
    }
  }
  fast_path_seed(plan, points, rows, count, options, w, clock, far, /*formula_given=*/given);
  const LaneSet newton_left = from_formula_first ? formula_first_left(*from_formula_first, count, w) : LaneSet{};
  return decide_lanes(plan, rows, count, options, w, clock, !formed_b, stages, newton_left);
}

// formula_first settles nearly every lane of a batch on the curve and none of a batch off it (noise
// of 1e-6 of the diagonal and more), where its kernel costs ~6% of what the stages then spend on
// each lane. So a thread whose batch it left nearly whole skips it for the next batches, twice as
// many each time it is left so again (at most kFormulaFirstMaxSkip), and tries once more: on a file
// off the curve it runs on about one batch in 16, and one good batch brings it back. Which batches
// take it changes no row (each lane it answers gets the stages' row, bit for bit): speed only.
// And where it settled every lane of the thread's batch before, as it does a batch after batch on
// the curve, it does not keep what it computed on the way for the lanes it leaves (FormulaLeft):
// a few stores a lane, which a file on the curve would not use.
struct FormulaFirstSkip {
  std::size_t skip = 0;     // batches still to skip
  std::size_t after = 0;    // how many to skip after the next batch it leaves nearly whole
  bool settled_all = false;  // it settled every lane of the batch before
};
inline constexpr std::size_t kFormulaFirstMaxSkip = 16;

FormulaFirstSkip& formula_first_skip() {
  thread_local FormulaFirstSkip skip;
  return skip;
}

// One batch: formula_first where the plan takes it (and `first`, and this thread does not skip it),
// then the stages for the lanes it leaves.
bool invert_batch_lanes(const PlanData& plan, const Point* points, PointResult* results, std::size_t count,
                        const InvertOptions& options, StageSeconds* stages, bool first = true) {
  StageClock clock(stages);
  if (!first || !takes_formula_first(plan, options))
    return invert_lanes(plan, points, LaneRows(results), count, options, stages, clock);
  FormulaFirstSkip& skip = formula_first_skip();
  if (skip.skip > 0) {
    --skip.skip;
    return invert_lanes(plan, points, LaneRows(results), count, options, stages, clock);
  }
  const FormulaLeft left =
      formula_first(plan, points, results, count, options, batch_workspace(), clock, /*keep=*/!skip.settled_all);
  skip.settled_all = left.count == 0;
  if (8 * left.count >= 7 * count) {  // nearly whole (at most one lane in eight settled)
    skip.after = std::min(kFormulaFirstMaxSkip, std::max<std::size_t>(1, 2 * skip.after));
    skip.skip = skip.after;
  } else {
    skip.after = 0;
  }
  if (left.count == 0) return false;
  if (left.count == count)  // the whole batch, in place
    return invert_lanes(plan, points, LaneRows(results), count, options, stages, clock, &left.first_iteration_leaves,
                        left.given);
  // Part of the batch: its lanes wait for a batch's worth in the stages queue (by_kind.hpp).
  queue_for_stages(plan, points, results, left, batch_workspace());
  clock.lap(&StageSeconds::decide);
  return false;
}

// The last m lanes of the stages queue (by_kind.hpp), through the rest of the stages.
bool invert_stages_queue(const PlanData& plan, std::size_t m, const InvertOptions& options, StageSeconds* stages) {
  StagesQueue& queue = stages_queue();
  StageClock clock(stages);
  const std::size_t first = queue.size - m;
  const LaneSet first_iteration_leaves = take_from_stages_queue(m, batch_workspace());
  // Their points and rows stay in the queue while they run (invert_lanes queues none).
  return invert_lanes(plan, &queue.point[first], LaneRows(&queue.target[first]), m, options, stages, clock,
                      &first_iteration_leaves, /*given=*/true);
}

// The first m lanes of the seed queue (by_kind.hpp), as a batch before its seed.
bool invert_seed_queue(const PlanData& plan, std::size_t m, const InvertOptions& options, StageSeconds* stages) {
  BatchWorkspace& w = batch_workspace();
  StageClock clock(stages);
  std::array<Point, kBatchLanes> points;
  std::array<PointResult*, kBatchLanes> gathered;
  take_from_seed_queue(m, w, points, gathered);
  clock.lap(&StageSeconds::form_b);
  // Its lanes are all near the segment (set_aside_far sent them), so not one is far.
  const LaneRows rows(gathered.data());
  fast_path_seed(plan, points.data(), rows, m, options, w, clock, FarLanes{.known = true, .lanes = {}});
  return decide_lanes(plan, rows, m, options, w, clock, /*b_formed=*/false, stages);
}

// The first m lanes of the far queue (by_kind.hpp), as a batch from the refinement on (far lanes
// skip the seed).
bool invert_far_queue(const PlanData& plan, std::size_t m, const InvertOptions& options, StageSeconds* stages) {
  BatchWorkspace& w = batch_workspace();
  StageClock clock(stages);
  std::array<PointResult*, kBatchLanes> gathered;
  take_from_far_queue(m, w, gathered);
  clock.lap(&StageSeconds::read_out);
  return decide_lanes(plan, LaneRows(gathered.data()), m, options, w, clock, /*b_formed=*/false, stages);
}

// A batch's worth of lanes (run by `lanes`), then the seed retry's queue once it fills the
// kernel's group (outside `lanes`, whose workspace the retry also uses).
template <typename Lanes>
void with_queues(const PlanData& plan, const InvertOptions& options, StageSeconds* stages, Lanes lanes) {
  if (lanes() && seed_retry_queue().size >= kSeedRetryFlushLanes) flush_seed_retry_queue(plan, options, stages);
}

// Runs the seed queue's, the far queue's and the stages queue's lanes, a batch at a time, while at
// least `least` wait in one: each stays below kBatchLanes lanes between batches (the room their
// capacity leaves for one more).
void run_sorted_queues(const PlanData& plan, const InvertOptions& options, StageSeconds* stages, std::size_t least) {
  SeedQueue& seeds = seed_queue();
  while (seeds.size > 0 && seeds.size >= least) {
    const std::size_t m = std::min(seeds.size, kBatchLanes);
    with_queues(plan, options, stages, [&] { return invert_seed_queue(plan, m, options, stages); });
  }
  FarQueue& far = far_queue();
  while (far.size > 0 && far.size >= least) {
    const std::size_t m = std::min(far.size, kBatchLanes);
    with_queues(plan, options, stages, [&] { return invert_far_queue(plan, m, options, stages); });
  }
  StagesQueue& left = stages_queue();
  while (left.size > 0 && left.size >= least) {
    const std::size_t m = std::min(left.size, kBatchLanes);
    with_queues(plan, options, stages, [&] { return invert_stages_queue(plan, m, options, stages); });
  }
}

// invert_batch, formula_first taken where `first`.
void run_batch(const PlanData& plan, const Point* points, PointResult* results, std::size_t count,
               const InvertOptions& options, StageSeconds* stages, bool first) {
  with_queues(plan, options, stages,
              [&] { return invert_batch_lanes(plan, points, results, count, options, stages, first); });
  if (seed_queue().size >= kBatchLanes || far_queue().size >= kBatchLanes || stages_queue().size >= kBatchLanes)
    run_sorted_queues(plan, options, stages, kBatchLanes);
}

}  // namespace

void invert_batch(const PlanData& plan, const Point* points, PointResult* results, std::size_t count,
                  const InvertOptions& options, StageSeconds* stages) {
  run_batch(plan, points, results, count, options, stages, /*first=*/true);
}

void invert_batch_by_stages(const PlanData& plan, const Point* points, PointResult* results, std::size_t count,
                            const InvertOptions& options) {
  run_batch(plan, points, results, count, options, nullptr, /*first=*/false);
}

void flush_queues(const PlanData& plan, const InvertOptions& options, StageSeconds* stages) {
  run_sorted_queues(plan, options, stages, 1);
  flush_seed_retry_queue(plan, options, stages);
  flush_svd_queue(plan, options, stages);
}

QueueScope::~QueueScope() {
  seed_queue().size = far_queue().size = stages_queue().size = 0;
  seed_retry_queue().size = 0;
  svd_queue().size = 0;
}

}  // namespace bezinv::detail
