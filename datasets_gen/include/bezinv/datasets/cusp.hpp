#pragma once
// Curves with a cusp at a chosen parameter, and points on them near it.
//
// P'(tc) = 0 is, for fixed denominators, linear in the numerator coefficients: with x = num / den,
//     x'(tc) = 0  <=>  num'(tc) den(tc) - num(tc) den'(tc) = 0
//                 <=>  sum_i num_i (beta_i'(tc) den(tc) - beta_i(tc) den'(tc)) = 0,
// and likewise for y. So a random curve is corrected by the minimal-norm change of each numerator
// that satisfies it, as with_self_intersection does for P(t1) = P(t2). Generically the result has
// an ordinary cusp there: P''(tc) != 0, and near it P(tc + s) - P(tc) ~ P''(tc) s^2 / 2 +
// P'''(tc) s^3 / 6, two branches that meet tangentially, |P'(tc + s)| ~ |P''(tc)| |s|: the
// parameter of a point there is as ill-conditioned as anywhere on a regular curve, by 1 / |s|.
#include <random>
#include <vector>

#include "bezinv/curve.hpp"
#include "bezinv/datasets/curve_sampling.hpp"
#include "bezinv/datasets/known_point.hpp"
#include "bezinv/datasets/random_curve.hpp"

namespace bezinv::datasets {

// A random curve (random_curve(kind, degree, rng, polygon)) corrected so that P'(tc) = 0, with
// degree >= 3 and 0 < tc < 1. Retries with new random curves until the result is verified: |P'(tc)|
// <= 1e-12 * diagonal, an ordinary cusp (|P''(tc)| >= 1% of the diagonal, P'''(tc) at least 15
// degrees from P''(tc), from differences of the second derivative), and the cusp isolated from
// every other branch (kIsolation). Throws std::invalid_argument for degree < 3 or tc outside (0, 1),
// std::runtime_error if no curve passes in 200 attempts.
Curve with_cusp(CurveKind kind, int degree, double tc, std::mt19937_64& rng,
                ControlPolygon polygon = ControlPolygon::unit_square);

// `count` points on a curve from with_cusp at t = tc +- s, s log-uniform in [1e-4, 1e-2] (either
// branch): near enough that the other branch is within the default tolerance for the smaller s,
// far enough that it is never within rounding (the branches are ~|P'''| s^3 apart). Each is
// isolated from every branch of the curve but the cusp's own two (parameters within 0.05 of tc).
std::vector<KnownPoint> near_cusp_points(const CurveSampling& sampling, double tc, int count, std::mt19937_64& rng);

}  // namespace bezinv::datasets
