#pragma once
// The same curve moved far from the origin, or shrunk: what the plan's centring and scaling must
// make harmless.
#include "bezinv/curve.hpp"

namespace bezinv::datasets {

// P(t) + (dx, dy): x_num += dx x_den, y_num += dy y_den (each denominator its own; for
// rational_bezier that is w_i (a_i + dx)). Rounded once per coefficient, so the result is the
// translate only up to u * |dx|: answers for it must be computed from it, not from the original.
Curve translated(const Curve& curve, double dx, double dy);

// factor P(t) about the origin: x_num and y_num times factor, rounded once per coefficient (the
// same caveat as translated).
Curve scaled(const Curve& curve, double factor);

}  // namespace bezinv::datasets
