#pragma once
// Lane-batched numerical kernels, one problem per SIMD lane: small dense symmetric matrices (their
// SVD, null vectors, Bezout matrices formed from coefficient matrices), the parameter read off a
// vector in the Bernstein basis, and Newton's method on a quotient of polynomials in the Bernstein
// basis. They know nothing of files, plans, tolerances' origins or statuses: the engine passes
// numbers and decides what the results mean. docs/kernels.md says what each computes and why.
//
// Layout (structure of arrays). A batch holds `count` matrices padded to `stride` lanes
// (stride = count rounded up to kBatchAlignment, padding lanes hold any finite values):
//     matrix entry (r, c) of lane l        B[(r * n + c) * stride + l]      (only r >= c is read)
//     singular value k of lane l           sigma[k * stride + l]            (descending)
//     component r of singular vector k     V[(k * n + r) * stride + l]
//     component r of the null vector       z[r * stride + l]
// so that one SIMD load fetches the same entry of consecutive matrices.
#include <cstddef>
#include <cstdint>
#include <limits>
#include <span>
#include <string_view>

namespace bezinv::kernels {

inline constexpr int kMaxBatchSize = 32;    // the largest n of any kernel
inline constexpr int kBatchAlignment = 8;   // lanes per AVX-512 register of doubles; strides are multiples

// The sizes each kernel is compiled for, n in [MinSize, MaxSize]: every size is one
// instantiation per instruction set, so only the sizes the engine calls (engine/src/pipeline/limits.hpp
// asserts its thresholds against these). Any other n throws std::out_of_range naming the kernel
// and its range.
inline constexpr int kSymmetricSvdMinSize = 2;            // symmetric_svd (Eigen above the max)
inline constexpr int kSymmetricSvdMaxSize = 16;
inline constexpr int kNullVectorMinSize = 2;              // null_vector
inline constexpr int kNullVectorMaxSize = kMaxBatchSize;
inline constexpr int kNullVectorSeedMinSize = 3;          // null_vector_seed (n = 3: the adjugate); the
inline constexpr int kNullVectorSeedMaxSize = 8;          // engine forms B in the seed from n = 8 on (8 is
                                                          // here for the test that the two seeds agree)
inline constexpr int kBezoutNullVectorSeedMinSize = 8;    // bezout_null_vector_seed
inline constexpr int kBezoutNullVectorSeedMaxSize = kMaxBatchSize;
inline constexpr int kBezoutMatrixMinSize = 2;            // bezout_matrix
inline constexpr int kBezoutMatrixMaxSize = kMaxBatchSize;
inline constexpr int kBernsteinParameterMinSize = 2;      // bernstein_parameter
inline constexpr int kBernsteinParameterMaxSize = kMaxBatchSize;
inline constexpr int kRationalNewtonMinDegree = 1;        // rational_newton: the curve's degree
inline constexpr int kRationalNewtonMaxDegree = kMaxBatchSize;
inline constexpr int kSpaceCheckMinDegree = 1;            // space_check: the curve's degree
inline constexpr int kSpaceCheckMaxDegree = kMaxBatchSize;
inline constexpr int kFormulaParameterMinDegree = 1;      // formula_parameter: the formula's degree
inline constexpr int kFormulaParameterMaxDegree = kMaxBatchSize;
inline constexpr int kFormulaNewtonMinDegree = 2;         // formula_newton: the curve's degree (a conic's
inline constexpr int kFormulaNewtonMaxDegree = 3;         // or a cubic's few operations)

// null_vector's solves from (1, ..., 1); null_vector_iterations takes at least as many.
inline constexpr int kNullVectorIterations = 3;

// The plane curve of rational_newton, (x_num / x_den, y_num / y_den): four polynomials in the
// Bernstein basis of degree `degree` (kRationalNewtonMinDegree..kRationalNewtonMaxDegree),
// degree + 1 coefficients each. With one denominator, y_den may be the very array x_den (the same
// pointer): the de Casteljau kernels then evaluate it once, with the same bits.
//
// `horner`, for the kernels that evaluate by Horner's rule (rational_slope, nearest_newton: O(n) a
// jet where de Casteljau is O(n^2); rational_newton ignores it), is the layout of the engine's
// plan.horner: per polynomial (x_num, x_den, y_num, y_den) 3 * degree numbers, c_i C(n,i)
// (i = 0..n), then the first derivative's n (c_{i+1} - c_i) C(n-1,i), then the second's n (n-1)
// (c_{i+2} - 2 c_{i+1} + c_i) C(n-2,i). Other rounding than de Casteljau's: those kernels' answers
// are not the scalar refinement's bits (the engine's off-curve path takes them, and the certified
// search proves, not compares, what they find).
struct RationalCurve {
  int degree;
  const double* x_num;
  const double* x_den;
  const double* y_num;
  const double* y_den;
  const double* horner = nullptr;
};

// The safeguards of rational_newton (the engine passes its tolerances.hpp values).
struct NewtonSettings {
  int max_iterations;   // Newton iterations
  double max_step;      // largest step in t of one iteration
  double trusted_step;  // steps up to this are taken without the descent test
  int max_halvings;     // of a larger step, looking for descent
  double final_step;    // a step up to this, where f' >= |P'|^2 / 2, is the last (see rational_newton)
  // A lane whose distance at its start exceeds this is off the curve for the caller's purpose:
  // it stops there (see rational_newton). Infinite: no lane stops.
  double leave_distance = std::numeric_limits<double>::infinity();
};

// The safeguards of nearest_newton (the engine passes its tolerances.hpp values).
struct NearestNewtonSettings {
  int max_iterations;  // Newton iterations (a halved step is one)
  double max_step;     // largest step in t of one iteration
  double trusted_step; // steps up to this are taken without the descent test
  int max_halvings;    // of one step whose end is farther than its start
  double final_step;   // a step up to this, where f' >= |P'|^2 / 2, is the last
};

// The space curve of space_check, P = (x / D_x, y / D_y, z / D_z), of degree `degree`
// (kSpaceCheckMinDegree..kSpaceCheckMaxDegree), laid out for Horner's rule on its polynomials and
// their derivatives side by side (the engine's SpaceData::first_order_forward and
// first_order_backward). With one denominator D (denominators = 1), width 8: entry i * 8 + j,
// i = 0..degree, is coefficient i, times C(degree, i), of x, y, z, D (j = 0..3) and, times
// C(degree - 1, i), of their derivatives (j = 4..7). With separate ones (denominators = 3), width
// 16: x, y, z, D_x, D_y, D_z (j = 0..5) and their derivatives (j = 8..13; 6, 7, 14, 15 zero).
// A derivative has one coefficient fewer: `forward` has a zero at i = degree, `backward` has the
// derivatives shifted up by one, a zero at i = 0.
struct SpaceCurve {
  int degree;
  int denominators;  // 1 or 3
  const double* forward;
  const double* backward;
};

// An inversion formula t = N(u, v) / M(u, v) of formula_parameter (the engine's FormulaPathData):
// N and M of total degree `degree` (kFormulaParameterMinDegree..kFormulaParameterMaxDegree) in the
// Chebyshev basis of a frame, sum_{i + j <= degree} c_ij T_i(a) T_j(b) with
// a = (u - centre_u) * inverse_half_u, b = (v - centre_v) * inverse_half_v, their (degree + 1)
// (degree + 2) / 2 coefficients in PlanePolynomial::index order (by i + j, then by j). Where the
// formula is not used: beyond max_coordinate in u or v, and where |M| is below min_denominator
// times the sum of its terms' sizes (near a base point of the formula: a double point, a cusp).
struct PlaneFormula {
  int degree;
  double centre_u, centre_v, inverse_half_u, inverse_half_v;
  double max_coordinate, min_denominator;
  const double* n;
  const double* m;
};

// How formula_newton normalizes a point (x, y) (the engine's PlanData::normalize): with `scale` a
// power of two and the centre given times it, (dx, dy) = (x scale - centre_x, y scale - centre_y),
// then the rotation (u, v) = (cos dx - sin dy, sin dx + cos dy), in that order.
struct PointFrame {
  double scale, centre_x, centre_y, cos, sin;
};

// Where formula_newton puts what it computes on the way, for every lane l < count (arrays count
// long): the point normalized by the frame (u, v) and N / M (t, as formula_parameter gives it,
// NaN where the formula is not used), so that a caller who takes a lane further need not again.
struct FormulaStart {
  double* u;
  double* v;
  double* t;
};

// Which lanes formula_newton does not settle, and which of those rational_newton's first iteration
// leaves where started from N / M (N / M in [0, 1], 1e-150 < h < 1e150 and h above
// settings.leave_distance), as bits: lane l is bit l % 64 of word l / 64, (count + 63) / 64 words.
// The kernel sets bits and clears none (the caller zeroes the words), so that a caller that sorts
// the lanes by kind need not test them one by one; a batch all settled (on a curve) sets none.
struct FormulaLanes {
  std::uint64_t* left;
  std::uint64_t* leaves;
};

// The isolation certificate's first test as formula_newton makes it (the engine's
// isolated_by_far_boxes): [0, 1] cut into `pieces` equal pieces, t in piece
// j = min(pieces - 1, int(t pieces)); a lane at t and distance d passes where
// (d < monotone[j] * monotone_factor or d < unique[j]) and far[j] - d > limit.
// With floors under those bounds (far[j] >= far_floor for every j, and monotone[j] * monotone_factor
// >= around_floor for every j or unique[j] >= around_floor for every j; -inf where unknown), a lane
// with d < around_floor and far_floor - d > limit passes in any piece (a rounded difference is
// monotone in its first operand): most lanes on a curve, without looking up their piece.
struct PieceCertificate {
  int pieces;
  const double* monotone;
  double monotone_factor;
  const double* unique;
  const double* far;
  double limit;
  double around_floor = -std::numeric_limits<double>::infinity();
  double far_floor = -std::numeric_limits<double>::infinity();
};

// One instruction set's kernels. All function pointers are non-null.
struct Implementation {
  std::string_view name;  // "scalar", "avx2", "avx512"

  // Singular value decomposition of every matrix of the batch (for symmetric B: its Jacobi
  // eigendecomposition; sigma = |lambda|, vectors = eigenvectors, both sorted by sigma descending).
  // n in [kSymmetricSvdMinSize, kSymmetricSvdMaxSize].
  void (*symmetric_svd)(int n, std::size_t count, std::size_t stride, const double* B, double* sigma,
                        double* V);

  // The null vector of every (nearly) singular matrix by LU with partial pivoting and inverse
  // iteration from (1, ..., 1) (every Bernstein basis vector is positive, so it always has a
  // component along the null vector). n in [kNullVectorMinSize, kNullVectorMaxSize]. Writes z (unit 2-norm) and, per lane, a quality
  // estimate `defect[l]` >= 0: small when the iteration converged to the singular vector of a
  // simple smallest singular value (nullity 1, or a slightly regular matrix: how singular B is,
  // estimate[l] says); lanes whose defect exceeds the caller's threshold must be redone with
  // symmetric_svd.
  // `estimate` (may be null; 2 rows of `stride`) receives the evidence without an SVD, both
  // relative to ||B||_F:
  //   estimate[l]          ||B z|| / ||B||_F, an upper bound of sigma_n / ||B||_F;
  //   estimate[stride + l] 1 / ||B^-1 w|| after inverse iterations orthogonal to z: an estimate of
  //                        sigma_{n-1} / ||B||_F from above (up to rounding; exact when w has
  //                        converged, and the fixed start w has a generic component along every
  //                        direction).
  // `second` (may be null; laid out like z) receives that deflated iterate, unit length
  // and orthogonal to z: an approximation of the singular vector of sigma_{n-1}, so that z and
  // second span the near-null space when sigma_{n-1} is small too.
  void (*null_vector)(int n, std::size_t count, std::size_t stride, const double* B, double* z,
                      double* defect, double* estimate, double* second);

  // null_vector with `iterations` solves from (1, ..., 1) instead of its three (iterations >= 3,
  // else std::invalid_argument; 3 gives null_vector's bits). Inverse iteration damps the other
  // directions by sigma_n / sigma_{n-1} per solve: where that is ~0.1 (a point near, not on, a
  // curve whose B has a small sigma_{n-1}), three solves leave z unsettled and a few more settle it.
  void (*null_vector_iterations)(int n, int iterations, std::size_t count, std::size_t stride, const double* B,
                                 double* z, double* defect, double* estimate, double* second);

  // A cheaper null vector, for a seed: inverse iteration from (1, ..., 1), but two solves instead
  // of three, with B = L D L^T factored without pivoting (n^3 / 6 multiply-adds, no per-lane row
  // swaps) and without the iterations orthogonal to z (no sigma_{n-1} estimate, no second
  // vector). Writes z (unit 2-norm), residual[l] = ||B z|| / ||B||_F and defect[l] = the chord
  // between the two iterates (null_vector's measure 1, over one step). Reads only B's lower
  // triangle. n in [kNullVectorSeedMinSize, kNullVectorSeedMaxSize].
  // The residual is computed only where defect[l] <= settled_defect, and is +inf elsewhere: a seed
  // that has not settled is of no use, and the residual forms B once more (1 or more: every lane,
  // the defect being at most 1). Each lane's numbers are the same whatever its batch.
  // Unpivoted, z may be poor after a small pivot, and a settled z is not proof of a simple null
  // vector: callers check what they make of it by other means (the engine's isolation
  // certificate) and send the lanes they cannot settle to null_vector or symmetric_svd
  // (docs/kernels.md, "The seed").
  // At n = 3, z is instead adj(B)^2 (1, 1, 1) normalised (the same two steps of inverse iteration,
  // without a factorization: adj(B) = det(B) B^-1), and the defect is the sine of the angle
  // between the two steps (batch/adjugate_null_vector-inl.hpp).
  void (*null_vector_seed)(int n, std::size_t count, std::size_t stride, const double* B, double* z,
                           double* defect, double* residual, double settled_defect);

  // Newton's method for the nearest point of `curve` to (u[l], v[l]) on the segment [0, 1], one
  // point per lane from the start t[l]: the engine's safeguarded refinement (engine/src/refine.hpp,
  // refine_parameter with stay_on_segment), operation for operation and without fused
  // multiply-add, so every implementation gives the scalar code's bits. Steps of
  // f(t) = (P(t) - P0) . P'(t), with f' = |P'|^2 + (P - P0) . P'' (|P'|^2 where that is not
  // positive), capped at settings.max_step and clamped to [0, 1]; a step above
  // settings.trusted_step is halved until |P(t) - P0| does not increase; a step of at most
  // settings.final_step, not cut by the clamp, where f' >= |P'|^2 / 2, is the last. A settled lane
  // gets its t and distance[l] = |P(t) - P0| (after a last step, by the first-order update
  // |P - P0 + P' s| of the distance before it; else measured before the last step where that
  // moved t by a few ulps). A lane the kernel does not settle (start not in [0, 1], or a distance that is not
  // finite or that the scalar code would compute with std::hypot) keeps its t and gets
  // distance[l] = NaN: the caller runs the scalar code for it. A lane whose distance at its start
  // exceeds settings.leave_distance keeps its t and gets distance[l] = +inf: a caller that cannot
  // tell the points on the curve from those off it before (no estimate) takes the latter to a
  // cheaper kernel, at the cost of one comparison. Every other lane is unaffected. Returns the
  // number of lanes left so (0 without a finite leave_distance). Arrays have `count` entries;
  // curve.degree in [kRationalNewtonMinDegree, kRationalNewtonMaxDegree].
  std::size_t (*rational_newton)(const RationalCurve& curve, const NewtonSettings& settings, std::size_t count,
                                 const double* u, const double* v, double* t, double* distance);

  // Starts for nearest_newton: per lane, the nearest to (u[l], v[l]) of every `stride`-th sample
  // k = 0, stride, 2 stride, ... <= last of a curve (samples: x, y of sample k at 2k, 2k + 1; the
  // first of equally near ones), moved to the vertex of the parabola through the squared
  // distances of it and its two sampled neighbours (at most one spacing): t[l] in [0, 1] as
  // k / last. Without fused multiply-add: every implementation gives the same bits.
  void (*nearest_sample)(const double* samples, int last, int stride, std::size_t count, const double* u,
                         const double* v, double* t);

  // Newton's method for the nearest point of `curve` to (u[l], v[l]) on the segment [0, 1], from
  // the start t[l], for points off the curve: the engine's certified search proves what it
  // finds, so it has no scalar twin to match, and costs a fraction of rational_newton's
  // (batch/nearest_newton-inl.hpp says how). Steps of f(t) = (P(t) - P0) . P'(t) with
  // f' = |P'|^2 + (P - P0) . P'' (|P'|^2 where that is not positive), capped at
  // settings.max_step and clamped to [0, 1]; a step above settings.trusted_step whose end is
  // farther from P0 than its start is halved back from its start (at most settings.max_halvings times); a step of at most
  // settings.final_step where f' >= |P'|^2 / 2 is the last, its distance by the jet's Taylor
  // polynomial |E + P' s + P'' s^2 / 2|. A settled lane gets its t and distance[l] = |P(t) - P0|;
  // out of iterations, the last point whose distance did not increase. A lane not settled (start
  // not in [0, 1], a distance that is not finite) keeps its t and gets distance[l] = NaN.
  // curve.horner is required; curve.degree in [kRationalNewtonMinDegree, kRationalNewtonMaxDegree].
  // Every implementation gives the same bits (fused multiply-adds on every target).
  void (*nearest_newton)(const RationalCurve& curve, const NearestNewtonSettings& settings, std::size_t count,
                         const double* u, const double* v, double* t, double* distance);

  // P(t[l]) = (x[l], y[l]) and P'(t[l]) = (dx[l], dy[l]) of `curve` by Horner's rule on
  // curve.horner (required), for `count` lanes: the engine's curve_slope_horner, operation for
  // operation and without fused multiply-add, so every implementation gives its bits (the
  // off-curve path's stationarity test of many hints at once). curve.degree in
  // [kRationalNewtonMinDegree, kRationalNewtonMaxDegree].
  void (*rational_slope)(const RationalCurve& curve, std::size_t count, const double* t, double* x, double* y,
                         double* dx, double* dy);

  // The paper's read-out (Marco & Martinez Sect. 3) for every lane's vector z (n components,
  // laid out as null_vector writes it; n in [kBernsteinParameterMinSize, kBernsteinParameterMaxSize]): for z along the Bernstein basis (beta_0(t), ...,
  // beta_{n-1}(t)) of degree n-1, consecutive components give t = i z_i / (i z_i + (n-i) z_{i-1}),
  // taken at the largest component and the larger of its neighbours. NaN where that denominator is
  // 0. Writes t[0..count); the engine's parameter_from_null_vector gives the same bits.
  void (*bernstein_parameter)(int n, std::size_t count, std::size_t stride, const double* z, double* t);

  // The Bezout matrix of every lane's point (u[l], v[l]) from the coefficient matrices B0, Bx, By,
  // Bxy (n x n, row-major, n in [kBezoutMatrixMinSize, kBezoutMatrixMaxSize]; the engine's
  // InversionPlan holds them, engine/include/bezinv/plan.hpp): entry (r, c), r >= c, of lane l is
  //     B[(r * n + c) * stride + l] = ((B0 - u Bx) - v By) + (u v) Bxy   at index r * n + c,
  // or (B0 - u Bx) - v By when Bxy is null (one denominator W: Bxy = Bez(W, W) = 0, and B is
  // affine in (u, v)), in that order and without fused multiply-add, so every implementation
  // gives the engine's bits (bezout_at).
  // The upper triangle is not written (the kernels read only r >= c). poison[l] is the sum of the
  // lane's entries times 0: 0, or NaN when an entry overflowed. The padding lanes of the last SIMD
  // vector get B0 (finite, as this layout asks); u, v and poison are read and written for l < count.
  void (*bezout_matrix)(int n, std::size_t count, std::size_t stride, const double* B0, const double* Bx,
                        const double* By, const double* Bxy, const double* u, const double* v, double* B,
                        double* poison);

  // null_vector_seed on the Bezout matrices of the points (u[l], v[l]), l < count, formed from the
  // coefficient matrices as bezout_matrix forms them, bit for bit, but in
  // registers and never stored: the same z, defect and residual as bezout_matrix followed by
  // null_vector_seed (for the n both take), and the same poison (NaN for a lane whose B overflowed; its other outputs
  // are then meaningless). At high degree a batch's B does not fit in L1, and reading it back
  // would be most of the seed's time. z, defect and residual are laid out as null_vector_seed's
  // (stride), the residual also only where defect[l] <= settled_defect. The settled lanes of a
  // SIMD group of mostly unsettled ones have their residual computed after the others, compacted,
  // so that a batch of points off the curve pays for the few that settled only.
  // n in [kBezoutNullVectorSeedMinSize, kBezoutNullVectorSeedMaxSize].
  void (*bezout_null_vector_seed)(int n, std::size_t count, std::size_t stride, const double* B0, const double* Bx,
                                  const double* By, const double* Bxy, const double* u, const double* v, double* z,
                                  double* defect, double* residual, double* poison, double settled_defect);

  // The check in space of a space curve's answers (engine/src/space/space_curve.cpp, space_refine's
  // first test), one point per lane: P(t) and P'(t) at the lane's t[l] in [0, 1] by Horner's rule,
  // the distance to the point (x[l], y[l], z[l]), and whether the Newton step of
  // (P - P0) . P' is below rounding (|g| / |P'|^2 <= 2 eps + 2 eps / |P'|): t is then the nearest
  // parameter to rounding. distance[l] = |P(t) - P0| where it is, NaN where it is not, where t is
  // not in [0, 1] or the distance is not finite (the caller runs the scalar code for those). The
  // operations are the engine's scalar ones in the same order, without fused multiply-add: a lane
  // settled here has the engine's bits. Arrays have `count` entries.
  void (*space_check)(const SpaceCurve& curve, std::size_t count, const double* t, const double* x, const double* y,
                      const double* z, double* distance);

  // t[l] = N / M at the point (u[l], v[l]) of `formula`, l < count, or NaN where the formula is not
  // used there (PlaneFormula says where; NaN points too): the engine's formula_parameter, operation
  // for operation and without fused multiply-add, so every implementation gives its bits. O(d^2)
  // a point where the Bezout seed is O(n^3): the formula path's algebraic step for a whole batch.
  void (*formula_parameter)(const PlaneFormula& formula, std::size_t count, const double* u, const double* v,
                            double* t);

  // The formula path's common case for a conic or a cubic, in one pass (a point on the curve away
  // from the formula's base points and from other branches): per point (xy[2l], xy[2l + 1]),
  // l < count, normalized by `frame`, t = N / M of `formula` (as formula_parameter), then
  // rational_newton's first iteration from that t with `settings` (settings.leave_distance
  // included). Where that iteration settles the lane (its last step, or a step that converged where
  // t's last ulps do not move P), at a distance of at most `tolerance` that `certificate` passes:
  // t[l] and distance[l] as formula_parameter then rational_newton give them, bit for bit. Every
  // other lane gets t[l] = NaN, and distance[l] = the first iteration's distance h = |P(t0) - P0|,
  // t0 = N / M clamped to [0, 1] (as the kernel's length computes it: NaN or inf where not finite):
  // the caller takes the lane the long way, and where t0 = N / M is in [0, 1] and
  // 1e-150 < h < 1e150 (length()'s own range: there rational_newton's first test keeps the lane),
  // h above settings.leave_distance tells that rational_newton's first iteration leaves it.
  // With `start` (else null), each lane's normalized point and N / M too (FormulaStart); with
  // `lanes` (else null), the lanes not settled and those the first iteration leaves as bits
  // (FormulaLanes). Returns the number of lanes settled. curve.degree in [kFormulaNewtonMinDegree,
  // kFormulaNewtonMaxDegree], formula.degree in formula_parameter's range.
  std::size_t (*formula_newton)(const PlaneFormula& formula, const RationalCurve& curve, const NewtonSettings& settings,
                                const PointFrame& frame, const PieceCertificate& certificate, double tolerance,
                                std::size_t count, const double* xy, double* t, double* distance,
                                const FormulaStart* start, const FormulaLanes* lanes);
};

// The implementation for this process: the best the CPU supports, or the one named by the
// environment variable BEZINV_KERNEL (scalar | avx2 | avx512), chosen once at first use.
// An unknown or unsupported BEZINV_KERNEL is reported on stderr once and the best is used.
const Implementation& active_implementation();

// Every implementation this build has that this CPU can run (scalar first). For tests and benchmarks.
std::span<const Implementation* const> available_implementations();

// stride for a batch of `count` matrices.
constexpr std::size_t batch_stride(std::size_t count) {
  return (count + kBatchAlignment - 1) / kBatchAlignment * kBatchAlignment;
}

}  // namespace bezinv::kernels
