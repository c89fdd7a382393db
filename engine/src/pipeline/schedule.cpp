#include "pipeline/schedule.hpp"

#include <tbb/blocked_range.h>
#include <tbb/enumerable_thread_specific.h>
#include <tbb/parallel_for.h>
#include <tbb/task_arena.h>

#include <algorithm>
#include <map>
#include <memory>
#include <mutex>
#include <optional>
#include <vector>

#include "piecewise/invert_piecewise.hpp"
#include "pipeline/batch.hpp"
#include "pipeline/formula_path.hpp"
#include "pipeline/workspace.hpp"
#include "space/invert_space.hpp"

namespace bezinv::detail {
namespace {

// One arena per thread count, made on first use and kept: creating one per call costs more than
// a small call's work (docs/README.md, "Threads"). Arenas may be entered from several threads at once.
tbb::task_arena& arena_for(int threads) {
  static std::mutex mutex;
  static std::map<int, std::unique_ptr<tbb::task_arena>> arenas;
  const std::lock_guard<std::mutex> lock(mutex);
  std::unique_ptr<tbb::task_arena>& arena = arenas[threads];
  // A prvalue: binding task_arena::automatic itself to make_unique's reference would odr-use it.
  const int concurrency = threads > 0 ? threads : int{tbb::task_arena::automatic};
  if (!arena) arena = std::make_unique<tbb::task_arena>(concurrency);
  return *arena;
}

// Runs of one curve shorter than this are inverted in parallel with each other rather than in
// their batches (invert with many plans).
constexpr std::size_t kShortRun = 8 * kBatchLanes;

// body(begin, end) for every batch, then end_of_range() after each range of batches a thread runs.
template <typename Body, typename EndOfRange>
void for_each_batch(std::size_t count, const InvertOptions& options, Body&& body, EndOfRange&& end_of_range) {
  const std::size_t batches = (count + kBatchLanes - 1) / kBatchLanes;
  auto run = [&](const tbb::blocked_range<std::size_t>& range) {
    const QueueScope scope;
    for (std::size_t b = range.begin(); b != range.end(); ++b)
      body(b * kBatchLanes, std::min(count, (b + 1) * kBatchLanes));
    end_of_range();
  };
  if (options.threads == 1 || batches <= 1) {
    run(tbb::blocked_range<std::size_t>(0, batches));
    return;
  }
  arena_for(options.threads).execute([&] { tbb::parallel_for(tbb::blocked_range<std::size_t>(0, batches, 4), run); });
}

}  // namespace

void invert_curve(const PlanData& plan, std::span<const Point> points, std::span<PointResult> results,
                  const InvertOptions& options, StageSeconds* stages) {
  // Stage times are summed per thread, then added up (seconds of work, not wall time). The
  // per-thread clocks only when asked for: made on every call, they cost more than a run of a few
  // points of a file of many curves.
  std::optional<tbb::enumerable_thread_specific<StageSeconds>> per_thread;
  if (stages) per_thread.emplace();
  auto local = [&]() -> StageSeconds* { return per_thread ? &per_thread->local() : nullptr; };
  // automatic: the curve's own inversion formula where this call's points repay making it. Made
  // here, before the threads start: the others would wait for the one that makes it.
  InvertOptions run_options = options;
  if (repays_curve_formula(plan, options, points.size())) {
    run_options.algebraic = Algebraic::formula;
    formula_path_data(plan);
  }
  for_each_batch(
      points.size(), run_options,
      [&](std::size_t begin, std::size_t end) {
        invert_batch(plan, points.data() + begin, results.data() + begin, end - begin, run_options, local());
      },
      [&] { flush_queues(plan, run_options, local()); });
  if (per_thread)
    for (const StageSeconds& s : *per_thread) {
      stages->form_b += s.form_b; stages->kernel += s.kernel; stages->read_out += s.read_out;
      stages->refine += s.refine; stages->off_curve += s.off_curve; stages->decide += s.decide;
    }
}

void for_each_range(std::size_t count, const InvertOptions& options,
                    const std::function<void(std::size_t, std::size_t)>& body, std::size_t grain) {
  if (options.threads == 1 || count <= grain) return body(0, count);
  arena_for(options.threads).execute([&] {
    tbb::parallel_for(tbb::blocked_range<std::size_t>(0, count, grain),
                      [&](const auto& range) { body(range.begin(), range.end()); });
  });
}

void invert_curves(std::span<const InversionPlan> plans, std::span<const int> curve_of, std::span<const Point> points,
                   std::span<const double> z, std::span<PointResult> results, const InvertOptions& options) {
  // Batches must hold points of one curve: runs of consecutive points of the same curve are
  // inverted in place (the common case: files grouped by curve); a point whose curve differs from
  // both neighbours forms a run of one. Rejected rows (curve_of < 0) keep what the caller set.
  // A long run is parallel in its batches; the short ones (many curves of few points each) are
  // parallel among themselves instead, each on one thread: shorter than a batch, a run alone
  // would leave the other threads idle.
  struct Run { std::size_t begin, end; };
  std::vector<Run> short_runs;
  std::size_t begin = 0;
  const std::size_t count = points.size();
  auto invert_run = [&](const Run& run, const InvertOptions& run_options) {
    const PlanData& plan = plan_data(plans[curve_of[run.begin]]);
    const std::size_t length = run.end - run.begin;
    if (plan.piecewise)
      invert_piecewise(plan, points.subspan(run.begin, length), z.empty() ? z : z.subspan(run.begin, length),
                       results.subspan(run.begin, length), run_options, nullptr);
    else if (plan.space)
      invert_space_curve(plan, points.subspan(run.begin, length), z.subspan(run.begin, length),
                         results.subspan(run.begin, length), run_options, nullptr);
    else
      invert_curve(plan, points.subspan(run.begin, length), results.subspan(run.begin, length), run_options, nullptr);
  };
  while (begin < count) {
    std::size_t end = begin + 1;
    while (end < count && curve_of[end] == curve_of[begin]) ++end;
    if (curve_of[begin] >= 0) {
      if (end - begin >= kShortRun || options.threads == 1)
        invert_run({begin, end}, options);
      else
        short_runs.push_back({begin, end});
    }
    begin = end;
  }
  if (short_runs.empty()) return;
  InvertOptions one_thread = options;
  one_thread.threads = 1;
  arena_for(options.threads).execute([&] {
    tbb::parallel_for(tbb::blocked_range<std::size_t>(0, short_runs.size(), 16), [&](const auto& range) {
      for (std::size_t r = range.begin(); r != range.end(); ++r) invert_run(short_runs[r], one_thread);
    });
  });
}

}  // namespace bezinv::detail
