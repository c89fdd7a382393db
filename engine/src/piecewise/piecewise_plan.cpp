#include "piecewise/piecewise_plan.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include "bezinv/nurbs.hpp"
#include "bezinv/tolerances.hpp"
#include "piecewise/control_box.hpp"

namespace bezinv::detail {

double PiecewiseData::tolerance(const InvertOptions& options) const {
  return std::max(options.relative_tolerance * diagonal, resolution);
}

double PiecewiseData::parameter(std::size_t k, double s) const { return std::lerp(spans[k].start, spans[k].end, s); }

double PiecewiseData::distance(std::size_t k, double s, const std::array<double, 3>& point) const {
  const auto p = spans[k].plan.curve().point3(s);
  return std::hypot(p[0] - point[0], p[1] - point[1], p[2] - point[2]);
}

double PiecewiseData::box_distance(std::size_t k, const std::array<double, 3>& point) const {
  const ControlBox& box = spans[k].box;
  double outside[3];
  for (int i = 0; i < 3; ++i) outside[i] = std::max({box.lo[i] - point[i], point[i] - box.hi[i], 0.0});
  const double d = std::hypot(outside[0], outside[1], outside[2]);
  return std::isfinite(d) ? d : std::numeric_limits<double>::quiet_NaN();
}

PiecewiseData make_piecewise_data(const Curve& curve) {
  validate(curve);
  PiecewiseData data;
  data.dimension = curve.dimension();
  const ControlBox box = control_box(curve);
  data.diagonal = box.diagonal();
  const double magnitude = box.magnitude();
  data.resolution = kResolutionUlps * (std::nextafter(magnitude, std::numeric_limits<double>::infinity()) - magnitude);
  data.domain = parameter_domain(curve);
  for (BezierSpan& span : bezier_spans(curve)) {
    PiecewiseSpan s;
    s.plan = make_plan(span.curve);
    s.start = span.start;
    s.end = span.end;
    s.box = control_box(span.curve);
    const double d = s.plan.diagonal();
    if (d > 0 && std::isfinite(d) && std::isfinite(data.diagonal)) s.tolerance_factor = data.diagonal / d;
    data.spans.push_back(std::move(s));
  }
  data.first_point = data.spans.front().plan.curve().point3(0.0);
  data.last_point = data.spans.back().plan.curve().point3(1.0);
  return data;
}

}  // namespace bezinv::detail
