#pragma once
// Whether a point of the curve is isolated: whether the curve comes within the tolerance of it
// only on its own branch, around its own parameter (engine internal).
//
// The fast path must look for a second parameter where the SVD path would (a small sigma_{n-1}):
// it refines the roots of span{z, second} along the segment, and most of them walk, in safeguarded
// Newton steps, back to the point's own t (docs/fast-path.md, "The isolation certificate"). This
// certificate answers the same question without walking, from data
// computed once per curve, in one comparison for most lanes (one per piece for the rest):
//
//  1. Far from t. The curve is cut into K = plan.isolation_pieces pieces [j/K, (j+1)/K]. With positive
//     weights each coordinate of a piece is a convex combination of its control values (x = X/Wx
//     of the x[i] / wx[i], y of its own ratios, with separate denominators too), so the piece lies
//     in their box. If the box of every piece not next to t's is farther than the tolerance from
//     P0, no parameter there can end within the tolerance. With one denominator the piece also
//     lies in the convex hull of its control points, and so in the capsule about the chord
//     between its ends that reaches them all: where a box is not far enough (it stands off a
//     slanted piece by up to half its width), the capsule may be (from
//     kIsolationCapsuleMinPieces pieces on).
//  2. Around t (its piece and the two next to it, N). With positive weights,
//         P' = (Hx / Wx^2, Hy / Wy^2) = (Hx, r Hy) / Wx^2,   Hx = X'Wx - XWx',  r = Wx^2 / Wy^2,
//     and (Hx, r Hy) = sum_k B_k (hx_k, r hy_k) over the Bernstein coefficients of Hx and Hy
//     (degree 2n - 1, of each piece as a curve of its own). With r between its bounds r_lo and
//     r_hi from the weights (r = 1 for a common denominator), every tangent on N is a positive
//     combination of the generators (hx_k, r_lo hy_k), (hx_k, r_hi hy_k). If all of them lie
//     within an angle alpha < 45 degrees of a direction c, any two tangents on N make an angle
//     below 2 alpha, so for tau in N
//         (P(tau) - P(t)) . P'(tau) >= cos(2 alpha) |P(tau) - P(t)| |P'(tau)|   (sign of tau - t)
//     and |P(tau) - P(t)| >= v |tau - t| with v = min (generator . c) / max Wx^2 a lower bound
//     of P' . c on N. A stationary point of the distance to P0 (|P(t) - P0| = d) then has
//     cos(2 alpha) |P(tau) - P(t)| <= d, so |tau - t| <= d / (cos(2 alpha) v): below
//     kDistinctParameterGap when d is small enough. Away from t the distance strictly decreases
//     towards t, so a Newton walk that reaches N ends at t.
//  3. Off the curve (d larger than that sliver): one stationary point on N. Two local minima of
//     f(tau) = |P(tau) - P0|^2 on N would have a stationary point between them with f'' <= 0.
//     Every stationary point tau has |P(tau) - P(t)| <= d / cos(2 alpha) (above), so there
//         f'' / 2 = |P'|^2 + (P - P0) . P'' >= v^2 - d (1 + 1 / cos(2 alpha)) M,
//     M a bound of |P''| on N: positive when d < v^2 / ((1 + 1 / cos(2 alpha)) M). Then every
//     stationary point on N is a strict minimum, so there is only one, and t is it (t is where a
//     refinement ended: a stationary point, or an end of the segment, where the walks stop too).
//     M comes from x'' = (Gx Wx - 2 Wx' Hx) / Wx^3, Gx = Hx' = X''Wx - XWx'' (and y's alike),
//     each polynomial bounded by its largest Bernstein coefficient and W from below by its
//     smallest.
// Together: no walk from any root can end within the tolerance at a parameter distinct from t.
// Not certified (the roots are refined as before): a weight that is not positive, a piece of N
// that turns by 45 degrees or more, a point off the curve by more than 3. allows (about a quarter
// of the radius of curvature, or less), or a box near P0 (a second branch passing close, which is
// what the check is for) whose capsule is near P0 too.
#include <algorithm>
#include <cmath>
#include <cstddef>
#include <cstdint>

#include "bezinv/kernels/batch.hpp"
#include "plan_data.hpp"

namespace bezinv::detail {

// K, the number of pieces: 32 up to degree 9, more above (isolation_piece_count says why).
inline constexpr int kIsolationMaxPieces = 512;
int isolation_piece_count(int degree);
// From this many pieces on, each keeps a capsule besides its box (plan.isolation_capsules): a
// point near the curve, a few pieces' length from it, is often within the box of a slanted piece
// two or more away but beyond its capsule. With fewer, longer pieces, the capsule seldom clears
// what the box does not, and testing it cost more than it saved (0.985x at degree 3, noise 1e-2).
inline constexpr int kIsolationCapsuleMinPieces = 128;
// Pieces per group of plan.isolation_groups: a point far from a group's box is far from all of
// them, so isolated() looks at the pieces of the few groups near the point only (K divides by it).
inline constexpr int kIsolationGroup = 8;
// isolation_far_wide: per piece, the distance from its box to the nearest box more than this many
// pieces away.
inline constexpr int kIsolationWide = 8;

// The squared distance from (u0, v0) to the box of piece q (0 inside it, and for a NaN point).
inline double isolation_box_distance2(const PlanData& plan, int q, double u0, double v0) {
  const int K = plan.isolation_pieces;
  const double* box = plan.isolation_boxes.data();  // x centres, x half-widths, y centres, y half-widths
  double dx = std::abs(u0 - box[q]) - box[K + q], dy = std::abs(v0 - box[2 * K + q]) - box[3 * K + q];
  dx = dx > 0 ? dx : 0.0;
  dy = dy > 0 ? dy : 0.0;
  return dx * dx + dy * dy;
}

// The squared distance from (u0, v0) to the box {x min, x max, y min, y max} (0 inside it): the
// stored boxes of the certified search's pieces and of the extension's.
inline double box_distance2(const double* box, double u0, double v0) {
  const double dx = std::max({box[0] - u0, u0 - box[1], 0.0}), dy = std::max({box[2] - v0, v0 - box[3], 0.0});
  return dx * dx + dy * dy;
}

// The squared distance from (u0, v0) to the chord from (ax, ay) to (bx, by), and the scale of the
// coordinates it came from (|P0 - a| and |b - a| by their components): the computed projection
// is some point of the chord, within a few ulps of that scale of the nearest (the distance is
// stationary in it there), so a caller allows that many. The capsules of the isolation pieces
// and of the extension's.
struct ChordDistance {
  double distance2, scale;
};
inline ChordDistance chord_distance2(double ax, double ay, double bx, double by, double u0, double v0) {
  const double dx = bx - ax, dy = by - ay, px = u0 - ax, py = v0 - ay;
  const double length2 = dx * dx + dy * dy, along = px * dx + py * dy;
  const double s = !(along > 0) || !(length2 > 0) ? 0.0 : along >= length2 ? 1.0 : along / length2;
  const double fx = px - s * dx, fy = py - s * dy;
  return {fx * fx + fy * fy, std::abs(px) + std::abs(py) + std::abs(dx) + std::abs(dy)};
}

// Fills plan.isolation_boxes, isolation_far, isolation_far_wide, isolation_monotone,
// isolation_unique and isolation_groups from the normalized curve (make_plan).
void isolation_pieces(PlanData& plan);

// Whether (u0, v0) is farther than plan.segment_far_reach (kSegmentFarDistance of the normalized
// diagonal) from every point of the segment, by its cell of plan.segment_far_near: a cell whose
// bit is clear is that far from every piece's capsule (or box, where it has none), and each piece
// lies in both. False outside the grid, for a NaN, and where the plan has no grid. The fast path
// does not seed such a point from B (docs/fast-path.md, "Far from the segment, no seed").
inline constexpr int kSegmentFarGrid = 512;
inline constexpr int kSegmentFarMinDegree = 15;  // where the seed is dearest (below, the grid's cache
                                                  // lines cost points near the curve more than it saves)
inline constexpr double kSegmentFarDistance = 3e-4;
// make_plan's grid (isolation_pieces calls it, after the pieces' boxes and capsules).
void segment_far_grid(PlanData& plan);
// The bit of cell (gu, gv) in plan.segment_far_near: tiles of 8 x 8 cells, a word each, row by
// row of tiles, so that the cells along a curve share cache lines (a row of cells a word would
// spread a curve's cells over kSegmentFarGrid lines).
inline std::size_t segment_far_bit(std::size_t gu, std::size_t gv) {
  return ((gv / 8) * (kSegmentFarGrid / 8) + gu / 8) * 64 + (gv % 8) * 8 + gu % 8;
}
inline bool segment_far(const PlanData& plan, double u0, double v0) {
  if (plan.segment_far_near.empty()) return false;
  const double gu = (u0 - plan.segment_far_u) * plan.segment_far_inverse_cell_u;
  const double gv = (v0 - plan.segment_far_v) * plan.segment_far_inverse_cell_v;
  if (!(gu >= 0 && gu < kSegmentFarGrid && gv >= 0 && gv < kSegmentFarGrid)) return false;
  const std::size_t bit = segment_far_bit(static_cast<std::size_t>(gu), static_cast<std::size_t>(gv));
  return !((plan.segment_far_near[bit / 64] >> (bit % 64)) & 1u);
}

// True when no parameter distinct from t (by more than kDistinctParameterGap) can be where a
// refinement of the distance to (u0, v0) ends within `tolerance`; `distance` is |P(t) - (u0, v0)|,
// all in normalized units. False whenever the certificate does not apply.
bool isolated(const PlanData& plan, double u0, double v0, double t, double distance, double tolerance);

// The first test of isolated() for `count` lanes at once, in a loop that vectorizes (the fast
// path's common case): certified[l] = 1 where the distance to the boxes far from t[l] alone proves
// isolated(plan, u0, v0, t[l], distance[l], tolerance), whatever the point; 0 where isolated()
// must decide (it may still certify, testing the point against each box).
void isolated_by_far_boxes(const PlanData& plan, const double* t, const double* distance, double tolerance,
                           std::size_t count, std::uint8_t* certified);

// That first test as the formula_newton kernel makes it (the same comparisons, the same bits); the
// plan must have the certificate (plan.isolation_monotone not empty).
kernels::PieceCertificate far_boxes_certificate(const PlanData& plan, double tolerance);

// True when P(t), at `distance` from (u0, v0), is the nearest point of the whole segment: the
// certificate with the point's own distance for the tolerance (every box not next to t's farther
// than it), and the distance below isolation_unique (t the only stationary point around it, a
// strict minimum, so the distance falls towards t across its piece and the two next to it). t
// must be a stationary point of the distance (the caller checks it). The certified search's
// quick proof (stationary_points.cpp).
bool nearest_on_segment(const PlanData& plan, double u0, double v0, double t, double distance);

}  // namespace bezinv::detail
