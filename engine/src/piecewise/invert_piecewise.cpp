#include "piecewise/invert_piecewise.hpp"

#include <algorithm>
#include <mutex>
#include <vector>

#include "piecewise/piecewise_plan.hpp"
#include "piecewise/whole_curve_answer.hpp"
#include "pipeline/schedule.hpp"
#include "space/invert_space.hpp"

namespace bezinv::detail {

void invert_piecewise(const PlanData& plan, std::span<const Point> points, std::span<const double> z,
                      std::span<PointResult> results, const InvertOptions& options, StageSeconds* stages) {
  const PiecewiseData& curve = *plan.piecewise;
  const std::size_t spans = curve.spans.size();
  // Each span at the whole curve's distance tolerance. Its off_curve rows must be the nearest point
  // of its segment (the whole curve's nearest is the nearest of those), so no projection.
  std::vector<InvertOptions> span_options(spans, options);
  for (std::size_t k = 0; k < spans; ++k) {
    span_options[k].relative_tolerance = options.relative_tolerance * curve.spans[k].tolerance_factor;
    span_options[k].off_curve = OffCurve::nearest;
    span_options[k].threads = 1;  // each block on the thread that combines its answers
  }
  // Blocks of points, every span's answers to a block kept until the block is combined; the
  // blocks in parallel, each on one thread, so the answers do not depend on the thread count.
  constexpr std::size_t kMaxBlock = 1024;
  const std::size_t count = points.size(), block_size = std::min(kMaxBlock, count);  // few points: buffers no larger
  if (count == 0) return;
  const std::size_t blocks = (count + block_size - 1) / block_size;
  std::mutex clock_mutex;
  for_each_range(
      blocks, options,
      [&](std::size_t first_block, std::size_t last_block) {
        std::vector<PointResult> answers(spans * block_size);  // span k's answer to point i at k * block_size + i
        std::vector<PointResult> of_point(spans);
        StageSeconds local;
        for (std::size_t block = first_block; block < last_block; ++block) {
          const std::size_t begin = block * block_size, size = std::min(count, begin + block_size) - begin;
          for (std::size_t k = 0; k < spans; ++k) {
            const PlanData& span = plan_data(curve.spans[k].plan);
            const std::span<PointResult> out(answers.data() + k * block_size, size);
            if (span.space)
              invert_space_curve(span, points.subspan(begin, size), z.subspan(begin, size), out, span_options[k],
                                 stages ? &local : nullptr);
            else
              invert_curve(span, points.subspan(begin, size), out, span_options[k], stages ? &local : nullptr);
          }
          for (std::size_t i = 0; i < size; ++i) {
            for (std::size_t k = 0; k < spans; ++k) of_point[k] = answers[k * block_size + i];
            const Point& p = points[begin + i];
            results[begin + i] =
                whole_curve_answer(curve, {p.x, p.y, curve.dimension == 3 ? z[begin + i] : 0.0}, of_point, options);
          }
        }
        if (!stages) return;
        const std::lock_guard<std::mutex> lock(clock_mutex);
        stages->form_b += local.form_b; stages->kernel += local.kernel; stages->read_out += local.read_out;
        stages->refine += local.refine; stages->off_curve += local.off_curve; stages->decide += local.decide;
        stages->space += local.space;
      },
      1);
}

}  // namespace bezinv::detail
