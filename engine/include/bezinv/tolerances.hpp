#pragma once
// Every number that decides an answer in bezinv, in one place, each with where it comes from.
// The reasoning and the measurements behind them: docs/accuracy-model.md and docs/fast-path.md.
// Change one only with the test that measures it (tests/engine/*). Numbers that only set speed
// (batch sizes, queue lengths) sit with their code and say so.
#include <algorithm>
#include <limits>

namespace bezinv {

// ---- Limits ------------------------------------------------------------------------------------

// Highest degree bezinv accepts (validate() refuses more, naming the limit). B is n x n, so the
// per-point workspaces are sized by it at compile time; the kernels' sizes are tied to it by
// static_asserts (engine/src/pipeline/limits.hpp).
inline constexpr int kMaxDegree = 32;

// ---- On the curve or not -----------------------------------------------------------------------

// Default on-curve tolerance, relative to the diagonal of the control points' bounding box.
inline constexpr double kDefaultRelativeTolerance = 1e-6;
// ... never below this many ulps of the box's largest coordinate: a point rounded to doubles from
// the curve is off it by ~0.71 ulp, and the curve's evaluation adds a few ulps of its size.
inline constexpr double kResolutionUlps = 4;

// ---- The plan: effective degree, straight lines ------------------------------------------------

// A curve is reduced from degree n to n - 1 (repeatedly) while all four power-basis leading
// coefficients are at most this times 2^n times the largest coefficient as given: 8 ulps, the
// typical rounding a degree elevation leaves there (docs/accuracy-model.md, "Effective degree").
inline constexpr double kElevatedLeadingRatio = 8 * 0x1p-52;
// B vanishes at a point (sigma_1 at most this times the size of B's terms before they cancel)
// where p and q are proportional: every point of a straight line traced at degree n. B is then
// rounding (~n eps of that size) and the parameters are the roots of p ("Straight lines").
inline constexpr double kVanishingBezoutRatio = 1e-10;

// ---- Degree drops (paper Sect. 4) --------------------------------------------------------------

// The leading power coefficient of p (or q) counts as zero when it is at most this times its size
// bound sum_i C(n,i) |p_i|: near such points a root runs off to infinity ("Degree drops").
inline constexpr double kDegreeDropRatio = 1e-9;

// ---- Several parameters: the null space of B ---------------------------------------------------

// More parameters are looked for in the near-null space of B when sigma_{n-1}/sigma_1 is at most
// this: O(noise) at a double point, rarely below 5e-5 elsewhere on random curves of degree <= 30;
// a false trigger costs a verified candidate, never a wrong answer ("The null space of dimension k").
// Near a cusp, where the two parameters of a double point are close, it is larger for the same
// distance: `bezinv stress` found a point on one branch with the other 4.5e-7 of the diagonal
// away (degree 4, parameters 0.300 and 0.311) at 1.03e-3, answered ok. So 1.1e-3, the most the fast
// path's gate allows (kFastPathGapRatio: its estimate is up to 1.8x high).
inline constexpr double kSecondNullDirectionRatio = 1.1e-3;
// At most this many singular vectors span that space (more than 2 for improper curves, lines
// traced at degree n, ill-conditioned B such as a graph of a function).
inline constexpr int kMaxNullSpaceDimension = 8;
// A QZ eigenvalue whose imaginary part is within this of its real part (relative, at least 1) is
// taken as real: a real double root split by rounding. Every root is verified by its distance.
inline constexpr double kComplexRootSlack = 1e-6;
// An eigenvalue of the pencil whose beta is at most this times the pencil's size is a root at
// infinity (a degree drop) or too far out to be more than rounding: skipped.
inline constexpr double kPencilInfinityRatio = 1e-13;
// A discriminant of the 2 x 2 pencil down to -kDoubleRootSlack b^2 is a double root blurred by
// rounding: one root.
inline constexpr double kDoubleRootSlack = 1e-10;

// Two parameters of a double point differ by more than this ...
inline constexpr double kDistinctParameterGap = 1e-7;
// ... and the curve leaves the tolerance of the point somewhere between them, checked at this many
// evenly spaced parameters (a slow stretch or a cusp within the tolerance stays inside: one answer).
inline constexpr int kBranchSamples = 31;

// ---- Refinement (docs/accuracy-model.md, "Refinement") -----------------------------------------

// Newton on (P(t) - P0) . P'(t): iteration cap, and the largest step in t, so the iteration stays
// in the basin of the parameter it started from.
inline constexpr int kNewtonMaxIterations = 60;
inline constexpr double kNewtonMaxStep = 0.125;
// Below this step Newton is in its quadratic region: steps are taken without the descent test
// (which cannot resolve t finer than ~sqrt(eps) off the curve).
inline constexpr double kNewtonTrustedStep = 1e-6;
// A step this small is the last: the new t is within C 1e-24 of the root (C = f''/2f'), below its
// ulp unless the curve all but stops; its distance is the first-order update of the last one.
inline constexpr double kNewtonFinalStep = 1e-12;
// The off-curve path's Newton kernel (nearest_newton) takes a step this small as its last where
// the distance is convex and s^2 |P''| is below rounding: Newton converges quadratically there, and
// what remains, about |f''/2f'| s^2, moves P by about s^2 |P''| (docs/kernels.md).
inline constexpr double kNearestNewtonFinalStep = 1e-9;
// On the formula path (engine/src/pipeline/formula_path.hpp) the refinement takes a step this small
// as its last, where the curve is flat enough over it (|P''| s^2 below rounding, the kernel's
// test): the formula's start is accurate to ~1e-10 (its segment_error), a step from there leaves
// about |f''/2f'| 1e-20, below t's ulp as kNearestNewtonFinalStep's does, and with
// kNewtonFinalStep a group of lanes would take a second jet for the few whose step exceeds 1e-12
// (1.04-1.12x the whole path at degrees 8-20; the stress tool's t within 0.04 of the accuracy bound).
inline constexpr double kFormulaNewtonFinalStep = 1e-9;
// A larger step is halved at most this many times looking for a point no farther from P0.
inline constexpr int kNewtonMaxHalvings = 40;
// A step that moves t by at most this many ulps of max(1, |t|) is the last (the kernels'
// rational_newton stops at the same: the two give the same bits, tests/kernels).
inline constexpr double kNewtonStopUlps = 4;

// ---- The nearest point of the segment (off-curve points) ---------------------------------------

// Samples per unit of degree, and the basins (local minima of the sampled distance, nearest first)
// refined: a curve of degree n has up to 2n - 1 of them, and only the nearest few can win.
inline constexpr int kNearestSamplesPerDegree = 16;
inline constexpr int kNearestMaxBasins = 8;
// A point so far that its normalized coordinates or its B overflow is answered from its direction:
// the nearest point of the segment to a stand-in on that ray at this distance (normalized units,
// curve size ~1), where nothing overflows ("Far points").
inline constexpr double kFarStandIn = 1e8;
// Beyond 1/eps (normalized units) the distances from a point to every point of the curve round to
// the same double, and the nearest cannot be told from them: the search looks from the same
// stand-in, and finds the point of the segment nearest in exact arithmetic (to O(1/kFarStandIn)).
inline constexpr double kFarEqualDistances = 1.0 / std::numeric_limits<double>::epsilon();
// The certified search (engine/src/stationary_points.hpp) trusts the sign of a Bernstein
// coefficient of g (the sign of the distance's derivative) only beyond this many ulps, times g's
// degree, of the scale of its terms: a bound of the rounding of making g per plan and combining it
// per point, with room to spare (a coefficient within it sends the point to the sampling search).
inline constexpr double kStationarySignUlps = 32;

// ---- The fast path (docs/fast-path.md) ---------------------------------------------------------
// It answers a lane only where the SVD path could not answer it differently.

// The fast path runs up to this degree (every degree).
inline constexpr int kFastPathMaxDegree = 32;
// Its sigma_{n-1} estimate (relative to ||B||_F, from above, at most 1.44x high on random spectra,
// 1.8x allowed in InvertProperty.FastPathAgreesWithTheSvdPath) looks for a second parameter below
// this, so at least wherever the SVD path would look (1.8 kSecondNullDirectionRatio below it; "The gap").
inline constexpr double kFastPathGapRatio = 2e-3;
static_assert(1.8 * kSecondNullDirectionRatio < kFastPathGapRatio);
// Both ratios are for the default tolerance. sigma_{n-1} grows about in proportion to the distance
// from the point to a second branch, so at a tolerance r times the default (relative to the
// diagonal, after the floor) both are r times larger, never smaller: `bezinv stress --tol 1e-4`
// found a cubic's point with its other branch within the tolerance at sigma_{n-1}/sigma_1 2.6e-3,
// answered ok on every path (docs/accuracy-model.md, "The null space of dimension k").
inline double scaled_to_tolerance(double ratio, double relative_tolerance) {
  return std::max(ratio, ratio * (relative_tolerance / kDefaultRelativeTolerance));  // NaN -> ratio
}
// Below this estimate the lane may be at a double point: the SVD path decides.
inline constexpr double kFastPathMinGap = 1e-5;
// z must have converged to this level (chord of the last two inverse iterates): it only seeds the
// refinement, which the distance verifies ("The seed").
inline constexpr double kFastPathMaxDefect = 1e-3;
// A refined t is a stationary point of the distance where cos(P(t) - P0, P'(t)) is at most this
// (refine.hpp, stationary_point): the nearest-point search then takes it as the one minimum of
// its interval instead of refining again ("Off the curve, by distance").
inline constexpr double kStationaryCosine = 1e-8;
// The isolation certificate's boxes are widened, and its tolerance raised, by this (relative) for
// the rounding of the subdivision and the distances: ~n eps, far below any tolerance.
inline constexpr double kIsolationMargin = 1e-12;

// ---- The SVD ------------------------------------------------------------------------------------

// Up to this degree the lane-batched Jacobi kernel, above it Eigen's tridiagonal QR per matrix
// (faster there, docs/kernels.md). The two differ in the last bits: part of every answer's bits.
inline constexpr int kLaneBatchedSvdMaxDegree = 16;

// ---- Inversion formulae (bezinv/inversion_formula.hpp) -----------------------------------------

// The solutions (N, M) of the formula's sampled system are the singular vectors whose singular
// values are at most this times the largest: rounding leaves ~1e-16 .. 1e-12 there at degrees up
// to 32, while a curve with no formula (traced more than once) keeps ~1e-4 or more.
inline constexpr double kFormulaNullRatio = 1e-8;
// Base points asked for fix the formula when the conditions they make on the solutions have no
// singular value below this times the largest (two coinciding base points make one ~0).
inline constexpr double kFormulaChoiceRatio = 1e-8;

// The formula path (engine/src/pipeline/formula_path.hpp): a plan's formula is used only where it
// is this accurate on the segment (InversionFormula::segment_error: a start Newton's method
// finishes in one or two steps), at a point only where |M| is at least kFormulaPathMinDenominator
// of the size of M's terms there (N/M then keeps ~10 digits; nearer the formula's base points, a
// double point or a cusp, the Bezout path), and within kFormulaPathMaxCoordinate of the curve in
// normalized units (farther points form B, whose overflow decides them far points).
inline constexpr double kFormulaPathMaxSegmentError = 1e-8;
inline constexpr double kFormulaPathMinDenominator = 1e-6;
inline constexpr double kFormulaPathMaxCoordinate = 1e6;
// Degrees at which the formula path is taken when asked for (the formula's: twice the curve's with
// separate denominators): the formula costs ~10 us to make at degree 3, ~80 ms at 20 (per plan,
// once), and more above.
inline constexpr int kFormulaPathMaxDegree = 20;
// Algebraic::automatic takes a conic's or cubic's linear formula only where its weights (the
// denominator's coefficients) are of one sign and within this ratio of each other. Beyond, the
// parametrization's speed varies by as much: near an end of tiny weight a few ulps of t are far
// apart in space, and N/M, accurate in t to the ulps of its terms, starts Newton farther than its
// stopping rule (steps of 4 eps in t) lets it come back; the null vector's ratio read-out keeps
// t's relative accuracy there. Measured on cubics with a first weight 1e-12 .. 1e12
// (tests/engine/cusps_and_slow_branches_test.cpp): residuals up to 3e8 times the accuracy bound
// at a ratio of 1e12, 4 times at 1e8, none above it at 1e4.
inline constexpr double kFormulaPathMaxWeightRatio = 1e3;
// A curve close to one of degree n - 1 (each of its polynomials' top power coefficient below this
// times power_leading_bound: a smooth function's graph, whose x(t) is linear and y(t)'s top
// differences tiny) has p and q nearly sharing the root at infinity at every point, so B is
// nearly singular twice over and the fast path's seed settles few of its points: measured on
// graphs of exp at degrees 5-12, most points reached the SVD path from a ratio of 1e-7 to 5e-7
// down and none from 1.3e-6 up. Algebraic::automatic takes the formula path on such a plan where
// it has a linear formula (formula_path.hpp); 1e-4 leaves a margin of 100 above that onset, and
// random curves are at 1e-2 and above.
inline constexpr double kNearLowerDegreeRatio = 1e-4;
// A polynomial curve's direction e makes e . P(t) linear (PlanData::linear_formula) when e is
// normal to every second difference of the control points to this fraction of their bound (the
// rounding of an exactly linear coordinate after normalization, with room), and the line's slope
// is at least kLinearDirectionMinSlope of the diagonal (else t is not well defined by e . P).
inline constexpr double kLinearDirectionRatio = 1e-13;
inline constexpr double kLinearDirectionMinSlope = 1e-3;

// ---- A curve's size ----------------------------------------------------------------------------

// Where a curve's ratios num_i / den_i do not bound it (a zero or negative denominator coefficient),
// its size comes from pieces halved until they do (engine/src/ratio_range.hpp): at least this many
// halvings deep (16 pieces: their ratios then exceed the curve by a few percent of its extent)...
inline constexpr int kRatioRangeMinHalvings = 4;
// ...and at most this many (pieces 1e-9 wide) and this many pieces in all, so a denominator within
// rounding of a root, or ratios that overflow, cost a bounded time.
inline constexpr int kRatioRangeHalvings = 30;
inline constexpr int kRatioRangePieces = 4096;

// ---- Curves refused ----------------------------------------------------------------------------

// A denominator has a root on [0, 1] (validate() refuses the curve) when subdivision cannot bound
// it away from zero after this many halvings (a piece 1e-12 wide): a double root, or within rounding.
inline constexpr int kDenominatorRootHalvings = 40;

// A composite curve's curves must meet end to start within this fraction of the diagonal of its
// control points' bounding box: a tenth of the default on-curve tolerance, so a gap the check lets
// through is invisible to the default inversion, yet ends computed in floating point (an
// unclamped NURBS, a rational curve's ends) or printed to 8 digits pass.
inline constexpr double kCompositeJointGap = 1e-7;

}  // namespace bezinv
