#pragma once
// The curves of Marco & Martinez's paper, transcribed from its text, and the demo's default cubic.
#include "bezinv/curve.hpp"

namespace bezinv::datasets {

// Example 1 (Sect. 4): separate denominators, degree 4,
//   x = (4, 4, 3, 3, 7) / (1, 1, 1, 1, 3),   y = (2, 3, 3, 3, 4) / (1, 1, 1, 1, 1)
// in the Bernstein basis. p = X - x0 W loses its t^4 term at x0 = 1/2 (the paper's degree drop).
Curve paper_example1_curve();

// Example 2 (Sect. 5): the rational Bezier curve of degree 15 (16 control points and weights).
// P(1/7) = (78193109744768, 131831466405881) / 9191995131007 (the paper's exact value).
Curve paper_example2_curve();

// Example 4 (Sect. 5): rational Bezier of degree 3, points (1,9) (2,1) (5,1) (4,1), weights
// 1 2 2 1; P(1/3) = (8/3, 109/45).
Curve paper_example4_curve();

// A plain cubic Bezier arch, (0,0) (1,2) (3,2) (4,0): symmetric, no inflection, no loop.
Curve default_cubic_curve();

}  // namespace bezinv::datasets
