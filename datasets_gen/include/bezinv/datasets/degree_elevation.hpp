#pragma once
// The same curve written at a higher degree: what the engine's effective-degree reduction must undo.
#include "bezinv/curve.hpp"

namespace bezinv::datasets {

// Elevates x_num, x_den, y_num, y_den `times` times by
//     q_i = (i / (n+1)) p_{i-1} + (1 - i / (n+1)) p_i,   i = 0..n+1,
// in double (the rounding is the point: the leading power coefficient is then round-off, not 0).
// The kind is kept (x_den = y_den stays true for bezier and rational_bezier; for bezier the
// all-ones denominator elevates to all ones exactly).
Curve degree_elevated(const Curve& curve, int times);

}  // namespace bezinv::datasets
