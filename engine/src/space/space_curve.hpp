#pragma once
// Space curves (engine internal): a curve in 3D inverted by the plane engine, each answer checked
// in space (docs/space-curves.md).
//
// The method stays the paper's. With r = Z - z0 W beside p = X - x0 W and q = Y - y0 W, the point's
// parameter t0 is a common root of all three. The plan takes two fixed combinations of them,
//     p' = a . (p, q, r),   q' = b . (p, q, r),
// with a, b orthonormal: they are p and q of the plane curve (a . (P - c), b . (P - c)), the space
// curve projected on the plane through the centre c of its control points spanned by their two
// principal axes. B(p', q') is affine in (x0, y0, z0) as the plane B is in (x0, y0), the plane plan
// precomputes it, and its null vector holds t0 (a common root of p, q, r is one of p', q').
//
// What a combination adds are spurious common roots: parameters where the curve and the point
// differ only along the plane's normal, where the projected curve passes through the projected
// point. The projection is a contraction (orthonormal a, b), so whatever is within the tolerance in
// space is within it in the plane: the plane engine misses no parameter. Each of its parameters is
// then refined and measured in space (space_answer), which keeps the real ones and drops the
// spurious ones; a point within the tolerance of no parameter in space is off the curve, answered
// with the nearest point of the segment in space. Principal axes because a plane curve in a tilted
// plane is then projected without distortion (the plane engine sees it as it is), and a space curve
// is spread as widely as it can be, which keeps spurious crossings of the projection rare.
#include <array>
#include <vector>

#include "bezinv/curve.hpp"
#include "bezinv/invert.hpp"

namespace bezinv::detail {

// A polynomial in the Bernstein basis, with c_i C(n, i) kept for Horner's rule: O(n) per value on
// [0, 1] (in s = t / (1 - t), or its mirror past 1/2), de Casteljau outside (the extension).
struct SpacePolynomial {
  std::vector<double> c, binomial_c;
  explicit SpacePolynomial(std::vector<double> coefficients = {});
  double operator()(double t) const;
  int degree() const { return static_cast<int>(c.size()) - 1; }
  // sum_i binomial_c[i] s^i (forward) or sum_i binomial_c[i] s^(m - i) (backward): times u^m
  // (u = 1 - t, s = t / u forward; u = t, s = (1 - t) / u backward) it is the value at t.
  double horner(bool forward, double s) const;
};

struct SpaceData {
  Curve curve;               // as given (validated, dimension 3)
  double diagonal = 0.0;     // of the control points' bounding box, input units
  std::array<double, 3> centre{}, a{}, b{};  // the projection: u = a . (P - centre), v = b . (P - centre)
  // Separate denominators: a and b are two coordinate axes, axes[0] and axes[1], where the curve
  // spreads on that coordinate plane nearly as on its principal plane (kCoordinatePlaneSpread):
  // the projected curve keeps the curve's degree. Else {-1, -1}: the principal plane, over the
  // product of the distinct denominators.
  std::array<int, 2> axes{-1, -1};
  double scale = 1.0, inverse_scale = 1.0;   // normalized units: (P - centre) / scale
  double normalized_resolution = 0.0;        // the coordinates' own resolution (as PlanData's)
  int degree = 0;
  // The normalized curve, coordinate k = num[k] / den[k], and the derivatives' polynomials
  // (degrees n - 1 and n - 2; zero below).
  std::array<SpacePolynomial, 3> num, den, d_num, d_den, dd_num, dd_den;
  // The same for Horner's rule, interleaved: for derivative order r (0, 1, 2), entry i * 8 + j is
  // coefficient i (times C(m, i), m = n - r) of polynomial j = num x, y, z, den x, y, z (6, 7
  // unused): one loop over i evaluates all six side by side.
  std::array<std::vector<double>, 3> interleaved;
  // P and P' in one Horner loop, first_order_width polynomials side by side. With one denominator
  // D for x, y, z (kinds bezier and rational_bezier), width 8: entry i * 8 + j, i = 0..n, is
  // coefficient i of num x, y, z, D (j = 0..3) and of their derivatives (j = 4..7, degree n - 1).
  // With separate denominators, width 16: num x, y, z, den x, y, z (j = 0..5) and their
  // derivatives (j = 8..13; 6, 7, 14, 15 zero). A derivative is padded with a zero where it has no
  // coefficient: at i = n for the forward loop (first_order_forward), before i = 0 for the backward
  // one (first_order_backward, shifted by one). The zero enters Horner's rule as 0 * s + c = c, so
  // every value is the same double as from interleaved[0] and interleaved[1] separately.
  std::vector<double> first_order_forward, first_order_backward;
  int first_order_width = 8;
  std::vector<double> samples;  // P at equally spaced t in [0, 1] (16 (n + 1) + 1 of them), normalized, x y z each
};

// A curve with separate denominators is projected on a coordinate plane where both its spreads
// there (the eigenvalues of its control points' covariance in those two coordinates) are at least
// this fraction of its spreads on its principal plane: at most twice as thin either way.
inline constexpr double kCoordinatePlaneSpread = 0.25;

// The space data of a validated space curve; throws CurveError for one the plane engine cannot take
// (separate denominators, no coordinate plane spread widely enough, and a principal projection
// whose degree exceeds kMaxDegree).
SpaceData make_space_data(const Curve& curve);

// The projected plane curve (the same kind; ids kept), whose plan inverts the projected points.
Curve projected_curve(const SpaceData& space);

// P(t) and its first two derivatives in t, normalized units; |P(t) - P0|.
struct SpaceJet {
  std::array<double, 3> p, dp, ddp;
};
// orders 2: P and P' only; 1: P only (the others zero).
SpaceJet space_jet(const SpaceData& space, double t, int orders = 3);
double space_distance(const SpaceJet& jet, const std::array<double, 3>& point);
double space_distance(const SpaceData& space, const std::array<double, 3>& point, double t);

// Newton's method on (P(t) - P0) . P'(t) = 0 from t0, safeguarded (a step that does not reduce the
// distance is halved), kept in [0, 1] when on_segment: a local minimum of |P(t) - P0| near t0 and
// the distance there.
struct SpaceRefined {
  double t, distance;
};
SpaceRefined space_refine(const SpaceData& space, const std::array<double, 3>& point, double t0, bool on_segment);

// The nearest point of the segment: every local minimum of the distance over the samples (and both
// ends) refined, the nearest kept.
SpaceRefined space_nearest(const SpaceData& space, const std::array<double, 3>& point);

// The normalized point.
inline std::array<double, 3> space_normalize(const SpaceData& space, double x, double y, double z) {
  const double s = space.inverse_scale;
  return {x * s - space.centre[0] * s, y * s - space.centre[1] * s, z * s - space.centre[2] * s};
}

// The space answer from the plane engine's answer r (for the projected point) to the normalized
// point, the tolerance in normalized units.
void space_answer(const SpaceData& space, const std::array<double, 3>& point, double tolerance,
                  const InvertOptions& options, PointResult& r);

}  // namespace bezinv::detail
