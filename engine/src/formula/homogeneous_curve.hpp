#pragma once
// The plan's normalized curve as one homogeneous polynomial curve (U, V, W)(t), the form in which
// polynomials in the plane are composed with it (the inversion formula, the implicit equation):
//     common denominator   (x_num, y_num, x_den)                       degree n
//     separate ones        (x_num y_den, y_num x_den, x_den y_den)     degree 2n
// then moved to the frame where the segment's box is [-1, 1]^2 (formula_curve): (u, v) =
// (U / W, V / W) are that frame's coordinates (bezinv/plane_polynomial.hpp).
#include <array>
#include <vector>

#include "bezinv/plane_polynomial.hpp"
#include "plan_data.hpp"

namespace bezinv::detail {

struct HomogeneousCurve {
  std::vector<double> u, v, w;  // Bernstein coefficients, one degree

  int degree() const { return static_cast<int>(w.size()) - 1; }
  // (U, V, W)(t), scaled so that its largest component is 1 (a homogeneous point).
  std::array<double, 3> at(double t) const;
  // The curve's point at t = infinity: the coefficients of the highest power of t that is not
  // negligible in all three (scaled as at()). W = 0 there when the curve goes to infinity.
  std::array<double, 3> at_infinity() const;
  // (U, V, W) at the homogeneous parameter (a, b), t = b / (a + b): de Casteljau with the weights
  // (a, b) for (1 - t, t), which reaches t = infinity (a + b = 0). Scaled as at().
  std::array<double, 3> at_homogeneous(double a, double b) const;
};

// Where the linear systems on the curve are sampled: homogeneous parameters (a, b) on the unit
// circle, half of them at the Chebyshev points of the segment (a = 1 - t, b = t, rescaled: the
// system's accuracy on the segment is what the engine uses), half spread over the rest of the
// projective line (the extension both ways and t = infinity): an arc alone determines a
// polynomial identity only as well as its points spread, and a short arc of a quartic leaves
// its formula uncertain in ~1e-8 (docs/inversion-formula.md).
struct CurveSample {
  double a, b;                  // the parameter, t = b / (a + b)
  std::array<double, 3> point;  // (U, V, W) there, scaled as at()
};
std::vector<CurveSample> curve_samples(const HomogeneousCurve& curve, int count);

// The curve in its frame: the plan's normalization (centre, rotation) followed by a scale per axis
// and a shift that put the box of the segment's points onto [-1, 1]^2, where the Chebyshev terms
// are of size 1 at the curve. (In the plan's own frame the segment fills |u|, |v| <= 1/2, often
// far less in one direction, and the systems lose a factor 2 per degree, and more, to it.)
struct FrameCurve {
  HomogeneousCurve curve;
  PlaneFrame frame;
};
FrameCurve formula_curve(const PlanData& plan);


}  // namespace bezinv::detail
