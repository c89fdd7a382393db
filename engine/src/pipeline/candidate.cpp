#include "pipeline/candidate.hpp"

#include <cmath>

#include "refine.hpp"

namespace bezinv::detail {

Candidate settle(const PlanData& plan, double u0, double v0, double t_algebraic, Path path,
                 double tolerance, bool refine) {
  Candidate c;
  c.path = path;
  if (!std::isfinite(t_algebraic)) return c;
  const bool inside = t_algebraic >= 0.0 && t_algebraic <= 1.0;
  auto measure = [&](double t) { return detail::distance(plan, u0, v0, t); };
  if (!refine) {
    // The paper's algebraic t. A point within tolerance of an end of the segment whose algebraic t
    // fell just outside [0,1] is on the segment: its t is clamped onto it.
    const double clamped = std::clamp(t_algebraic, 0.0, 1.0);
    c.t = t_algebraic;
    c.distance = measure(t_algebraic);
    if (!inside && measure(clamped) <= tolerance) { c.t = clamped; c.distance = measure(clamped); }
  } else {
    const detail::Refined main = detail::refine_parameter(plan, u0, v0, t_algebraic, /*stay_on_segment=*/inside);
    c.t = main.t;
    c.distance = main.distance;
    const bool at_end = c.t == 0.0 || c.t == 1.0;
    if (inside && at_end && !(c.distance <= tolerance)) {
      // Clamped at an end but not there: the point may be on the extension just past it.
      const detail::Refined beyond = detail::refine_parameter(plan, u0, v0, t_algebraic, false);
      if (beyond.distance < c.distance) { c.t = beyond.t; c.distance = beyond.distance; }
    } else if (!inside) {
      // Started on the extension: the nearest point of the segment wins if it is within tolerance.
      const detail::Refined on_segment =
          detail::refine_parameter(plan, u0, v0, std::clamp(t_algebraic, 0.0, 1.0), true);
      if (on_segment.distance <= tolerance) { c.t = on_segment.t; c.distance = on_segment.distance; }
    }
  }
  classify(c, tolerance);
  return c;
}

}  // namespace bezinv::detail
