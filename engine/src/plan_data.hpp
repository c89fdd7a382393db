#pragma once
// What an InversionPlan holds: the per-curve precomputation the pipeline reads (engine internal;
// bezinv/plan.hpp is what a user sees).
//
// For a point (x0, y0), with p = X_num - x0 X_den and q = Y_num - y0 Y_den, bilinearity and
// antisymmetry of the Bezoutian give
//     B(x0, y0) = Bez(X_num, Y_num) - x0 Bez(X_den, Y_num) - y0 Bez(X_num, Y_den) + x0 y0 Bez(X_den, Y_den)
//               =        B0         - x0        Bx          - y0        By          + x0 y0     Bxy,
// with Bxy = Bez(W, W) = 0 when the denominators are one W (rational Bezier), so B is affine there.
#include <algorithm>
#include <array>
#include <atomic>
#include <cmath>
#include <limits>
#include <memory>
#include <mutex>
#include <span>
#include <string>
#include <cstdint>
#include <vector>

#include "bezinv/curve.hpp"
#include "bezinv/plan.hpp"

namespace bezinv::detail {

// The spacing of the doubles at `magnitude` (>= 0): the step up, except at the largest double,
// whose step up is inf (which made the tolerance floor inf there: every point on the curve).
inline double ulp(double magnitude) {
  const double above = std::nextafter(magnitude, std::numeric_limits<double>::infinity());
  return std::isfinite(above) ? above - magnitude : magnitude - std::nextafter(magnitude, 0.0);
}

// The exponent e of the scale 2^e that normalizes a curve whose control box has half-diagonal
// `half_diagonal` (> 0) and largest coordinate `magnitude`: about the half-diagonal, so the
// normalized curve is a few units wide; clamped so that 2^-e is a double too (the clamp does
// nothing for diagonals from 1e-301 to the largest double; past it, 2^1023 leaves the normalized
// curve a few units wide); and never so small that the coordinates' resolution, kResolutionUlps
// ulps of `magnitude`, overflows in normalized units, which made the tolerance inf (a curve 1e-300
// wide at 1e308, far narrower than its coordinates resolve, is normalized as if 2^-960 of an ulp
// of them wide: a point to the engine, within the tolerance of every point near it).
inline int normalizing_exponent(double half_diagonal, double magnitude) {
  int e = 0;
  std::frexp(half_diagonal, &e);
  e = std::clamp(e + 1, -1000, 1023);
  if (magnitude > 0 && std::isfinite(magnitude)) e = std::min(std::max(e, std::ilogb(ulp(magnitude)) - 960), 1023);
  return e;
}

// The principal axes of a curve's control points come from the squares of their offsets from the
// box's centre in normalized units, about 1. Offsets far from 1 (a control point of a negative
// weight far outside its tiny segment; a curve narrower than its coordinates resolve) would make
// those squares overflow or underflow: the power of two that brings the largest, `farthest`, to
// about 1 (exact; the axes do not change), and 0, no scaling and the same bits, inside [2^-100, 2^100].
inline int offset_rescaling(double farthest) {
  if (!(farthest > 0) || !std::isfinite(farthest) || (farthest >= 0x1p-100 && farthest <= 0x1p100)) return 0;
  return -std::ilogb(farthest);
}

// What only the answers off the curve need: the certified nearest point of the segment and the
// clearance of the extension. Up to about four times the rest of a plan to make (sign tests on
// pieces of polynomials of degree up to 6n), so a plan makes it on first use (off_curve_data), and plans
// whose points are all on the curve never pay for it.
struct SpaceData;
struct PiecewiseData;

struct OffCurveData {
  // The certified nearest-point search (engine/src/stationary_points.hpp): on each of
  // kStationaryPieces pieces of [0, 1], the Bernstein coefficients (degree stationary_degree) of
  // G0, Gx, Gy, with G0 - u0 Gx - v0 Gy of the sign of the distance's derivative (piece-major:
  // G0, Gx, Gy of piece 0, then piece 1, ...), and per piece and polynomial a bound of the terms
  // that round in them; per piece the box around its isolation boxes (x min, x max, y min, y max).
  // Empty (degree 0) where the plan is not usable.
  int stationary_degree = 0;
  std::vector<double> stationary_g, stationary_scale, stationary_boxes;

  // The clearance of the extension (engine/src/extension.hpp): on each of its pieces (of t >= 1
  // and t <= 0, each as s in [0, 1]; ordered by extension_far2, smallest first, NaN before all, so
  // that a point stops at the first piece whose radius it lies within) the Bernstein coefficients (degree
  // extension_degree) of H0, Hx, Hy, Hw (piece-major), per piece and polynomial a bound of the
  // terms that round in them, and the box of the piece's control points (x min, x max, y min,
  // y max; NaN where its weights are not of one sign), and the square of a radius about the
  // origin it stays outside (0: none). Empty (degree 0) below degree 2.
  int extension_degree = 0;
  std::vector<double> extension_h, extension_scale, extension_boxes, extension_far2;
  // Per piece, the boxes of its parts (extension_parts[4 k .. 4 k + 3] for k from
  // extension_part_begin[piece] to extension_part_begin[piece + 1]; none for most pieces): a wide
  // piece near the curve halved, its curve alone, until each part is narrow
  // (extension.hpp, kExtensionPartRatio).
  std::vector<double> extension_parts;
  std::vector<std::uint32_t> extension_part_begin;
  // Per piece and per part, a capsule that holds it: the chord from its first control point to its
  // last and a reach about it that every control point is within (a x, a y, b x, b y, reach,
  // extension.hpp, kCapsuleStride each; NaN reach where there is none: separate denominators, or
  // weights not of one sign). Parallel to extension_boxes and extension_parts.
  std::vector<double> extension_capsules, extension_part_capsules;
  // Per piece, where it is: its half (0: t >= 1, 1: t <= 0) and its interval of s, three doubles
  // each (for the tests and for diagnostics; the proof does not read them).
  std::vector<double> extension_intervals;
};

// What clears most points of the extension at once (engine/src/extension.hpp, extension_grid):
// per cell of a kExtensionGrid x kExtensionGrid grid over the segment's surroundings (cell (i, j)
// from u + i / inverse_cell, v + j / inverse_cell, row-major in j) a distance within which no piece
// of the extension comes of any point of the cell. Empty where there is no extension. Per cell
// also the pieces whose own such distance is below listed_below, nearest first (cell k's from
// near_begin[k] to near_begin[k + 1] in near_piece, their distances in near_bound).
struct ExtensionGrid {
  double u = 0.0, v = 0.0, inverse_cell = 0.0;
  std::vector<double> clear;
  double listed_below = 0.0;
  std::vector<std::uint32_t> near_begin, near_piece;
  std::vector<double> near_bound;
};

// A count that plans share between threads and a copy of a plan starts again at 0.
class SharedCount {
 public:
  SharedCount() = default;
  SharedCount(const SharedCount&) {}
  SharedCount& operator=(const SharedCount&) {
    count_.store(0, std::memory_order_relaxed);
    return *this;
  }
  // The count after adding k.
  std::size_t add(std::size_t k) const { return count_.fetch_add(k, std::memory_order_relaxed) + k; }

 private:
  mutable std::atomic<std::size_t> count_{0};
};

// The inversion formula as the formula path evaluates it (engine/src/pipeline/formula_path.hpp):
// t = N / M with N, M sums of c_ij T_i(a) T_j(b), i + j <= degree, in the coordinates of the
// formula's frame, a = (u - centre_u) / half_u, b = (v - centre_v) / half_v from the plan's
// normalized (u, v) (bezinv/inversion_formula.hpp). `usable` only where the formula exists and is
// accurate on the segment (kFormulaPathMaxSegmentError).
struct FormulaPathData {
  bool usable = false;
  int degree = 0;
  double centre_u = 0.0, centre_v = 0.0, inverse_half_u = 1.0, inverse_half_v = 1.0;
  std::vector<double> n, m;  // PlanePolynomial::index order
};

// Made once, by whichever thread first asks (the plan is shared const between threads). A copy of
// a plan starts empty and makes its own: the copy may be changed before its first use.
template <class Data>
class Lazy {
 public:
  Lazy() = default;
  Lazy(const Lazy&) : Lazy() {}
  Lazy& operator=(const Lazy&) {
    slot_ = std::make_unique<Slot>();
    return *this;
  }
  Lazy(Lazy&&) noexcept = default;
  Lazy& operator=(Lazy&&) noexcept = default;

  template <class Make>
  const Data& get(Make&& make) const {
    // Made already, the common case: one load (std::call_once costs a call per use, and the
    // off-curve path asks several times per point).
    if (slot_->made.load(std::memory_order_acquire)) return slot_->data;
    std::call_once(slot_->once, [&] {
      make(slot_->data);
      slot_->made.store(true, std::memory_order_release);
    });
    return slot_->data;
  }

  // The data if it has been made, else null (without making it).
  const Data* if_made() const {
    return slot_->made.load(std::memory_order_acquire) ? &slot_->data : nullptr;
  }

 private:
  struct Slot {
    std::once_flag once;
    std::atomic<bool> made{false};
    Data data;
  };
  std::unique_ptr<Slot> slot_ = std::make_unique<Slot>();
};

struct PlanData {
  Curve curve;          // as given (validated)
  int input_degree = 0; // degree as given
  int degree = 0;       // effective degree n after exact reduction of a degree-elevated curve

  // Normalization (docs/accuracy-model.md, "Normalization"): u = R (P - centre) / scale, with R a rotation (identity for separate
  // denominators, which a rotation would mix); each numerator/denominator pair is also divided by
  // its largest denominator coefficient. Translation and rotation leave B unchanged in exact
  // arithmetic (Bez is alternating: a unimodular change of (p, q) multiplies it by det = 1); the
  // scale and the denominator division multiply it by 1/(scale^2 max|x_den| max|y_den|). So the
  // null vectors, the singular-value ratios and the algebraic parameter are the same; in floating point the
  // affine combination below no longer cancels digits for curves far from the origin, and a line
  // parallel to an axis no longer makes p identically zero.
  // scale is the power of two in [diagonal, 2 diagonal) (1 for a curve of one point): scaling adds
  // no rounding, and normalizing a point is a multiplication by inverse_scale.
  std::array<double, 2> centre{0.0, 0.0};
  double scale = 1.0, inverse_scale = 1.0;
  double cos_rotation = 1.0, sin_rotation = 0.0;

  // The normalized curve at the effective degree (n+1 coefficients each).
  std::vector<double> x_num, x_den, y_num, y_den;
  bool common_denominator = true;

  // B(u0, v0) = B0 - u0 Bx - v0 By + u0 v0 Bxy in normalized coordinates (n x n, row-major).
  std::vector<double> B0, Bx, By, Bxy;
  // The curve lies on a straight line (within kVanishingBezoutRatio of its size): B vanishes at
  // every point of it, and its points are inverted from the roots of p (engine/src/pipeline/decide.cpp).
  bool straight_line = false;
  // The curve is close to one of degree n - 1 (kNearLowerDegreeRatio): B is nearly singular twice
  // over at every point, and Algebraic::automatic takes the formula path where linear_formula is
  // usable (formula_path.hpp).
  bool near_lower_degree = false;
  // A polynomial curve with a direction e along which e . P(t) is linear in t (a function's graph
  // y = f(x) with x(t) linear, and its rotations): t = (e . P - e . P(0)) / (e . P'), an inversion
  // formula of degree 1 valid at every point, which the formula path takes before the curve's own
  // (plan.cpp, linear_direction_formula). Not usable otherwise.
  FormulaPathData linear_formula;
  // A conic's or a cubic's (one denominator) inversion formula of degree 1, made with the plan
  // (formula/linear_inversion_formula.hpp): Algebraic::automatic takes the formula path with it
  // where formula_weights_moderate. Not usable at other degrees or kinds.
  FormulaPathData low_degree_formula;
  // The denominator's coefficients of one sign and within kFormulaPathMaxWeightRatio of each other
  // (one denominator): where Algebraic::automatic may take low_degree_formula.
  bool formula_weights_moderate = false;
  // max |entry| of B0, Bx, By, Bxy: a bound of B's terms before they cancel, for any point.
  std::array<double, 4> bezout_max_entries{0.0, 0.0, 0.0, 0.0};

  // The normalized curve's four polynomials for Horner's rule (engine/src/refine.hpp,
  // curve_jet_horner): per polynomial c_i C(n,i), then its first and second derivatives' alike.
  std::vector<double> horner;

  // The nearest-point search's samples of the normalized curve, P(k / S) for k = 0..S as
  // (x, y) pairs (engine/src/refine.hpp): computed once here instead of for every off-curve point.
  std::vector<double> nearest_samples;

  // Isolation certificate (engine/src/isolation.hpp), for K = isolation_pieces pieces of [0, 1]: a
  // box holding each piece of the curve (K x centres, K x half-widths, then the same for y; the
  // whole plane where a weight is not positive), the distance from each box to the nearest box not
  // next to it, and per piece a bound that makes the curve monotone around it and the distance
  // from the curve below which a point has one nearest parameter there (0: none); and per group of
  // kIsolationGroup consecutive pieces the box around their boxes (x min, x max, y min, y max,
  // widened by kIsolationMargin), which clears the whole group with one comparison; per piece,
  // the distance from its box to the nearest box more than kIsolationWide pieces away. Empty for
  // degree < 2.
  int isolation_pieces = 0;
  std::vector<double> isolation_boxes, isolation_far, isolation_monotone, isolation_unique, isolation_groups,
      isolation_far_wide;
  // Floors of the first test's bounds over every piece: isolation_far[j] >= isolation_far_floor, and
  // isolation_monotone[j] * kDistinctParameterGap >= isolation_around_floor for every j or
  // isolation_unique[j] >= it for every j (-inf where a bound is NaN). A distance below both passes
  // the test in any piece (kernels::PieceCertificate).
  double isolation_far_floor = -std::numeric_limits<double>::infinity();
  double isolation_around_floor = -std::numeric_limits<double>::infinity();
  // Cells far from the segment (isolation.hpp, segment_far): over the pieces' boxes, a
  // kSegmentFarGrid x kSegmentFarGrid grid of bits, set for a cell that comes within
  // segment_far_reach of some piece's capsule or box (cell (i, j) from
  // segment_far_u + i / segment_far_inverse_cell_u, likewise in v; its bit segment_far_bit). Empty below
  // kSegmentFarMinDegree, or where a piece has no box (a weight that is not positive).
  double segment_far_u = 0.0, segment_far_v = 0.0, segment_far_inverse_cell_u = 0.0,
         segment_far_inverse_cell_v = 0.0, segment_far_reach = 0.0;
  std::vector<std::uint64_t> segment_far_near;
  // Per piece, with one denominator, a capsule that holds it where its box stands off it (a
  // slanted piece): the chord between its ends and the largest distance of a control point from
  // it (K x a x, a y, b x, b y, then K reaches; NaN reach for separate denominators, a weight
  // that is not positive, or K below kIsolationCapsuleMinPieces).
  std::vector<double> isolation_capsules;

  // What only answers off the curve use, built by the first point that asks (off_curve_data).
  Lazy<OffCurveData> off_curve;
  // The extension's grid, built once kExtensionGridAfter lanes of the plan have reached the
  // off-curve path (extension_grid), counted in extension_lanes.
  Lazy<ExtensionGrid> extension_grid;
  SharedCount extension_lanes;
  // The curve's inversion formula, made by the first batch that takes the formula path, projects an
  // off-curve point or reports N/M unrefined (formula_path_data).
  Lazy<FormulaPathData> formula_path;

  // A space curve (space/space_curve.hpp): this plan is its projection's, `curve` the projected
  // plane curve, and `space` the curve as given with what checks the answers in space. Null for a
  // plane curve.
  std::shared_ptr<const SpaceData> space;
  // A NURBS or composite curve (piecewise/piecewise_plan.hpp): the plans of its spans, `curve` the
  // curve as given; nothing else here is set but the diagonal, the degree and usable. Null otherwise.
  std::shared_ptr<const PiecewiseData> piecewise;

  // Power-basis leading coefficients of the four polynomials and their size bounds, for
  // detecting a degree drop of p and q at a given point (paper Sect. 4).
  double lead_x_num = 0, lead_x_den = 0, lead_y_num = 0, lead_y_den = 0;

  // Diagonal of the bounding box of the control points (input units): tolerances are relative to
  // it (inf for a box wider than the largest double; normalized_diagonal is finite).
  double diagonal = 0.0;
  double normalized_diagonal = 0.0;  // diagonal / scale
  // The floor of the on-curve tolerance, normalized units: kResolutionUlps ulps of the largest
  // coordinate of the box, so a point rounded to doubles from the curve counts as on it however
  // far from the origin the curve sits.
  double normalized_resolution = 0.0;

  // False when no point of the curve can be given one parameter (all its points coincide); every
  // point of it is then reported `failed` with `reason`.
  bool usable = true;
  const char* reason = "";  // static text

  // Input coordinates -> normalized (inline: the engine normalizes whole batches in one loop).
  std::array<double, 2> normalize(double x, double y) const {
    // Scaled before the difference (by a power of two: the same bits as scaling after it), so a
    // point near the largest double on the far side of the centre does not overflow.
    const double dx = x * inverse_scale - centre[0] * inverse_scale, dy = y * inverse_scale - centre[1] * inverse_scale;
    return {cos_rotation * dx - sin_rotation * dy, sin_rotation * dx + cos_rotation * dy};
  }
  // P(t) in normalized coordinates.
  std::array<double, 2> normalized_point(double t) const;
};


// The plan's data (the one accessor the engine uses; InversionPlan keeps it private).
inline const PlanData& plan_data(const InversionPlan& plan) { return *plan.data_; }

// Builds the data of make_plan.
PlanData make_plan_data(const Curve& curve);

// B(u0, v0) from the plan's matrices, for a point already in normalized coordinates.
void bezout_at(const PlanData& plan, double u0, double v0, std::span<double> out);

// The plan's OffCurveData, made on the first call (stationary_pieces, extension_pieces); safe to
// call from any number of threads at once.
const OffCurveData& off_curve_data(const PlanData& plan);

// The plan's formula for the formula path (made on first use; usable false where there is none).
const FormulaPathData& formula_path_data(const PlanData& plan);

}  // namespace bezinv::detail
