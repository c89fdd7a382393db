// The public entry points of inversion (bezinv/invert.hpp). The pipeline behind them is in
// engine/src/pipeline/ (docs/README.md walks a point through it).
#include "bezinv/invert.hpp"

#include "bezinv/profile.hpp"

#include "bezinv/kernels/batch.hpp"
#include "pipeline/batch.hpp"
#include "pipeline/schedule.hpp"
#include "plan_data.hpp"

namespace bezinv {

const char* to_string(Status status) {
  switch (status) {
    case Status::ok: return "ok";
    case Status::outside_segment: return "outside_segment";
    case Status::double_point: return "double_point";
    case Status::off_curve: return "off_curve";
    case Status::invalid_input: return "invalid_input";
    case Status::failed: return "failed";
  }
  return "?";
}

const char* to_string(Path path) {
  switch (path) {
    case Path::none: return "none";
    case Path::bezout: return "bezout";
    case Path::bezout_pair: return "bezout_pair";
    case Path::sylvester: return "sylvester";
    case Path::nearest: return "nearest";
    case Path::bezout_lu: return "bezout_lu";
    case Path::formula: return "formula";
    case Path::projection: return "projection";
  }
  return "?";
}

const char* to_string(OffCurve off_curve) {
  switch (off_curve) {
    case OffCurve::nearest: return "nearest";
    case OffCurve::projection: return "projection";
  }
  return "?";
}

std::string_view active_kernel_name() {
  // The lane-batched implementation (degrees <= kLaneBatchedSvdMaxDegree; Eigen per matrix above).
  return kernels::active_implementation().name;
}

PointResult invert_point(const InversionPlan& plan, Point point, const InvertOptions& options) {
  PointResult r;
  const detail::QueueScope scope;
  const detail::PlanData& data = detail::plan_data(plan);
  detail::invert_batch(data, &point, &r, 1, options, nullptr);
  detail::flush_queues(data, options, nullptr);
  return r;
}

void invert(const InversionPlan& plan, std::span<const Point> points, std::span<PointResult> results,
            const InvertOptions& options) {
  detail::invert_curve(detail::plan_data(plan), points, results, options, nullptr);
}

void invert(const InversionPlan& plan, std::span<const Point> points, std::span<PointResult> results,
            const InvertOptions& options, StageSeconds& stages) {
  detail::invert_curve(detail::plan_data(plan), points, results, options, &stages);
}

void invert(std::span<const InversionPlan> plans, std::span<const int> curve_of, std::span<const Point> points,
            std::span<PointResult> results, const InvertOptions& options) {
  detail::invert_curves(plans, curve_of, points, results, options);
}

}  // namespace bezinv
