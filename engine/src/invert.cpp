// The public entry points of inversion (bezinv/invert.hpp). The pipeline behind them is in
// engine/src/pipeline/ (docs/README.md walks a point through it).
#include "bezinv/invert.hpp"

#include <stdexcept>
#include <string>
#include <vector>

#include "bezinv/kernels/batch.hpp"
#include "bezinv/profile.hpp"
#include "pipeline/batch.hpp"
#include "pipeline/schedule.hpp"
#include "piecewise/invert_piecewise.hpp"
#include "plan_data.hpp"
#include "quote.hpp"
#include "space/invert_space.hpp"

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

bool algebraic_named(std::string_view name, Algebraic& algebraic) {
  if (name == "bezout") algebraic = Algebraic::bezout;
  else if (name == "formula") algebraic = Algebraic::formula;
  else if (name == "auto") algebraic = Algebraic::automatic;
  else return false;
  return true;
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

namespace {

void require_dimension(const InversionPlan& plan, int dimension) {
  if (plan.dimension() != dimension)
    throw std::invalid_argument("bezinv::invert: curve " + detail::quoted_excerpt(plan.curve().id) + " is a " +
                                (plan.dimension() == 3 ? "space curve: its points need z (Point3)"
                                                       : "plane curve: its points are Point (x, y)"));
}

}  // namespace

PointResult invert_point(const InversionPlan& plan, Point point, const InvertOptions& options) {
  require_dimension(plan, 2);
  PointResult r;
  const detail::PlanData& data = detail::plan_data(plan);
  if (data.piecewise) {
    detail::invert_piecewise(data, std::span<const Point>(&point, 1), {}, std::span<PointResult>(&r, 1), options, nullptr);
    return r;
  }
  const detail::QueueScope scope;
  detail::invert_batch(data, &point, &r, 1, options, nullptr);
  detail::flush_queues(data, options, nullptr);
  return r;
}

void invert(const InversionPlan& plan, std::span<const Point> points, std::span<PointResult> results,
            const InvertOptions& options) {
  require_dimension(plan, 2);
  if (detail::plan_data(plan).piecewise)
    return detail::invert_piecewise(detail::plan_data(plan), points, {}, results, options, nullptr);
  detail::invert_curve(detail::plan_data(plan), points, results, options, nullptr);
}

void invert(const InversionPlan& plan, std::span<const Point> points, std::span<PointResult> results,
            const InvertOptions& options, StageSeconds& stages) {
  require_dimension(plan, 2);
  if (detail::plan_data(plan).piecewise)
    return detail::invert_piecewise(detail::plan_data(plan), points, {}, results, options, &stages);
  detail::invert_curve(detail::plan_data(plan), points, results, options, &stages);
}

void invert(std::span<const InversionPlan> plans, std::span<const int> curve_of, std::span<const Point> points,
            std::span<PointResult> results, const InvertOptions& options) {
  for (std::size_t i = 0; i < curve_of.size(); ++i)
    if (curve_of[i] >= 0 && (i == 0 || curve_of[i] != curve_of[i - 1])) require_dimension(plans[curve_of[i]], 2);
  detail::invert_curves(plans, curve_of, points, {}, results, options);
}

PointResult invert_point(const InversionPlan& plan, Point3 point, const InvertOptions& options) {
  PointResult r;
  invert(plan, std::span<const Point3>(&point, 1), std::span<PointResult>(&r, 1), options);
  return r;
}

namespace {

void invert_space(const InversionPlan& plan, std::span<const Point3> points, std::span<PointResult> results,
                  const InvertOptions& options, StageSeconds* stages) {
  require_dimension(plan, 3);
  std::vector<Point> xy(points.size());
  std::vector<double> z(points.size());
  for (std::size_t i = 0; i < points.size(); ++i) xy[i] = {points[i].x, points[i].y}, z[i] = points[i].z;
  if (detail::plan_data(plan).piecewise)
    return detail::invert_piecewise(detail::plan_data(plan), xy, z, results, options, stages);
  detail::invert_space_curve(detail::plan_data(plan), xy, z, results, options, stages);
}

}  // namespace

void invert(const InversionPlan& plan, std::span<const Point3> points, std::span<PointResult> results,
            const InvertOptions& options) {
  invert_space(plan, points, results, options, nullptr);
}

void invert(const InversionPlan& plan, std::span<const Point3> points, std::span<PointResult> results,
            const InvertOptions& options, StageSeconds& stages) {
  invert_space(plan, points, results, options, &stages);
}

void invert(std::span<const InversionPlan> plans, std::span<const int> curve_of, std::span<const Point> points,
            std::span<const double> z, std::span<PointResult> results, const InvertOptions& options) {
  bool space = false;  // (looked at once per run of one curve: files are usually grouped by curve)
  for (std::size_t i = 0; i < curve_of.size() && !space; ++i)
    space = curve_of[i] >= 0 && (i == 0 || curve_of[i] != curve_of[i - 1]) && plans[curve_of[i]].dimension() == 3;
  if (space && z.size() != points.size())
    throw std::invalid_argument("bezinv::invert: points of space curves need z for every point");
  detail::invert_curves(plans, curve_of, points, z, results, options);
}

}  // namespace bezinv
