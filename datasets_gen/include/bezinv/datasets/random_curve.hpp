#pragma once
// Random curves of each kind, reproducible from a std::mt19937_64 seed.
#include <random>

#include "bezinv/curve.hpp"

namespace bezinv::datasets {

// Where the control points come from.
//   unit_square    independent uniform points in [0,1]^2. At high degree the curve is the smooth
//                  average of a wild polygon: it stays near the middle, loops and self-approaches
//                  are common, which is what exercises the isolation checks of the point sets.
//   perturbed_arc  points on a circular arc (centre (0.5, 0.5), radius 0.5, opening 90..300
//                  degrees) moved by up to 0.08 in each coordinate: a "reasonable" design curve.
enum class ControlPolygon { unit_square, perturbed_arc };

const char* to_string(ControlPolygon polygon);

// kind = bezier:           the control points;
//        rational_bezier:  the control points with weights uniform in [0.5, 2];
//        rational:         separate denominators x_den, y_den with coefficients uniform in [0.5, 2]
//                          (positive Bernstein coefficients: no pole on [0,1]) and numerators
//                          num_i = a_i den_i, so x(t) is a convex combination of the a_i.
// The id names the kind, degree and polygon.
Curve random_curve(CurveKind kind, int degree, std::mt19937_64& rng,
                   ControlPolygon polygon = ControlPolygon::unit_square);

}  // namespace bezinv::datasets
