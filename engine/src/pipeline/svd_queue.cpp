#include "pipeline/svd_queue.hpp"

#include "pipeline/stage_clock.hpp"
#include "pipeline/svd_path.hpp"

namespace bezinv::detail {

SvdQueue& svd_queue() {
  thread_local SvdQueue queue;
  return queue;
}

void flush_svd_queue(const PlanData& plan, const InvertOptions& options, StageSeconds* stages) {
  SvdQueue& queue = svd_queue();
  if (queue.size == 0) return;
  StageClock clock(stages);
  const std::size_t m = queue.size;
  queue.size = 0;
  svd_path(plan, queue.B.data(), queue.u.data(), queue.v.data(), queue.target.data(), m, options,
           batch_workspace(), clock);
}

}  // namespace bezinv::detail
