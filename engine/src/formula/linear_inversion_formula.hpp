#pragma once
// The linear inversion formula of a conic or a cubic with one denominator, t = N(u, v) / M(u, v)
// with N and M of degree one (Wang & Joe: degree max(1, n - 2)), in the plan's normalized
// coordinates, for the formula path (engine/src/pipeline/formula_path.hpp).
//
// With P(t) = (X(t), Y(t)) / W(t) of degree n and N = n0 W + n1 X + n2 Y, M = m0 W + m1 X + m2 Y as
// linear forms in homogeneous coordinates, N(P) = t M(P) on the curve is the polynomial identity
//     F(t) - t G(t) = 0,   F = n0 W + n1 X + n2 Y,   G = m0 W + m1 X + m2 Y,
// of degree n + 1. In the Bernstein basis of degree n + 1 (F degree-elevated, t G shifted), times
// n + 1, its coefficients are
//     k f_{k-1} + (n + 1 - k) f_k - k g_{k-1}    (k = 0 .. n + 1; f_{-1} = f_{n+1} = 0),
// linear in the six unknowns: n + 2 equations. A cubic has five and a formula fixed up to a factor
// (its pencil's centre is the double point). A conic has four; the fifth fixes its centre at
// P(inf) as the paper recommends for a segment (formula (9)): N(P(inf)) = 0, P(inf) being the
// second difference of the homogeneous control points (M(P(inf)) = 0 follows from the identity's
// top coefficient). The formula is the null vector of that 5 x 6 system, from a column-pivoted
// QR of its transpose: a few microseconds per plan, where the general construction
// (bezinv/inversion_formula.hpp, sampled conditions and SVDs in its own frame) costs tens.
#include "plan_data.hpp"

namespace bezinv::detail {

// The formula of a plan of degree 2 or 3 with one denominator, usable when the system has a
// one-dimensional null space and N / M reproduces the parameter of every nearest-point sample where
// the formula path would use it (within kFormulaPathMaxSegmentError). Not usable otherwise.
FormulaPathData linear_inversion_formula(const PlanData& plan);

}  // namespace bezinv::detail
