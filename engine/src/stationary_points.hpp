#pragma once
// Where the distance from a point to the curve is stationary, and the nearest point of the segment
// with a proof that it is the nearest (engine internal).
//
// For P0 = (u0, v0) and f(t) = |P(t) - P0|^2, with x = X / Wx, y = Y / Wy and
// Hx = X' Wx - X Wx' (so x' = Hx / Wx^2; Hy alike):
//     f'(t) / 2 = (X - u0 Wx) Hx / Wx^3 + (Y - v0 Wy) Hy / Wy^3.
// Times Wx^3 Wy^3 (of one sign on [0, 1]: validate refuses a denominator with a root there) this
// is a polynomial g whose sign is that of f' (up to the constant sign s of Wx^3 Wy^3), affine in P0:
//     s g = G0 - u0 Gx - v0 Gy,
//     G0 = X Hx Wy^3 + Y Hy Wx^3,   Gx = Wx Hx Wy^3,   Gy = Wy Hy Wx^3         (degree 6n - 1),
// and with one denominator W (divide by W^3 instead)
//     G0 = X Hx + Y Hy,             Gx = W Hx,         Gy = W Hy               (degree 3n - 1).
// make_plan stores the Bernstein coefficients of G0, Gx, Gy on each of kStationaryPieces pieces of
// [0, 1]; per point g's coefficients on a piece are one affine combination. In the Bernstein basis
// a polynomial has at most as many roots in the interval as its coefficients change sign, and the
// same number modulo 2: no change, no stationary point there; one change from - to +, exactly one,
// a minimum; more, the piece is halved (de Casteljau) until each part says.
//
// certified_nearest_on_segment finds the global minimum of f on [0, 1] by branch and bound: the
// best of the ends and of the refined hint is an upper bound; a piece whose isolation boxes
// (isolation.hpp) are all farther cannot hold anything nearer and is skipped; every other piece is
// classified by the sign changes of g and its one minimum, if it has one, found by Newton's method
// kept inside its bracket. The answer is certified when every piece that could hold a nearer
// point was classified; a coefficient too small for its sign to be trusted, or a piece still
// undecided after kStationaryMaxHalvings halvings, leaves it uncertified (the caller then falls
// back to the sampling search, refine.hpp).
#include <limits>

#include "plan_data.hpp"

namespace bezinv::detail {

// The number of pieces g is stored on (make_plan). Speed only: more pieces store more
// coefficients per plan, fewer make more pieces need halving per point.
inline constexpr int kStationaryPieces = 16;
// How many times a piece with more than one sign change may be halved for one point.
inline constexpr int kStationaryMaxHalvings = 6;
// Two candidates whose distances differ by at most this many ulps are equally near (a tie): the
// first found is kept.
inline constexpr double kNearestTieUlps = 8;

// Fills plan.stationary_degree, stationary_g and stationary_scale from the normalized curve.
void stationary_pieces(const PlanData& plan, OffCurveData& data);

struct NearestOnSegment {
  double t = 0.0, distance = 0.0;
  bool certified = false;  // t is proved the nearest point of [0, 1] (to rounding)
};

// The nearest point of the segment to (u0, v0), normalized coordinates; `hint` (if in [0, 1]) is a
// start the caller already has, refined here unless `hint_distance` is given: then the hint is
// already refined (a stationary point of the distance, or where the safeguards stopped) and
// hint_distance its distance; `hint_stationary` is then stationary_point's answer for it where the
// caller has it (1 or 0; -1: not known, tested here). When not certified, t and distance are the
// best found so far.
NearestOnSegment certified_nearest_on_segment(const PlanData& plan, double u0, double v0, double hint,
                                              double hint_distance = std::numeric_limits<double>::quiet_NaN(),
                                              int hint_stationary = -1);

}  // namespace bezinv::detail
