#pragma once
// How many separate branches of the segment pass within a radius of a point: a proof, not a
// sampling. The segment is subdivided (de Casteljau, long double); a piece whose control points'
// box is farther than the radius from the point is dropped (with positive denominators a rational
// piece lies in the box of its control points x_num_i / x_den_i, y_num_i / y_den_i), the others are
// halved until their box is under radius / 8. The pieces kept form runs of adjacent parameters: two
// runs are two branches, between which the curve goes farther than the radius (the pieces there
// were dropped). What a sampling misses (a loop of a curve with extreme weights inside a sliver of
// parameter, two minima of the distance a few samples apart where the curve nearly stops) this
// finds.
#include "bezinv/curve.hpp"
#include "bezinv/datasets/reference_evaluation.hpp"

namespace bezinv::datasets {

// The number of runs (0 when no point of the segment is within the radius), or -1 when the proof
// does not apply: a denominator coefficient not positive, or more than kMaxPieces pieces kept.
int branches_within(const Curve& curve, RealPoint point, Real radius);

}  // namespace bezinv::datasets
