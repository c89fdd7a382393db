#pragma once
// The curve beyond its segment, and the proof that none of it comes near a point (engine internal).
//
// The contract answers `outside_segment` where the extension of the curve (t outside [0, 1])
// passes within the tolerance of the point. An off-curve answer therefore needs, besides the
// nearest point of the segment, the proof that no point of the extension is that near: then no
// algebraic parameter could lead anywhere else, and the Bezout/SVD work decides nothing.
//
// The extension as two rational curves of [0, 1]. A polynomial of degree m in Bernstein form on
// [0, 1], sum c_i C(m,i) (1-t)^(m-i) t^i, is the form F(a, b) = sum c_i C(m,i) a^(m-i) b^i at
// (a, b) = (1 - t, t). With s in [0, 1],
//     t = 1 / (1 - s)    (t from 1 to +inf):   (a, b) ~ (-s, 1),   F = sum c_i C(m,i) (-s)^(m-i),
//     t = -s / (1 - s)   (t from 0 to -inf):   (a, b) ~ (1, -s),   F = sum c_i C(m,i) (-s)^i,
// both F(a, b) = (1 - s)^m f(t(s)): the same sign as f wherever t is finite, and at s = 1 the
// form's value at t = infinity. In the Bernstein basis of s the coefficients are alternating
// sums, b_j = sum_{k<=j} C(j,k) (-1)^k c_{m-k} (first half) and c_k in place of c_{m-k} (second).
//
// The clearance polynomial. For P0 = (u0, v0) and a radius r, with x = X / Wx, y = Y / Wy,
//     h = Wy^2 (X - u0 Wx)^2 + Wx^2 (Y - v0 Wy)^2 - r^2 Wx^2 Wy^2 = Wx^2 Wy^2 (|P - P0|^2 - r^2)
//       = H0 + u0 Hx + v0 Hy + (u0^2 + v0^2 - r^2) Hw,
//     H0 = Wy^2 X^2 + Wx^2 Y^2,   Hx = -2 X Wx Wy^2,   Hy = -2 Y Wy Wx^2,   Hw = Wx^2 Wy^2
// (degree 4n; with one denominator W divide by W^2: H0 = X^2 + Y^2, Hx = -2 X W, Hy = -2 Y W,
// Hw = W^2, degree 2n). h > 0 wherever the curve is farther than r from P0, and at a pole (a
// real root of a denominator) h is a square, not negative. make_plan stores H0, Hx, Hy, Hw on
// kExtensionPieces pieces of each half; per point h's coefficients on a piece are one affine
// combination, and all of them positive (beyond their rounding) prove the piece clear. Where a
// piece's weights are of one sign its control points' box bounds it too, which clears most
// pieces with four comparisons (make_plan halves the pieces around a pole until it does, for all
// but a narrow one), and a wide one near the curve keeps the boxes of its parts (the convex hull
// of a part's control points lies in that of the piece's, so they bound it more closely, and a
// point farther than the radius from all of them is clear of the piece). Where the curve has one
// denominator, a piece and each part also keep a capsule: the chord between their ends and the
// largest distance of a control point from it. The piece is in the convex hull of its control
// points, which the capsule holds, so a point farther than that reach plus the radius from the
// chord is clear; a box stands off a slanted piece by up to half its width, a capsule by about
// its sagitta, so points beside the extension near the segment's ends clear without the h test.
// A piece far out (towards a pole, or towards infinity on a polynomial curve)
// clears with one: make_plan finds a radius R about the origin it stays outside (H0 - R^2 Hw
// has positive coefficients), and |P - P0| >= R - |P0|. A piece none of these clears is halved
// (de Casteljau) a few times per point. Before any piece, a grid over the segment's surroundings
// (made once a few hundred points of a plan have come this way) clears most points with one comparison: per
// cell, the least over the pieces of what their box (or parts' boxes) and far radius prove for the
// whole cell, and the list of the few pieces that prove less than kExtensionGridListed of the
// diagonal, nearest first: a point its cell does not clear tests those alone.
#include <cstddef>

#include "plan_data.hpp"

namespace bezinv::detail {

// Pieces per half (speed only: more store more coefficients, fewer need more halving), each
// halved at plan time up to kExtensionMaxPlanHalvings times while the quick tests would not clear
// it for points near the curve (extension_pieces says when; kExtensionBoxRatio: a box wider than
// this fraction of the curve's diagonal counts as too wide).
inline constexpr int kExtensionPieces = 8;
inline constexpr int kExtensionMaxPlanHalvings = 5;
inline constexpr double kExtensionBoxRatio = 0.25;
// A piece near the curve whose box is wider than kExtensionPartRatio of the curve's diagonal is
// also halved, its curve alone (no h, so cheaply), at most kExtensionPartHalvings times, into
// parts whose boxes a point must be within the radius of for the piece to need its h test: a
// noisy point near the curve is often inside a wide piece's box but outside every part's. The
// grid takes the parts' boxes too, so it clears more cells.
inline constexpr double kExtensionPartRatio = 0.05;
inline constexpr int kExtensionPartHalvings = 2;
// A capsule's doubles: a x, a y, b x, b y (the chord), reach (extension_capsules).
inline constexpr int kCapsuleStride = 5;
// How deep a piece that is not yet clear may be halved for one point, and how many halvings in
// all: a point near the extension (a noisy point just beyond an end of the segment) needs a deep
// part of one piece only; a point the proof cannot settle goes to the SVD path, which at eight
// halvings deep took 1 point in 5,000 and 4% of the time at degree 15, noise 1e-2. The count
// bounds the work on any point (an extension about as far as the radius all along would
// otherwise halve every part).
inline constexpr int kExtensionMaxHalvings = 14;
inline constexpr int kExtensionMaxSplits = 48;
// The grid that clears most points before any piece is looked at (a point otherwise scans the
// pieces whose far radius it is within, 5-40 of them near the curve, each a box test whose branch
// mispredicts): cells per side, how far beyond the segment's samples it reaches (in diagonals),
// and after how many lanes of a plan have reached the off-curve path it is built (it costs about
// as much as that many scans).
inline constexpr int kExtensionGrid = 32;
inline constexpr double kExtensionGridMargin = 0.25;
inline constexpr std::size_t kExtensionGridAfter = 512;
// Each cell also lists the pieces that could be within this fraction of the curve's diagonal of
// some point of it, nearest first, so that a point its value does not clear tests those pieces
// only (the few whose box or parts reach the cell) instead of scanning 20-40 of them; a radius
// beyond it scans them all.
inline constexpr double kExtensionGridListed = 0.01;

// Fills plan.extension_degree, extension_h, extension_scale, extension_boxes, extension_far2,
// extension_parts, extension_part_begin, extension_capsules and extension_part_capsules
// (degree >= 2).
void extension_pieces(const PlanData& plan, OffCurveData& data);

// Whether no point of the curve with t outside [0, 1] (nor at t = infinity) is within `radius` of
// (u0, v0), normalized coordinates. False when it cannot tell (a piece still undecided after
// kExtensionMaxHalvings halvings or kExtensionMaxSplits in all, a coefficient within its
// rounding) as well as when one is.
// With `grid` (extension_grid), a point whose cell clears it is clear at once: every piece would
// pass its box or far-radius test, so the pieces give the same answer.
bool extension_clear(const PlanData& plan, double u0, double v0, double radius, const ExtensionGrid* grid = nullptr);

// The point's cell of the grid, or kNoCell outside it (or for a NaN, or an empty grid).
inline constexpr std::size_t kNoCell = static_cast<std::size_t>(-1);
inline std::size_t grid_cell(const ExtensionGrid& grid, double u0, double v0) {
  if (grid.clear.empty()) return kNoCell;
  const double gu = (u0 - grid.u) * grid.inverse_cell, gv = (v0 - grid.v) * grid.inverse_cell;
  if (!(gu >= 0 && gu < kExtensionGrid && gv >= 0 && gv < kExtensionGrid)) return kNoCell;
  return static_cast<std::size_t>(gv) * kExtensionGrid + static_cast<std::size_t>(gu);
}

// Whether the point's cell of the grid proves it clear: a point outside the grid, or a NaN, is not.
inline bool grid_clears(const ExtensionGrid& grid, double u0, double v0, double radius) {
  const std::size_t cell = grid_cell(grid, u0, v0);
  return cell != kNoCell && radius < grid.clear[cell];
}

// The plan's grid, counting `lanes` more lanes of the off-curve path on it: null until
// kExtensionGridAfter have been counted, then made (once) and returned; `force` makes it at once.
const ExtensionGrid* extension_grid(const PlanData& plan, std::size_t lanes, bool force = false);

}  // namespace bezinv::detail
