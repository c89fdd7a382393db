// A NURBS or composite curve as rational Bezier spans (bezinv/nurbs.hpp).
#include <cmath>
#include <utility>

#include "bezinv/nurbs.hpp"
#include "piecewise/homogeneous_spline.hpp"
#include "piecewise/knot_insertion.hpp"

namespace bezinv {
namespace {

// A span's homogeneous control points as a Bezier curve: rational_bezier's layout (numerators
// w x, denominators w), or bezier where every weight of the spline is 1 (their combinations are
// 1 too; kept exact so the span is polynomial).
Curve span_curve(const Curve& nurbs, const detail::HomogeneousSpan& span, bool polynomial) {
  Curve c;
  c.id = nurbs.id;
  c.kind = polynomial ? CurveKind::bezier : CurveKind::rational_bezier;
  for (const auto& q : span.points) {
    c.x_num.push_back(q[0]);
    c.y_num.push_back(q[1]);
    c.x_den.push_back(polynomial ? 1.0 : q[3]);
    if (nurbs.dimension() == 3) c.z_num.push_back(q[2]);
  }
  c.y_den = c.x_den;
  if (nurbs.dimension() == 3) c.z_den = c.x_den;
  return c;
}

}  // namespace

std::array<double, 2> parameter_domain(const Curve& curve) {
  if (curve.kind == CurveKind::nurbs) {
    const std::size_t p = static_cast<std::size_t>(curve.degree());
    return {curve.knots[p], curve.knots[curve.knots.size() - 1 - p]};
  }
  if (curve.kind == CurveKind::composite) return {0.0, static_cast<double>(curve.curves.size())};
  return {0.0, 1.0};
}

std::vector<BezierSpan> bezier_spans(const Curve& curve) {
  std::vector<BezierSpan> spans;
  if (curve.kind == CurveKind::nurbs) {
    bool polynomial = true;
    for (const double w : curve.x_den) polynomial = polynomial && w == 1.0;
    for (const auto& span : detail::bezier_decomposition(detail::homogeneous_spline(curve)))
      spans.push_back({span_curve(curve, span, polynomial), span.start, span.end});
    return spans;
  }
  if (curve.kind != CurveKind::composite) return {{curve, 0.0, 1.0}};
  for (std::size_t k = 0; k < curve.curves.size(); ++k) {
    const Curve& part = curve.curves[k];
    const double offset = static_cast<double>(k);
    if (part.kind != CurveKind::nurbs) {
      spans.push_back({part, offset, offset + 1});
      continue;
    }
    // Curve k's knot parameter normalized to [0, 1] over its domain [a, b]: (u - a) / (b - a) is
    // exactly 0 and 1 at the ends, so consecutive curves' spans meet at the same parameter.
    const auto [a, b] = parameter_domain(part);
    for (BezierSpan& span : bezier_spans(part)) {
      span.start = offset + (span.start - a) / (b - a);
      span.end = offset + (span.end - a) / (b - a);
      spans.push_back(std::move(span));
    }
  }
  return spans;
}

}  // namespace bezinv
