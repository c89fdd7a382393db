#pragma once
// Curves with a double point at chosen parameters, and points at and around it.
//
// For fixed denominators the condition P(t1) = P(t2) is linear in the numerator coefficients:
//     x(t1) = x(t2)  <=>  sum_i x_num_i (beta_i(t1) W(t2) - beta_i(t2) W(t1)) = 0   (W = x_den),
// and likewise for y. So a random curve is corrected by the minimal-norm change of x_num (and of
// y_num) that satisfies it: x_num -= g (g . x_num) / (g . g), g_i = beta_i(t1) W(t2) - beta_i(t2) W(t1),
// repeated once on the rounded result.
#include <random>
#include <vector>

#include "bezinv/curve.hpp"
#include "bezinv/datasets/curve_sampling.hpp"
#include "bezinv/datasets/known_point.hpp"
#include "bezinv/datasets/random_curve.hpp"

namespace bezinv::datasets {

// A random curve (random_curve(kind, degree, rng, polygon)) corrected so that P(t1) = P(t2), with
// 0 <= t1 < t2 <= 1 and degree >= 3. Retries with new random curves until the result is verified:
// |P(t1) - P(t2)| <= 1e-14 * diagonal, a transversal crossing (the tangents at least 15 degrees
// apart), both speeds above 1% of the diagonal, and the crossing isolated from every other branch
// (kIsolation). Throws std::invalid_argument for degree < 3 or t1, t2 out of order, and
// std::runtime_error if no curve passes in 200 attempts.
Curve with_self_intersection(CurveKind kind, int degree, double t1, double t2, std::mt19937_64& rng,
                             ControlPolygon polygon = ControlPolygon::unit_square);

// Points at the double point P(t1) = P(t2) of a curve from with_self_intersection: first the
// crossing itself (t = t1, t2 = t2), then `count` points at distance radius_relative * diagonal in
// random directions, whose t and t2 are the nearest points of the two branches (each refined in
// long double) and `distance` the larger of the two distances. Points not isolated from the rest of
// the curve are skipped.
std::vector<KnownPoint> crossing_points(const CurveSampling& sampling, double t1, double t2, int count,
                                        double radius_relative, std::mt19937_64& rng);

}  // namespace bezinv::datasets
