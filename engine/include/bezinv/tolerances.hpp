#pragma once
// Every number that decides something in bezinv lives here, with where it comes from.
// Change one only with the test that measures it (tests/engine/*).

namespace bezinv {

// Highest degree bezinv accepts (the issue asks for "at least 30"). The Bezout matrix is
// n x n, so per-point workspaces are sized by this at compile time: no heap in the hot loop.
inline constexpr int kMaxDegree = 32;

// Default on-curve tolerance, relative to the diagonal of the bounding box of the curve's
// control points: a point within kDefaultRelativeTolerance * diagonal of the curve counts as on it.
inline constexpr double kDefaultRelativeTolerance = 1e-6;
// ... but never below this many ulps of the largest coordinate of the curve's bounding box: a point
// computed on the curve and rounded to doubles is off it by up to half an ulp per coordinate
// (0.71 ulp), and the curve's own evaluation adds a few ulps of its size. Matters only where the
// curve is small against its distance from the origin (a 1-unit curve at 1e12: ulp 1.2e-4).
inline constexpr double kResolutionUlps = 4;

// A second candidate parameter (self-intersection, or a root pushed towards infinity by a
// near degree drop) is looked for in the two-dimensional near-null space of B when
// sigma_{n-1}/sigma_1 is at most this. At a double point with noise delta (relative to the
// curve size) the ratio is O(delta); proper curves rarely go below 5e-5 elsewhere (measured on random curves of degree <= 30),
// so 1e-3 catches every double point within the default tolerance at the price of an occasional
// extra (cheap, verified) candidate. Candidates are always verified by their residual, so a
// false trigger costs time, never correctness.
inline constexpr double kSecondNullDirectionRatio = 1e-3;

// Fast path (refinement on): a lane whose null vector comes from LU and inverse iteration is
// answered without an SVD only when the kernel's evidence rules out what the SVD path would do
// differently (engine/src/invert.cpp, stages 2-4 of the fast path), or, on the segment, when the
// isolation certificate does: then no gap is estimated, and of the constants below only
// kFastPathMaxDefect (on the seed's settling) applies.
// kFastPathGapRatio: the SVD path looks for a second parameter when sigma_{n-1}/sigma_1 <=
// kSecondNullDirectionRatio. The fast path's estimate of sigma_{n-1}/||B||_F is from above (at most
// 1.44x over on the kernel tests' random spectra, kernels/src/batch/constants.hpp) and
// ||B||_F >= sigma_1, so where the SVD path looks the estimate is below 1.44x the threshold (on the
// property tests' curves it is at most 1.38x the SVD's sigma_{n-1}/sigma_1): looking whenever it is
// below 2x the threshold looks at least whenever the SVD path would. (3x looked on 57k of 200k
// on-curve points at degree 8, 2x on 36k; the pipeline 5-8% faster there.)
// kFastPathMaxDefect: z must have converged to the singular vector of a simple sigma_n to this
// level (chord between the last two inverse iterates; eps / sigma_{n-1}). It is only the seed of the
// refinement, which must lie in the right Newton basin and is verified by the refined distance, so
// it need not be a null vector: noisy points within the tolerance are answered here too (at noise
// 1e-7 of the curve size, 1e-6 answered 57% of points at degree 8 and 1e-3 answers 99.9%, with the
// same statuses as the SVD path, tests/engine/invert_property_test.cpp). Nullity 2 gives ~1.
// kFastPathMaxDegree: the LU kernel is sized up to kernels::kMaxBatchSize.
// kFastPathMinGap: below this sigma_{n-1} estimate the lane may be at a double point (the ratio is
// O(distance to the crossing), and proper curves mostly stay above 5e-5 elsewhere); it goes to
// the SVD path, whose two last singular vectors are exact where the kernel's second vector is not.
inline constexpr double kFastPathGapRatio = 2 * kSecondNullDirectionRatio;
inline constexpr double kFastPathMinGap = 1e-5;
inline constexpr double kFastPathMaxDefect = 1e-3;
inline constexpr int kFastPathMaxDegree = 32;
// The fast path answers an off-curve lane (docs/fast-path.md, "Off the curve") only where its
// refinement stopped at a stationary point of the distance: cos(P(t) - P0, P'(t)) at most this.
// The stationary point the SVD path's search would find is then within 2 cos d |P'| / v^2 of t,
// ~1e-13 for d = 1e-5 of the curve's size; Newton's last step leaves cos at ~1e-16 / d.
inline constexpr double kStationaryCosine = 1e-8;
// ... and not where a root of span{z, second} lies this close to an end of the segment: the SVD's
// slightly different vectors may put it on the other side, to be walked along the extension there.
inline constexpr double kRootNearEnd = 1e-6;

// The SVD path's kernel: up to this degree the lane-batched Jacobi kernel (one matrix per SIMD
// lane), above it Eigen's tridiagonal QR per matrix, which is faster there (docs/kernels.md). The
// two differ in the last bits, so this number is part of every answer's bits.
inline constexpr int kLaneBatchedSvdMaxDegree = 16;

// Degree drop (paper Sect. 4): the power-basis leading coefficient of p = X - x0 W (or q) counts as
// zero when it is at most this times sum_i C(n,i)|p_i|, the bound on its size. Near such points one
// root of p and q runs off to infinity and the Bezout matrix gains a near-null direction.
inline constexpr double kDegreeDropRatio = 1e-9;

// Effective degree (plan time): a curve given at degree n whose four Bernstein polynomials all have
// a power-basis leading coefficient at most this times its size bound, 2^n times the largest
// coefficient as given (before the curve is moved to its centre), is reduced to degree n-1
// (repeatedly). That is the rounding that degree elevation in double leaves there: each elevated
// coefficient is off by an ulp or two of the coefficients' size, and the leading coefficient, a
// signed sum with binomial weights, gathers 2^n of them at worst and about 2^n / (pi n)^(1/4) of
// them typically. The bound is in ulps of the input's own digits, so a curve is judged the same
// wherever it sits: the 1-unit cubic at 1e12 keeps its degree, as at the origin. Too small a bound
// keeps an elevated curve at its given degree (its points still get verified answers, through the
// second-parameter search, only slower); too large a one drops a real term of the curve, which
// no later step can recover: so the bound sits near the typical rounding, not the worst case.
inline constexpr double kElevatedLeadingRatio = 8 * 0x1p-52;

// The null space of B at a point is searched for parameters (engine/src/invert.cpp, decide) in
// the span of the singular vectors of every sigma_i/sigma_1 at most kSecondNullDirectionRatio, at
// most kMaxNullSpaceDimension of them: more than 2 where a point has several parameters over C
// (an improperly parametrized curve, a line traced at degree n), or where B is ill-conditioned
// (a graph of a function has p of degree 1). A QZ eigenvalue of that search whose imaginary part
// is within kComplexRootSlack of its real part (relative, at least 1) is taken as real: a real
// double root splits into such a pair by rounding; every root is verified by its distance.
inline constexpr int kMaxNullSpaceDimension = 8;
// B vanishes at a point (sigma_1 at most this times the size of B's terms before they cancel,
// max_ij |B0| + |x0 Bx| + |y0 By| + |x0 y0 Bxy|) where p and q are proportional: on a straight line
// traced at degree n, every point of the line. There B is rounding, ~n eps times that size; on any
// other curve sigma_1 is of the order of that size. The parameters are then the roots of p.
inline constexpr double kVanishingBezoutRatio = 1e-10;
inline constexpr double kComplexRootSlack = 1e-6;

// Two parameters of a double point must differ by more than this to count as distinct branches.
inline constexpr double kDistinctParameterGap = 1e-7;
// The fast path's pair check skips a root of span{z, second} this close to the lane's refined t:
// it is z's own root (z ~ b(t) lies in the span), refining it lands on t again, and it cannot be a
// parameter distinct from t by more than kDistinctParameterGap (100 times farther).
inline constexpr double kSameRoot = 1e-2 * kDistinctParameterGap;
// ... and the curve must leave the tolerance of the point somewhere between them: checked at this
// many evenly spaced parameters (a loop back to the point is wide in parameter; a slow stretch of
// the curve, e.g. near a tiny weight, or a cusp within the tolerance stays inside throughout).
inline constexpr int kBranchSamples = 31;

// Newton refinement: iteration cap, and the largest step (in t) one iteration may take, so the
// iteration stays in the basin of the algebraic parameter it started from.
inline constexpr int kNewtonMaxIterations = 60;
inline constexpr double kNewtonMaxStep = 0.125;
// Below this step size Newton is in its quadratic region and its steps are taken without the
// descent test (which cannot resolve t finer than ~sqrt(eps) when the point is off the curve).
inline constexpr double kNewtonTrustedStep = 1e-6;
// A step this small is the last. Newton's error after a step s is about C s^2, C = f''/2f'; with
// f' >= |P'|^2 / 2 (checked: the distance is far from concave there), C is at most
// 3|P''|/|P'| + |P - P0| |P'''| / |P'|^2, so the new t is within C 1e-24 of the root: below its
// ulp unless C > 1e7, i.e. unless the curve all but stops (|P'| < 1e-7 |P''| on a normalized
// curve), where t is ill-determined anyway (the rounding of P0 alone moves it by eps / |P'|). Its
// distance is then the first-order update |(P(t) - P0) + P'(t) s| of the one at hand, exact to
// s^2 |P''| / 2 <= 1e-24 |P''| besides the rounding a direct evaluation has too. On-curve seeds
// are within about 1e-14 of their root, so this takes one jet per point where the step rule alone
// (a step of a few ulps) took two for most of them (tests/kernels/rational_newton_test.cpp and
// the property tests' accuracy model hold with it as before). Not where s^2 |P''| exceeds eps
// (|P''| ~ 1e24 next to a weight of 1e-12): there the distance is measured at the new t.
inline constexpr double kNewtonFinalStep = 1e-12;
// A larger step is halved at most this many times looking for a point no farther from P0.
inline constexpr int kNewtonMaxHalvings = 40;

// Nearest-point search on the segment (off-curve points): samples per unit of degree.
inline constexpr int kNearestSamplesPerDegree = 16;

// A point so far that its normalized coordinates or its Bezout matrix overflow is answered from
// its direction (engine/src/pipeline/far_point.hpp): the nearest point of the segment to a stand-in
// on that ray at this distance from the centre (normalized units, curve size ~1), where nothing
// overflows and the direction to every point of the curve is that of the ray to within 1e-8.
inline constexpr double kFarStandIn = 1e8;

}  // namespace bezinv
