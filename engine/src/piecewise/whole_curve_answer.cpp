#include "piecewise/whole_curve_answer.hpp"

#include <algorithm>
#include <cmath>
#include <vector>

#include "bezinv/tolerances.hpp"
#include "plan_data.hpp"
#include "refine.hpp"
#include "space/space_curve.hpp"

namespace bezinv::detail {
namespace {

struct SpanCandidate {
  std::size_t span;
  double s, t, residual;    // span parameter, whole-curve parameter, |P - point| (input units)
  const PointResult* from;  // the span's answer it comes from
};

// Whether the curve leaves the tolerance of the point somewhere from (span a, s_a) to (span b,
// s_b), a before b: kBranchSamples parameters inside each span's stretch of the way.
bool leaves(const PiecewiseData& curve, const std::array<double, 3>& point, std::size_t a, double s_a, std::size_t b,
            double s_b, double tolerance) {
  for (std::size_t k = a; k <= b; ++k) {
    const double from = k == a ? s_a : 0.0, to = k == b ? s_b : 1.0;
    for (int i = 1; i <= kBranchSamples; ++i)
      if (!(curve.distance(k, from + (to - from) * i / (kBranchSamples + 1), point) <= tolerance)) return true;
  }
  return false;
}

// Two candidates on separate branches: the curve leaves the tolerance between them, and on a
// closed curve also on the way round through its ends.
bool separate(const PiecewiseData& curve, const std::array<double, 3>& point, const SpanCandidate& x, const SpanCandidate& y,
              double tolerance, bool closed) {
  if (x.t == y.t) return false;
  const SpanCandidate& lo = x.t < y.t ? x : y;
  const SpanCandidate& hi = x.t < y.t ? y : x;
  if (lo.span == hi.span && hi.s - lo.s <= kDistinctParameterGap) return false;
  if (!leaves(curve, point, lo.span, lo.s, hi.span, hi.s, tolerance)) return false;
  if (!closed) return true;
  return leaves(curve, point, hi.span, hi.s, curve.spans.size() - 1, 1.0, tolerance) ||
         leaves(curve, point, 0, 0.0, lo.span, lo.s, tolerance);
}

// The nearest point of span k's segment [0, 1], for a span whose answer was not on it.
SpanCandidate nearest_on_span(const PiecewiseData& curve, std::size_t k, const std::array<double, 3>& point,
                          const PointResult& answer) {
  const PlanData& plan = plan_data(curve.spans[k].plan);
  double s = PointResult::nan, residual = PointResult::nan;
  if (plan.space) {
    const SpaceRefined r = space_nearest(*plan.space, space_normalize(*plan.space, point[0], point[1], point[2]));
    s = r.t;
    residual = r.distance * plan.space->scale;
  } else {
    const auto uv = plan.normalize(point[0], point[1]);
    if (std::isfinite(uv[0]) && std::isfinite(uv[1])) {
      s = nearest_parameter_on_segment(plan, uv[0], uv[1], std::clamp(answer.t, 0.0, 1.0));
      residual = detail::distance(plan, uv[0], uv[1], s) * plan.scale;
    }
  }
  return {k, s, curve.parameter(k, s), residual, &answer};
}

bool nearer(const SpanCandidate& a, const SpanCandidate& b) {
  return a.residual < b.residual || (a.residual == b.residual && a.t < b.t);
}

PointResult answer_from(const SpanCandidate& c, Status status) {
  PointResult r = *c.from;
  r.t = c.t;
  r.residual = c.residual;
  r.status = status;
  r.t2 = PointResult::nan;
  return r;
}

}  // namespace

PointResult whole_curve_answer(const PiecewiseData& curve, const std::array<double, 3>& point,
                               std::span<const PointResult> answers, const InvertOptions& options) {
  const std::size_t last = curve.spans.size() - 1;
  const double tolerance = curve.tolerance(options);
  const bool closed = std::hypot(curve.first_point[0] - curve.last_point[0], curve.first_point[1] - curve.last_point[1],
                                 curve.first_point[2] - curve.last_point[2]) <= tolerance;
  std::vector<SpanCandidate> on_segment, beyond_ends;
  const PointResult* failed = nullptr;
  for (std::size_t k = 0; k <= last; ++k) {
    const PointResult& r = answers[k];
    switch (r.status) {
      case Status::invalid_input: return r;  // the point's own fault: every span says so
      case Status::failed: failed = failed ? failed : &r; break;
      case Status::ok: on_segment.push_back({k, r.t, curve.parameter(k, r.t), r.residual, &r}); break;
      case Status::double_point:
        on_segment.push_back({k, r.t, curve.parameter(k, r.t), r.residual, &r});
        on_segment.push_back({k, r.t2, curve.parameter(k, r.t2), curve.distance(k, r.t2, point), &r});
        break;
      case Status::outside_segment:
        if ((k == 0 && r.t < 0) || (k == last && r.t > 1))
          beyond_ends.push_back({k, r.t, curve.parameter(k, r.t), r.residual, &r});
        break;
      case Status::off_curve: break;
    }
  }

  if (!on_segment.empty()) {
    const SpanCandidate* best = &on_segment.front();
    for (const SpanCandidate& c : on_segment)
      if (nearer(c, *best)) best = &c;
    const SpanCandidate* second = nullptr;
    for (const SpanCandidate& c : on_segment)
      if ((!second || nearer(c, *second)) && separate(curve, point, *best, c, tolerance, closed)) second = &c;
    if (second) {
      const SpanCandidate& lo = best->t < second->t ? *best : *second;
      const SpanCandidate& hi = best->t < second->t ? *second : *best;
      PointResult r = answer_from(lo, Status::double_point);
      r.t2 = hi.t;
      return r;
    }
    PointResult r = answer_from(*best, Status::ok);
    // A closed curve's end is its start: a point there is one point, reported at the start of the
    // domain. "There": the start is as near as the best candidate, to the input's resolution (a
    // point just before the end keeps its own parameter).
    if (closed && best->span == last && (best->s == 1.0 || !leaves(curve, point, last, best->s, last, 1.0, tolerance))) {
      const double residual = curve.distance(0, 0.0, point);
      if (residual <= std::min(tolerance, best->residual + curve.resolution)) r.t = curve.domain[0], r.residual = residual;
    }
    return r;
  }

  if (!beyond_ends.empty()) {
    const SpanCandidate* best = &beyond_ends.front();
    for (const SpanCandidate& c : beyond_ends)
      if (nearer(c, *best)) best = &c;
    return answer_from(*best, Status::outside_segment);
  }

  // Off the curve: the nearest of the spans' nearest points on their segments.
  std::vector<SpanCandidate> nearest;
  for (std::size_t k = 0; k <= last; ++k) {
    const PointResult& r = answers[k];
    if (r.status == Status::off_curve) nearest.push_back({k, r.t, curve.parameter(k, r.t), r.residual, &r});
    if (r.status == Status::outside_segment) nearest.push_back(nearest_on_span(curve, k, point, r));
  }
  const SpanCandidate* best = nullptr;
  for (const SpanCandidate& c : nearest)
    if (std::isfinite(c.residual) && (!best || nearer(c, *best))) best = &c;
  if (!best) return failed ? *failed : answers.front();
  PointResult r = answer_from(*best, Status::off_curve);
  if (best->from->status != Status::off_curve) {
    r.path = Path::nearest;
    r.sigma_min = r.sigma_next = PointResult::nan;
  }
  return r;
}

}  // namespace bezinv::detail
