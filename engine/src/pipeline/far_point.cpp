#include "pipeline/far_point.hpp"

#include <algorithm>
#include <cmath>

#include "refine.hpp"

namespace bezinv::detail {

void answer_far_point(const PlanData& plan, const Point& point, PointResult& r) {
  // The direction from the centre, in coordinates scaled by a power of two so nothing overflows.
  const int e = std::max(std::ilogb(std::max(std::abs(point.x), std::abs(point.y))),
                         std::ilogb(std::max({std::abs(plan.centre[0]), std::abs(plan.centre[1]), 1.0})));
  const double dx = std::ldexp(point.x, -e) - std::ldexp(plan.centre[0], -e);
  const double dy = std::ldexp(point.y, -e) - std::ldexp(plan.centre[1], -e);
  const double a = plan.cos_rotation * dx - plan.sin_rotation * dy, b = plan.sin_rotation * dx + plan.cos_rotation * dy;
  const double length = std::hypot(a, b);
  r = PointResult{};
  r.status = Status::off_curve;
  r.path = Path::nearest;
  r.t = detail::nearest_parameter_on_segment(plan, kFarStandIn * a / length, kFarStandIn * b / length, -1.0);
  // |P(t) - P0| in input units, halved first so the differences do not overflow (inf only when
  // the distance itself exceeds the largest double).
  const auto p = plan.curve.point(r.t);
  r.residual = 2 * std::hypot(0.5 * p[0] - 0.5 * point.x, 0.5 * p[1] - 0.5 * point.y);
}

}  // namespace bezinv::detail
