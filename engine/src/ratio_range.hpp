#pragma once
// The range of one coordinate x(t) = num(t) / den(t) of a curve over its segment t in [0, 1],
// from the Bernstein coefficients alone: what sizes a plan (the tolerance is relative to it).
#include <span>

namespace bezinv::detail {

struct RatioRange {
  double lo, hi;
};

// Whether the ratios num_i / den_i bound x(t) on [0, 1]: every den_i of one strict sign and every
// ratio finite. Then x(t) = sum_i w_i(t) (num_i / den_i) with w_i = den_i B_i(t) / den(t) >= 0
// summing to 1, a convex combination of the ratios (the control points of a rational Bezier curve).
bool ratios_bound(std::span<const double> num, std::span<const double> den);

// The smallest and largest of the ratios where ratios_bound holds. Where it does not (a zero
// coefficient of den, a "control point at infinity"; coefficients of both signs; a ratio that
// overflows), the segment is halved by de Casteljau until the pieces' ratios bound them: den has no
// root on [0, 1] (validate), so on short enough pieces its coefficients all take its sign. A piece
// still not bounded after kRatioRangeHalvings levels (a den within rounding of a root), or once
// kRatioRangePieces pieces are spent (ratios that overflow everywhere), counts by its end points only.
RatioRange ratio_range(std::span<const double> num, std::span<const double> den);

}  // namespace bezinv::detail
