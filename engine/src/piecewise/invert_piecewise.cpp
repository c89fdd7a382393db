#include "piecewise/invert_piecewise.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
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
  //
  // A span is asked only about the points that its answer could change (the whole answer is the
  // same as with every span asked, bit for bit): the first and last spans always (their extensions
  // give outside_segment), and any span whose box is within twice the tolerance of the point (an
  // ok or double_point answer needs the point within the tolerance of the span's segment, which
  // lies in its box). A span not asked answers off_curve at an infinite distance, which the whole
  // answer passes over. Where that answer is then off_curve (or failed), the spans not asked whose
  // box is as near as its nearest point are asked after all, and the answer made again.
  constexpr std::size_t kMaxBlock = 1024;
  const std::size_t count = points.size(), block_size = std::min(kMaxBlock, count);  // few points: buffers no larger
  if (count == 0) return;
  const std::size_t blocks = (count + block_size - 1) / block_size;
  const double reach = 2 * curve.tolerance(options);
  PointResult not_asked;
  not_asked.status = Status::off_curve;
  not_asked.residual = std::numeric_limits<double>::infinity();
  std::mutex clock_mutex;
  for_each_range(
      blocks, options,
      [&](std::size_t first_block, std::size_t last_block) {
        std::vector<PointResult> answers(spans * block_size);  // span k's answer to point i at k * block_size + i
        std::vector<double> box_distances(spans * block_size);
        std::vector<std::size_t> asked;  // the block's points span k is asked about
        std::vector<Point> asked_points;
        std::vector<double> asked_z;
        std::vector<PointResult> asked_answers;
        std::vector<PointResult> of_point(spans);
        StageSeconds local;
        auto ask = [&](std::size_t k, std::span<const Point> xy, std::span<const double> zs, std::span<PointResult> out) {
          const PlanData& span = plan_data(curve.spans[k].plan);
          if (span.space)
            invert_space_curve(span, xy, zs, out, span_options[k], stages ? &local : nullptr);
          else
            invert_curve(span, xy, out, span_options[k], stages ? &local : nullptr);
        };
        auto at = [&](std::size_t i) {
          const Point& p = points[i];
          return std::array<double, 3>{p.x, p.y, curve.dimension == 3 ? z[i] : 0.0};
        };
        for (std::size_t block = first_block; block < last_block; ++block) {
          const std::size_t begin = block * block_size, size = std::min(count, begin + block_size) - begin;
          for (std::size_t k = 0; k < spans; ++k) {
            asked.clear();
            for (std::size_t i = 0; i < size; ++i) {
              const double d = curve.box_distance(k, at(begin + i));
              box_distances[k * block_size + i] = d;
              if (k == 0 || k + 1 == spans || !(d > reach)) asked.push_back(i);
              else answers[k * block_size + i] = not_asked;
            }
            if (asked.size() == size) {
              ask(k, points.subspan(begin, size), z.empty() ? z : z.subspan(begin, size),
                  std::span(answers.data() + k * block_size, size));
              continue;
            }
            asked_points.resize(asked.size());
            asked_z.resize(z.empty() ? 0 : asked.size());
            asked_answers.resize(asked.size());
            for (std::size_t j = 0; j < asked.size(); ++j) {
              asked_points[j] = points[begin + asked[j]];
              if (!z.empty()) asked_z[j] = z[begin + asked[j]];
            }
            ask(k, asked_points, asked_z, asked_answers);
            for (std::size_t j = 0; j < asked.size(); ++j) answers[k * block_size + asked[j]] = asked_answers[j];
          }
          for (std::size_t i = 0; i < size; ++i) {
            for (std::size_t k = 0; k < spans; ++k) of_point[k] = answers[k * block_size + i];
            const std::array<double, 3> point = at(begin + i);
            PointResult r = whole_curve_answer(curve, point, of_point, options);
            if (r.status == Status::off_curve || r.status == Status::failed) {
              // Nearer than its nearest point, to the input's resolution: a span not asked may hold it.
              const double nearest = r.status == Status::off_curve && std::isfinite(r.residual)
                                         ? r.residual + curve.resolution
                                         : std::numeric_limits<double>::infinity();
              bool asked_more = false;
              for (std::size_t k = 1; k + 1 < spans; ++k) {
                if (box_distances[k * block_size + i] > nearest) continue;
                if (!(box_distances[k * block_size + i] > reach)) continue;  // asked already
                ask(k, points.subspan(begin + i, 1), z.empty() ? z : z.subspan(begin + i, 1), std::span(&of_point[k], 1));
                asked_more = true;
              }
              if (asked_more) r = whole_curve_answer(curve, point, of_point, options);
            }
            results[begin + i] = r;
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
