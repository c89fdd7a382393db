#pragma once
// A point whose answer is known by construction, and the margins the generators guarantee.
#include <limits>

#include "bezinv/invert.hpp"

namespace bezinv::datasets {

struct KnownPoint {
  static constexpr double nan = std::numeric_limits<double>::quiet_NaN();
  Point point{nan, nan};  // what the engine is given (a double point)
  double t = nan;         // its parameter; for a point off the curve, the nearest point's on the segment
  double t2 = nan;        // at a double point, the other parameter (t < t2)
  double distance = nan;  // |P(t) - point|, exact to long double: the rounding of the point for
                          // on-curve sets, the offset for off-curve sets
  double speed = nan;     // |P'(t)|: an error e in the point moves its parameter by about e / speed
  double scale = nan;     // max over x, y of (sum_i |num_i beta_i(t)| + |x(t)| sum_i |den_i beta_i(t)|) / |den(t)|:
                          // evaluating P(t) in floating point with unit round-off u errs by about
                          // n u scale, so n u scale / speed is the accuracy any double method can
                          // promise for t (>= |P(t)|: it also covers the rounding of the point)
};

// Every generated point is farther than kIsolation * diagonal from every branch of the curve other
// than the one(s) it was made on, over the whole parameter line (segment and extension). 100 x the
// engine's default tolerance, so the expected status never hinges on how a near-double point is
// treated.
inline constexpr double kIsolation = 1e-4;

// Off-curve points: every other local minimum of the distance over the segment is at least
// (1 + kNearestGap) times the nearest one, so "the nearest point of the segment" is unambiguous
// and its parameter well defined.
inline constexpr double kNearestGap = 1e-2;

}  // namespace bezinv::datasets
