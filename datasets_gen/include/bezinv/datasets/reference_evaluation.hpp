#pragma once
// The generators' own evaluation of a curve, in long double and sharing no code with engine/src,
// so that a parameter the generators call "true" does not inherit an engine bug.
//
// Two evaluations:
//  - points at a real t (the answers: P(t) of a generated point, Newton's method for nearest
//    points) by a compensated de Casteljau in long double, accurate to far below a double ulp also
//    on the extension, where cancellation in the alternating basis costs a plain evaluation
//    (|1-t| + |t|)^n digits (a few double ulps at t = 1.3, n = 20);
//  - points for dense sampling (whether another branch comes near: margins of 1e-4, not ulps) by
//    the homogeneous Bernstein form
//        p[c : s] = sum_i C(n,i) c^{n-i} s^i p_i,      [c : s] = [1-t : t],
//    which covers the whole real parameter line including t = inf (c = -s).
#include <array>
#include <optional>
#include <span>

#include "bezinv/curve.hpp"
#include "bezinv/invert.hpp"

namespace bezinv::datasets {

using Real = long double;

struct RealPoint { Real x = 0, y = 0; };

// A homogeneous value and the sum of the absolute values of its terms (the scale its rounding and
// cancellation are judged against).
struct HomogeneousValue { Real value = 0, magnitude = 0; };
HomogeneousValue homogeneous_value(std::span<const double> coefficients, Real c, Real s);

// P at [c : s]; empty when a denominator is below `min_relative_denominator` times its magnitude
// (a pole, or so much cancellation that the point means nothing).
std::optional<RealPoint> reference_point(const Curve& curve, Real c, Real s,
                                         Real min_relative_denominator = 1e-9L);

// P(t) for any real t (the caller keeps away from poles), by the compensated de Casteljau.
RealPoint reference_point(const Curve& curve, Real t);

// P(t), P'(t), P''(t). For x = N / D:  x' = (N' - D' x) / D,  x'' = (N'' - 2 D' x' - D'' x) / D.
struct ReferenceJet { RealPoint p, d1, d2; };
ReferenceJet reference_jet(const Curve& curve, Real t);

// |W(t)| / sum_i |w_i beta_i(t)|, the smaller for x_den and y_den: 1 on [0,1] for positive
// coefficients, small near a pole or where the extension's alternating basis cancels.
Real denominator_conditioning(const Curve& curve, Real t);

// max over x, y of (sum_i |num_i beta_i(t)| + |x(t)| sum_i |den_i beta_i(t)|) / |den(t)|: the
// scale of the rounding error of evaluating P(t) in floating point (KnownPoint::scale).
Real evaluation_scale(const Curve& curve, Real t);

// Diagonal of the bounding box of the control points (num_i / den_i) and the two end points: the
// size the engine's tolerance is relative to (InversionPlan::diagonal says the same).
double control_diagonal(const Curve& curve);

// Nearest double point.
Point rounded(RealPoint p);

Real distance(RealPoint a, RealPoint b);
Real distance(RealPoint a, Point b);

}  // namespace bezinv::datasets
