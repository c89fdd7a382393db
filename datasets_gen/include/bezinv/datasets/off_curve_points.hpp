#pragma once
// Points off the curve with a known nearest point of the segment: P(t0) + d N(t0), N the unit
// normal. t0 is then a critical point of the distance; it is the nearest point when d is below the
// radius of curvature on that side and no other part of the segment is closer, which the generator
// checks by dense sampling (CurveSampling) and discards candidates that fail. One candidate in
// eight is instead placed beyond an end of the segment (off at 20..70 degrees from the outward
// tangent), where the nearest point of the segment is the end itself (t exactly 0 or 1).
//
// Guarantees of every returned point: the nearest point of the segment is at t (refined in long
// double for the point as rounded to double) at distance `distance`; every other local minimum of
// the distance over the segment is at least max((1 + kNearestGap) distance, kIsolation * diagonal);
// the extension of the curve is farther than kIsolation * diagonal.
#include <random>
#include <vector>

#include "bezinv/datasets/curve_sampling.hpp"
#include "bezinv/datasets/known_point.hpp"

namespace bezinv::datasets {

// Offsets d log-uniform in [min_relative, max_relative] * diagonal.
std::vector<KnownPoint> normal_offset_points(const CurveSampling& sampling, int count, double min_relative,
                                             double max_relative, std::mt19937_64& rng);

// The parameter of the point of the curve nearest to p near t0 (Newton's method on
// (P(t) - p) . P'(t) = 0 in long double).
Real nearest_parameter_near(const Curve& curve, RealPoint p, Real t0);

}  // namespace bezinv::datasets
