#pragma once
// NURBS and composite curves as rational Bezier spans (docs/nurbs-and-composite.md).
//
// A curve of kind nurbs or composite (bezinv/curve.hpp) is inverted span by span: knot insertion
// (Boehm) to full multiplicity turns a NURBS into one rational Bezier curve per non-empty knot
// interval of its domain, and a composite is the spans of its curves in order. Each span s in
// [0, 1] is the stretch [start, end] of the whole curve's parameter:
//   nurbs       the knot parameter u in [knots[p], knots[m - p]] (m + 1 knots, degree p): the span
//               of [u_i, u_{i+1}] has t = u_i + s (u_{i+1} - u_i)
//   composite   curve k covers [k, k + 1]: t = k + its own parameter, a nurbs curve's normalized to
//               [0, 1] over its domain
//   the others  one span, [0, 1]
// make_plan plans every span; invert answers for the whole curve, in that parameter.
#include <array>
#include <vector>

#include "bezinv/curve.hpp"

namespace bezinv {

struct BezierSpan {
  Curve curve;       // kind bezier or rational_bezier (a composite's curves of other kinds as given)
  double start = 0;  // the whole curve's parameter at s = 0 and at s = 1: t = lerp(start, end, s)
  double end = 1;
};

// The spans of a validated curve, in order of the parameter (a curve that is not piecewise: itself,
// [0, 1]). Knot intervals of zero length give no span.
std::vector<BezierSpan> bezier_spans(const Curve& curve);

// The parameters of the curve's two ends: [knots[p], knots[m - p]] for nurbs, [0, number of curves]
// for composite, [0, 1] for the others.
std::array<double, 2> parameter_domain(const Curve& curve);

// Whether the curve is inverted through spans (kind nurbs or composite).
inline bool piecewise(const Curve& curve) {
  return curve.kind == CurveKind::nurbs || curve.kind == CurveKind::composite;
}

}  // namespace bezinv
