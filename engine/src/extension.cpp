#include "extension.hpp"

#include <algorithm>
#include <array>
#include <bit>
#include <cmath>
#include <limits>
#include <numeric>
#include <span>
#include <utility>
#include <vector>

#include "bernstein_arithmetic.hpp"
#include "bezinv/tolerances.hpp"
#include "isolation.hpp"

namespace bezinv::detail {
namespace {

constexpr double kEpsilon = std::numeric_limits<double>::epsilon();
constexpr int kHalves = 2;
using Span = std::span<const double>;

// The coefficients in s of one half (header): b_j = sum_{k<=j} C(j,k) (-1)^k c_{m-k} for t >= 1
// (half 0), c_k for t <= 0 (half 1); with `bound`, the sums of the absolute values of the terms.
BernsteinPoly on_half(const std::vector<double>& c, int half, bool bound) {
  const int m = static_cast<int>(c.size()) - 1;
  BernsteinPoly out(m + 1, 0.0);
  for (int j = 0; j <= m; ++j) {
    double sum = 0.0, binomial_jk = 1.0;  // C(j, k), exact (j <= kMaxDegree)
    for (int k = 0; k <= j; ++k) {
      const double ck = c[half == 0 ? m - k : k];
      sum += bound ? binomial_jk * std::abs(ck) : ((k % 2) ? -binomial_jk : binomial_jk) * ck;
      binomial_jk = binomial_jk * (j - k) / (k + 1);
    }
    out[j] = sum;
  }
  return out;
}

// The curve's four polynomials (x_num, x_den, y_num, y_den) on one half, or their bounds.
std::array<BernsteinPoly, 4> curve_on_half(const PlanData& plan, int half, bool bound) {
  return {on_half(plan.x_num, half, bound), on_half(plan.x_den, half, bound), on_half(plan.y_num, half, bound),
          on_half(plan.y_den, half, bound)};
}

// H0, Hx, Hy, Hw of the header from the curve's polynomials on a half, or with `bound` (the
// polynomials' bounds) the bounds of their terms.
std::array<BernsteinPoly, 4> clearance_polynomials(const std::array<BernsteinPoly, 4>& curve, bool common_denominator,
                                                   bool bound) {
  const auto& [X, Wx, Y, Wy] = curve;
  if (common_denominator)
    return {combine(product(X, X), product(Y, Y), 1.0), scaled(product(X, Wx), bound ? 2.0 : -2.0),
            scaled(product(Y, Wx), bound ? 2.0 : -2.0), product(Wx, Wx)};
  const BernsteinPoly Wx2 = product(Wx, Wx), Wy2 = product(Wy, Wy);
  return {combine(product(Wy2, product(X, X)), product(Wx2, product(Y, Y)), 1.0),
          scaled(product(Wy2, product(X, Wx)), bound ? 2.0 : -2.0),
          scaled(product(Wx2, product(Y, Wy)), bound ? 2.0 : -2.0), product(Wx2, Wy2)};
}

// Control point k of a piece along one axis (0: x = X / Wx, 1: y = Y / Wy) and the bound of its
// rounding, from the bounds of the coefficients' terms.
struct ControlCoordinate {
  double value, error;
};
ControlCoordinate control_coordinate(Span X, Span Wx, Span Y, Span Wy, const std::array<Span, 4>& bounds, int k,
                                     int axis) {
  const double gamma = kStationarySignUlps * static_cast<double>(X.size()) * kEpsilon;
  const double num = axis == 0 ? X[k] : Y[k], den = axis == 0 ? Wx[k] : Wy[k];
  const double value = num / den;
  return {value, gamma * (bounds[2 * axis][k] + std::abs(value) * bounds[2 * axis + 1][k]) / std::abs(den)};
}

bool one_sign(Span w) {
  return std::all_of(w.begin(), w.end(), [](double v) { return v > 0; }) ||
         std::all_of(w.begin(), w.end(), [](double v) { return v < 0; });
}

// The box of a piece's control points (x from X / Wx, y from Y / Wy), widened by the rounding of
// the coefficients; NaN where a weight is not of the piece's one sign (the box would not hold it).
std::array<double, 4> control_box(Span X, Span Wx, Span Y, Span Wy, const std::array<Span, 4>& bounds) {
  const double nan = std::numeric_limits<double>::quiet_NaN();
  std::array<double, 4> box{std::numeric_limits<double>::infinity(), -std::numeric_limits<double>::infinity(),
                            std::numeric_limits<double>::infinity(), -std::numeric_limits<double>::infinity()};
  const int n = static_cast<int>(X.size()) - 1;
  if (!one_sign(Wx) || !one_sign(Wy)) return {nan, nan, nan, nan};
  for (int k = 0; k <= n; ++k)
    for (int axis = 0; axis < 2; ++axis) {
      const auto [value, error] = control_coordinate(X, Wx, Y, Wy, bounds, k, axis);
      if (!std::isfinite(value) || !std::isfinite(error)) return {nan, nan, nan, nan};
      box[2 * axis] = std::min(box[2 * axis], value - error);
      box[2 * axis + 1] = std::max(box[2 * axis + 1], value + error);
    }
  return box;
}

// The capsule of a piece's control points (header, kCapsuleStride): the chord from the first to
// the last and the largest distance of a control point from it, widened by the points' rounding
// and by that of the distances (a few ulps of the coordinates). All NaN where the curve has two
// denominators (x = X / Wx and y = Y / Wy are then not one convex combination of the control
// points) or a weight is not of the piece's one sign.
std::array<double, kCapsuleStride> control_capsule(Span X, Span W, Span Y, const std::array<Span, 4>& bounds,
                                                   bool common_denominator) {
  const double nan = std::numeric_limits<double>::quiet_NaN();
  if (!common_denominator || !one_sign(W)) return {nan, nan, nan, nan, nan};
  const int n = static_cast<int>(X.size()) - 1;
  const auto x = [&](int k) { return control_coordinate(X, W, Y, W, bounds, k, 0); };
  const auto y = [&](int k) { return control_coordinate(X, W, Y, W, bounds, k, 1); };
  const double ax = x(0).value, ay = y(0).value, bx = x(n).value, by = y(n).value;
  double reach = 0.0, size = 0.0;
  for (int k = 0; k <= n; ++k) {
    const auto [qx, ex] = x(k);
    const auto [qy, ey] = y(k);
    // Squares, not hypot (a tenth of the plan's off-curve data went to it): a coordinate large
    // enough to overflow them makes the reach infinite, and the capsule NaN below.
    const auto [distance2, scale] = chord_distance2(ax, ay, bx, by, qx, qy);
    reach = std::max(reach, std::sqrt(distance2) + std::sqrt(ex * ex + ey * ey));
    size = std::max(size, scale);
  }
  reach = reach * (1 + 1e-12) + 16 * kEpsilon * size;
  if (!std::isfinite(reach) || !std::isfinite(size)) return {nan, nan, nan, nan, nan};
  return {ax, ay, bx, by, reach};
}

// Whether (u0, v0) is farther than `radius` from every point within the capsule's reach of its
// chord (false for a NaN capsule); the slack on the reach covers chord_distance2's few ulps of
// the coordinates and the rounding of the comparison.
bool capsule_clear(const double* c, double u0, double v0, double radius) {
  const auto [distance2, scale] = chord_distance2(c[0], c[1], c[2], c[3], u0, v0);
  const double reach = (c[4] + radius) * (1 + 8 * kEpsilon) + 8 * kEpsilon * scale;
  return distance2 > reach * reach;
}

// The square of a radius R about the origin that the piece stays outside: h at P0 = 0 and r = R,
// H0 - R^2 Hw, has all its coefficients positive beyond their rounding, gamma (scale0 + R^2
// scale_w) (0 where none is found). Half the largest R^2 that allows, so the check below has
// room: coefficient k allows R^2 < (H0_k - gamma scale0) / (Hw_k + gamma scale_w). The rounding
// term belongs in the solve: far along the extension of a polynomial curve (t -> inf) Hw is
// about 0 beside its bound, and R^2 from H0 / Hw alone would always fail the check.
double far_radius2(Span H0, Span Hw, double scale0, double scale_w) {
  const double gamma = kStationarySignUlps * static_cast<double>(H0.size()) * kEpsilon;
  double r2 = std::numeric_limits<double>::infinity();
  for (std::size_t k = 0; k < H0.size(); ++k) {
    const double room = H0[k] - gamma * scale0, per_r2 = Hw[k] + gamma * scale_w;
    if (!(room > 0)) return 0.0;
    if (per_r2 > 0) r2 = std::min(r2, room / per_r2);
  }
  r2 = 0.5 * r2;
  if (!std::isfinite(r2) || !(r2 > 0)) return 0.0;
  for (std::size_t k = 0; k < H0.size(); ++k)
    if (!(H0[k] - r2 * Hw[k] > gamma * (scale0 + r2 * scale_w))) return 0.0;
  return r2;
}

// kExtensionPieces = 2^kBaseLevels: the pieces every half starts with come from halving it.
static_assert(std::has_single_bit(static_cast<unsigned>(kExtensionPieces)));
constexpr int kBaseLevels = std::countr_zero(static_cast<unsigned>(kExtensionPieces));

// A piece of a half, every polynomial of it as a polynomial of [0, 1] again, in one block: the
// curve's four (X, Wx, Y, Wy; degree n) and their bounds, then h's four (H0, Hx, Hy, Hw; degree
// m) and their bounds.
struct Piece {
  int n = 0, m = 0;
  std::vector<double> c;  // 8 (n + 1), then 8 (m + 1)

  Piece(int n_, int m_) : n(n_), m(m_), c(8 * static_cast<std::size_t>(n + 1) + 8 * static_cast<std::size_t>(m + 1)) {}
  Span curve(int which) const { return {c.data() + which * (n + 1), static_cast<std::size_t>(n + 1)}; }  // 4..7: bounds
  Span h(int which) const { return {c.data() + 8 * (n + 1) + which * (m + 1), static_cast<std::size_t>(m + 1)}; }
  double* curve_data(int which) { return c.data() + which * (n + 1); }
  double* h_data(int which) { return c.data() + 8 * (n + 1) + which * (m + 1); }
};

// The two halves of a piece, each polynomial halved by one de Casteljau triangle at 1/2. Halving
// rounds each coefficient once per level on the bound of its terms, which the piece's halved
// bound polynomials carry: kBaseLevels + kExtensionMaxPlanHalvings levels stay well inside the
// kStationarySignUlps (m + 1) ulps the sign tests allow.
std::pair<Piece, Piece> halves(const Piece& piece) {
  std::pair<Piece, Piece> out{Piece(piece.n, piece.m), Piece(piece.n, piece.m)};
  for (int which = 0; which < 8; ++which) {
    split(piece.curve(which).data(), piece.n, 0.5, out.first.curve_data(which), out.second.curve_data(which));
    split(piece.h(which).data(), piece.m, 0.5, out.first.h_data(which), out.second.h_data(which));
  }
  return out;
}

// The box {x min, x max, y min, y max} of the segment's samples (plan.nearest_samples): where the
// points near the curve are.
std::array<double, 4> samples_box(const PlanData& plan) {
  constexpr double inf = std::numeric_limits<double>::infinity();
  std::array<double, 4> box{inf, -inf, inf, -inf};
  const std::vector<double>& samples = plan.nearest_samples;
  for (std::size_t k = 0; k + 1 < samples.size(); k += 2)
    for (int axis = 0; axis < 2; ++axis) {
      box[2 * axis] = std::min(box[2 * axis], samples[k + axis]);
      box[2 * axis + 1] = std::max(box[2 * axis + 1], samples[k + axis]);
    }
  return box;
}

// The diagonal of a box {x min, x max, y min, y max} (NaN for a NaN box).
double box_diagonal(const std::array<double, 4>& box) { return std::hypot(box[1] - box[0], box[3] - box[2]); }

// A piece's curve alone: X, Wx, Y, Wy and their bounds (Piece's first 8 (n + 1) coefficients),
// for the boxes of its parts; on the stack, halved as halves() halves it.
constexpr std::size_t kCurveStride = kMaxBernsteinDegree + 1;
using CurveOnly = std::array<double, 8 * kCurveStride>;

void curve_halves(const CurveOnly& curve, int n, CurveOnly& left, CurveOnly& right) {
  for (std::size_t which = 0; which < 8; ++which)
    split(curve.data() + which * kCurveStride, n, 0.5, left.data() + which * kCurveStride,
          right.data() + which * kCurveStride);
}

// Polynomial `which` of a CurveOnly (X, Wx, Y, Wy, then their bounds), degree n.
Span curve_span(const CurveOnly& curve, int n, std::size_t which) {
  return Span(curve.data() + which * kCurveStride, static_cast<std::size_t>(n + 1));
}

std::array<double, 4> curve_box(const CurveOnly& curve, int n) {
  const auto span = [&](std::size_t which) { return curve_span(curve, n, which); };
  return control_box(span(0), span(1), span(2), span(3), {span(4), span(5), span(6), span(7)});
}

std::array<double, kCapsuleStride> curve_capsule(const CurveOnly& curve, int n, bool common_denominator) {
  const auto span = [&](std::size_t which) { return curve_span(curve, n, which); };
  return control_capsule(span(0), span(1), span(2), {span(4), span(5), span(6), span(7)}, common_denominator);
}

// Whether (u0, v0) is farther than the radius from every part of the piece, by the part's box or
// its capsule (false where the piece has no parts).
bool parts_clear(const OffCurveData& data, int piece, double u0, double v0, double radius) {
  const std::uint32_t begin = data.extension_part_begin[piece], end = data.extension_part_begin[piece + 1];
  if (begin == end) return false;
  for (std::uint32_t k = begin; k < end; ++k)
    if (!(box_distance2(data.extension_parts.data() + 4 * static_cast<std::size_t>(k), u0, v0) > radius * radius) &&
        !capsule_clear(data.extension_part_capsules.data() + kCapsuleStride * static_cast<std::size_t>(k), u0, v0, radius))
      return false;
  return true;
}

// The pieces by their far radius, nearest the origin first (NaN, no radius known, before all):
// a point then tests only the pieces up to the first whose radius it lies within, where it tested
// the far radius of every piece (30-40 of them, nearly all cleared by it). The clearance is every
// piece's, so the order changes no answer.
void order_by_far_radius(OffCurveData& data) {
  const int m = data.extension_degree;
  const std::size_t pieces = data.extension_far2.size();
  std::vector<std::size_t> order(pieces);
  std::iota(order.begin(), order.end(), std::size_t{0});
  auto key = [&](std::size_t i) {
    const double far2 = data.extension_far2[i];
    return std::isnan(far2) ? -std::numeric_limits<double>::infinity() : far2;
  };
  std::stable_sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) { return key(a) < key(b); });
  const std::size_t h_size = 4 * static_cast<std::size_t>(m + 1);
  std::vector<double> h(data.extension_h.size()), scale(data.extension_scale.size()),
      boxes(data.extension_boxes.size()), far2(pieces), parts, capsules(data.extension_capsules.size()), part_capsules,
      intervals(data.extension_intervals.size());
  std::vector<std::uint32_t> part_begin{0};
  parts.reserve(data.extension_parts.size());
  for (std::size_t k = 0; k < pieces; ++k) {
    const std::size_t i = order[k];
    std::copy_n(data.extension_h.begin() + i * h_size, h_size, h.begin() + k * h_size);
    std::copy_n(data.extension_scale.begin() + 4 * i, 4, scale.begin() + 4 * k);
    std::copy_n(data.extension_boxes.begin() + 4 * i, 4, boxes.begin() + 4 * k);
    std::copy_n(data.extension_capsules.begin() + kCapsuleStride * i, kCapsuleStride, capsules.begin() + kCapsuleStride * k);
    std::copy_n(data.extension_intervals.begin() + 3 * i, 3, intervals.begin() + 3 * k);
    far2[k] = data.extension_far2[i];
    parts.insert(parts.end(), data.extension_parts.begin() + 4 * data.extension_part_begin[i],
                 data.extension_parts.begin() + 4 * data.extension_part_begin[i + 1]);
    part_capsules.insert(part_capsules.end(),
                         data.extension_part_capsules.begin() + kCapsuleStride * data.extension_part_begin[i],
                         data.extension_part_capsules.begin() + kCapsuleStride * data.extension_part_begin[i + 1]);
    part_begin.push_back(static_cast<std::uint32_t>(parts.size() / 4));
  }
  data.extension_h = std::move(h);
  data.extension_scale = std::move(scale);
  data.extension_boxes = std::move(boxes);
  data.extension_far2 = std::move(far2);
  data.extension_parts = std::move(parts);
  data.extension_capsules = std::move(capsules);
  data.extension_part_capsules = std::move(part_capsules);
  data.extension_intervals = std::move(intervals);
  data.extension_part_begin = std::move(part_begin);
}

// The grid of ExtensionGrid (plan_data.hpp). A piece's box and its far radius R each bound
// the distance from every point of a cell to the piece: by the distance between the cell and the
// box, and by R less the cell's corner farthest from the origin (|P - P0| >= |P| - |P0|). The cell
// keeps the least over the pieces of the larger of the two, so that a point of it whose radius is
// below that value would pass, piece by piece, the very tests extension_clear makes. In squares,
// so that the pieces' loop takes no square root: it runs once per plan, pieces x cells.
void make_extension_grid(const PlanData& plan, const OffCurveData& data, ExtensionGrid& grid) {
  constexpr int G = kExtensionGrid;
  constexpr double inf = std::numeric_limits<double>::infinity();
  const std::array<double, 4> samples = samples_box(plan);
  const double side =
      std::max(samples[1] - samples[0], samples[3] - samples[2]) + 2 * kExtensionGridMargin * plan.normalized_diagonal;
  if (!std::isfinite(side) || !(side > 0)) return;
  const double cell = side / G;
  grid.u = 0.5 * (samples[0] + samples[1]) - 0.5 * side;
  grid.v = 0.5 * (samples[2] + samples[3]) - 0.5 * side;
  grid.inverse_cell = 1.0 / cell;
  // The cells' edges, each cell widened by a millionth of its side: a point that the index's
  // arithmetic rounds into the next cell is still inside the one whose value it reads.
  const double pad = 1e-6 * cell;
  std::array<double, G> u0, u1, v0, v1;
  for (int i = 0; i < G; ++i) {
    u0[i] = grid.u + i * cell - pad, u1[i] = grid.u + (i + 1) * cell + pad;
    v0[i] = grid.v + i * cell - pad, v1[i] = grid.v + (i + 1) * cell + pad;
  }
  std::array<double, G * G> corner;  // the distance of each cell's farthest corner from the origin
  for (int j = 0; j < G; ++j)
    for (int i = 0; i < G; ++i) {
      const double x = std::max(std::abs(u0[i]), std::abs(u1[i])), y = std::max(std::abs(v0[j]), std::abs(v1[j]));
      corner[j * G + i] = std::sqrt(x * x + y * y);
    }
  std::vector<double> clear2(static_cast<std::size_t>(G) * G, inf);
  // The cells' lists (ExtensionGrid): (cell, bound squared, piece) for every bound below
  // listed_below, sorted by cell and bound below.
  grid.listed_below = kExtensionGridListed * plan.normalized_diagonal;
  const double listed2 = grid.listed_below * grid.listed_below;
  struct Listed {
    std::uint32_t cell;
    double bound2;
    std::uint32_t piece;
  };
  std::vector<Listed> listed;
  const std::size_t pieces = data.extension_far2.size();
  std::array<double, G> dx2, dy2;
  constexpr int kMostParts = 1 << kExtensionPartHalvings;
  std::array<std::array<double, G>, kMostParts> part_dx2, part_dy2;
  // The squares of the distances from each column's (or row's) cells to a box, 0 for a NaN box.
  const auto distances2 = [&](const double* box, std::array<double, G>& x2, std::array<double, G>& y2) {
    const bool boxed = box[0] == box[0];  // NaN: the box does not hold the piece
    for (int i = 0; i < G; ++i) {
      const double dx = boxed ? std::max({box[0] - u1[i], u0[i] - box[1], 0.0}) : 0.0;
      const double dy = boxed ? std::max({box[2] - v1[i], v0[i] - box[3], 0.0}) : 0.0;
      x2[i] = dx * dx, y2[i] = dy * dy;
    }
  };
  for (std::size_t piece = 0; piece < pieces; ++piece) {
    const double far2 = data.extension_far2[piece], far = far2 > 0 ? std::sqrt(far2) : 0.0;  // NaN: none
    distances2(data.extension_boxes.data() + 4 * piece, dx2, dy2);
    const std::uint32_t first_part = data.extension_part_begin[piece];
    const int parts = static_cast<int>(data.extension_part_begin[piece + 1] - first_part);
    for (int k = 0; k < parts; ++k)
      distances2(data.extension_parts.data() + 4 * static_cast<std::size_t>(first_part + k), part_dx2[k], part_dy2[k]);
    for (int j = 0; j < G; ++j)
      for (int i = 0; i < G; ++i) {
        const double by_radius = far - corner[j * G + i], by_radius2 = by_radius > 0 ? by_radius * by_radius : 0.0;
        double by_box2 = dx2[i] + dy2[j];
        if (parts > 0) {  // the nearest part, where it is farther than the box
          double by_parts2 = std::numeric_limits<double>::infinity();
          for (int k = 0; k < parts; ++k) by_parts2 = std::min(by_parts2, part_dx2[k][i] + part_dy2[k][j]);
          by_box2 = std::max(by_box2, by_parts2);
        }
        const double bound2 = by_box2 > by_radius2 ? by_box2 : by_radius2;
        double& value = clear2[static_cast<std::size_t>(j) * G + i];
        value = bound2 < value ? bound2 : value;
        if (bound2 < listed2)
          listed.push_back({static_cast<std::uint32_t>(j * G + i), bound2, static_cast<std::uint32_t>(piece)});
      }
  }
  std::sort(listed.begin(), listed.end(), [](const Listed& a, const Listed& b) {
    return a.cell != b.cell ? a.cell < b.cell : a.bound2 < b.bound2;
  });
  grid.near_begin.assign(static_cast<std::size_t>(G) * G + 1, 0);
  grid.near_piece.resize(listed.size());
  grid.near_bound.resize(listed.size());
  for (std::size_t k = 0; k < listed.size(); ++k) {
    ++grid.near_begin[listed[k].cell + 1];
    grid.near_piece[k] = listed[k].piece;
    grid.near_bound[k] = std::sqrt(listed[k].bound2) * (1.0 - 1e-9);  // as the cells' values, below
  }
  std::partial_sum(grid.near_begin.begin(), grid.near_begin.end(), grid.near_begin.begin());
  // Those sums, products and square roots round: a part in 1e9 below them is safely below the
  // exact values.
  for (double& value : clear2) value = std::sqrt(value) * (1.0 - 1e-9);
  grid.clear = std::move(clear2);
}

}  // namespace

void extension_pieces(const PlanData& plan, OffCurveData& data) {
  data.extension_degree = 0;
  data.extension_h.clear();
  data.extension_scale.clear();
  data.extension_boxes.clear();
  data.extension_far2.clear();
  data.extension_parts.clear();
  data.extension_part_begin.assign(1, 0);
  data.extension_capsules.clear();
  data.extension_part_capsules.clear();
  data.extension_intervals.clear();
  if (plan.degree < 2) return;
  const int m = (plan.common_denominator ? 2 : 4) * plan.degree;
  data.extension_degree = m;
  // Where points near the curve are: the box of the segment's samples, widened by
  // kExtensionPartRatio of the curve (the parts are for the pieces whose box reaches it).
  std::array<double, 4> near_box = samples_box(plan);
  for (int side = 0; side < 4; ++side) near_box[side] += (side % 2 ? 1 : -1) * kExtensionPartRatio * plan.normalized_diagonal;
  for (int half = 0; half < kHalves; ++half) {
    const std::array<BernsteinPoly, 4> curve = curve_on_half(plan, half, false),
                                       curve_bound = curve_on_half(plan, half, true);
    const std::array<BernsteinPoly, 4> h = clearance_polynomials(curve, plan.common_denominator, false),
                                       h_bound = clearance_polynomials(curve_bound, plan.common_denominator, true);
    Piece whole(plan.degree, m);
    for (int which = 0; which < 4; ++which) {
      std::copy(curve[which].begin(), curve[which].end(), whole.curve_data(which));
      std::copy(curve_bound[which].begin(), curve_bound[which].end(), whole.curve_data(4 + which));
      std::copy(h[which].begin(), h[which].end(), whole.h_data(which));
      std::copy(h_bound[which].begin(), h_bound[which].end(), whole.h_data(4 + which));
    }
    // The half cut into kExtensionPieces pieces (kBaseLevels halvings), each piece halved again
    // (up to kExtensionMaxPlanHalvings times) while neither quick test would clear it for points
    // near the curve: its far radius is below the curve's size, and its box does not hold it (a
    // weight of the other sign: a pole nearby) or is wider than kExtensionBoxRatio of the curve.
    // Points near the curve then pay the h test only on a few narrow pieces. Depth first, left
    // half first (then ordered by far radius, below).
    const auto add = [&](auto&& self, const Piece& piece, int level, double a, double b) -> void {
      if (level < kBaseLevels) {
        const auto [left, right] = halves(piece);
        self(self, left, level + 1, a, 0.5 * (a + b));
        self(self, right, level + 1, 0.5 * (a + b), b);
        return;
      }
      const std::array<double, 4> box =
          control_box(piece.curve(0), piece.curve(1), piece.curve(2), piece.curve(3),
                      {piece.curve(4), piece.curve(5), piece.curve(6), piece.curve(7)});
      std::array<double, 4> scale;
      for (int which = 0; which < 4; ++which) scale[which] = max_abs(piece.h(4 + which));
      const double far2 = far_radius2(piece.h(0), piece.h(3), scale[0], scale[3]);
      const double size = plan.normalized_diagonal;
      const bool wide = !(box_diagonal(box) <= kExtensionBoxRatio * size);  // NaN: wide
      if (far2 < size * size && wide && level - kBaseLevels < kExtensionMaxPlanHalvings) {
        const auto [left, right] = halves(piece);
        self(self, left, level + 1, a, 0.5 * (a + b));
        self(self, right, level + 1, 0.5 * (a + b), b);
        return;
      }
      data.extension_intervals.insert(data.extension_intervals.end(), {static_cast<double>(half), a, b});
      for (int which = 0; which < 4; ++which) {
        data.extension_h.insert(data.extension_h.end(), piece.h(which).begin(), piece.h(which).end());
        data.extension_scale.push_back(scale[which]);
      }
      data.extension_boxes.insert(data.extension_boxes.end(), box.begin(), box.end());
      const std::array<double, kCapsuleStride> capsule =
          control_capsule(piece.curve(0), piece.curve(1), piece.curve(2),
                          {piece.curve(4), piece.curve(5), piece.curve(6), piece.curve(7)}, plan.common_denominator);
      data.extension_capsules.insert(data.extension_capsules.end(), capsule.begin(), capsule.end());
      data.extension_far2.push_back(far2);
      // Its parts (header): where its box reaches the segment's surroundings and is wider than
      // kExtensionPartRatio of the curve, halved, the curve alone, until each is narrower or
      // kExtensionPartHalvings deep; none where a part's box does not hold it.
      const std::size_t parts_before = data.extension_parts.size();
      const auto narrow = [&](const std::array<double, 4>& b) {
        return box_diagonal(b) <= kExtensionPartRatio * size;  // NaN: not narrow
      };
      const bool reaches = box[0] <= near_box[1] && box[1] >= near_box[0] && box[2] <= near_box[3] && box[3] >= near_box[2];
      if (reaches && far2 < size * size && !narrow(box)) {  // reaches: false for a NaN box
        bool held = true;
        const auto add_part = [&](auto&& self, const CurveOnly& curve, int halvings) -> void {
          if (!held) return;
          const std::array<double, 4> part = curve_box(curve, plan.degree);
          if (!(part[0] == part[0])) {
            held = false;
            return;
          }
          if (halvings == kExtensionPartHalvings || narrow(part)) {
            data.extension_parts.insert(data.extension_parts.end(), part.begin(), part.end());
            const std::array<double, kCapsuleStride> capsule = curve_capsule(curve, plan.degree, plan.common_denominator);
            data.extension_part_capsules.insert(data.extension_part_capsules.end(), capsule.begin(), capsule.end());
            return;
          }
          CurveOnly left, right;
          curve_halves(curve, plan.degree, left, right);
          self(self, left, halvings + 1);
          self(self, right, halvings + 1);
        };
        CurveOnly whole_curve;
        for (int which = 0; which < 8; ++which)
          std::copy(piece.curve(which).begin(), piece.curve(which).end(), whole_curve.data() + which * kCurveStride);
        add_part(add_part, whole_curve, 0);  // the piece itself, not narrow: halved at once
        if (!held) {
          data.extension_parts.resize(parts_before);
          data.extension_part_capsules.resize(parts_before / 4 * kCapsuleStride);
        }
      }
      data.extension_part_begin.push_back(static_cast<std::uint32_t>(data.extension_parts.size() / 4));
    };
    add(add, whole, 0, 0.0, 1.0);
  }
  order_by_far_radius(data);
}

const ExtensionGrid* extension_grid(const PlanData& plan, std::size_t lanes, bool force) {
  if (const ExtensionGrid* grid = plan.extension_grid.if_made()) return grid;
  if (!force && plan.extension_lanes.add(lanes) < kExtensionGridAfter) return nullptr;
  const OffCurveData& data = off_curve_data(plan);
  return &plan.extension_grid.get([&](ExtensionGrid& grid) { make_extension_grid(plan, data, grid); });
}

namespace {

// A point and radius as every piece's tests need them: with c = |P0|^2 - r^2 the piece's h is
// H0 + u0 Hx + v0 Hy + c Hw (header), and c_bound = |P0|^2 + r^2 bounds c's part of its rounding.
struct Clearance {
  double u0, v0, radius, radius2, c, c_bound, gamma;
  Clearance(int m, double u0_, double v0_, double radius_)
      : u0(u0_), v0(v0_), radius(radius_), radius2(radius_ * radius_), c(u0_ * u0_ + v0_ * v0_ - radius2),
        c_bound(u0_ * u0_ + v0_ * v0_ + radius2), gamma(kStationarySignUlps * (m + 1) * kEpsilon) {}
};

// Whether the piece is clear of the point: its box, its capsule or its parts, else its h with
// every coefficient positive beyond its rounding, the piece halved (de Casteljau) up to
// kExtensionMaxHalvings deep (kExtensionMaxSplits halvings in all) until each part says.
bool piece_clear(const OffCurveData& data, int piece, const Clearance& q) {
  const int m = data.extension_degree;
  const double* box = data.extension_boxes.data() + piece * 4;
  if (box[0] == box[0] && box_distance2(box, q.u0, q.v0) > q.radius2) return true;  // not NaN: the box holds the piece
  if (capsule_clear(data.extension_capsules.data() + kCapsuleStride * static_cast<std::size_t>(piece), q.u0, q.v0, q.radius))
    return true;
  if (parts_clear(data, piece, q.u0, q.v0, q.radius)) return true;
  struct Interval {
    int halvings;
    std::array<double, kMaxBernsteinDegree + 1> h;
  };
  std::array<Interval, kExtensionMaxHalvings + 2> stack;
  const double* H = data.extension_h.data() + static_cast<std::size_t>(piece) * 4 * (m + 1);
  const double* scale = data.extension_scale.data() + piece * 4;
  const double slack =
      q.gamma * (scale[0] + std::abs(q.u0) * scale[1] + std::abs(q.v0) * scale[2] + q.c_bound * scale[3]);
  int waiting = 0, splits = 0;
  Interval& first = stack[waiting++];
  first.halvings = 0;
  for (int k = 0; k <= m; ++k)
    first.h[k] = H[k] + q.u0 * H[m + 1 + k] + q.v0 * H[2 * (m + 1) + k] + q.c * H[3 * (m + 1) + k];
  while (waiting > 0) {
    Interval& here = stack[--waiting];
    // The end coefficients are h at the ends: a negative one is a point of the curve within r.
    if (!(here.h[0] > -slack) || !(here.h[m] > -slack)) return false;
    bool positive = true;
    for (int k = 0; k <= m && positive; ++k) positive = here.h[k] > slack;
    if (positive) continue;
    if (here.halvings == kExtensionMaxHalvings || ++splits > kExtensionMaxSplits) return false;
    // The halves in this slot and the next; the slack stays the piece's (de Casteljau's convex
    // combinations do not enlarge the terms).
    const int halvings = here.halvings + 1;
    Interval& left = stack[waiting + 1];
    split(here.h.data(), m, 0.5, left.h.data(), here.h.data());
    left.halvings = here.halvings = halvings;
    waiting += 2;
  }
  return true;
}

}  // namespace

bool extension_clear(const PlanData& plan, double u0, double v0, double radius, const ExtensionGrid* grid) {
  const OffCurveData& data = off_curve_data(plan);
  const int m = data.extension_degree;
  if (m == 0 || !std::isfinite(u0) || !std::isfinite(v0) || !(radius >= 0)) return false;
  const std::size_t cell = grid ? grid_cell(*grid, u0, v0) : kNoCell;
  if (cell != kNoCell && radius < grid->clear[cell]) return true;  // most points: nothing more to make
  const Clearance q(m, u0, v0, radius);
  if (cell != kNoCell) {
    // The cell's list holds every piece whose bound for the cell is below listed_below, nearest
    // first: those beyond the radius pass their quick tests, the others are tested.
    if (radius < grid->listed_below) {
      for (std::uint32_t k = grid->near_begin[cell]; k < grid->near_begin[cell + 1]; ++k) {
        if (radius < grid->near_bound[k]) break;
        if (!piece_clear(data, static_cast<int>(grid->near_piece[k]), q)) return false;
      }
      return true;
    }
  }
  const int pieces = static_cast<int>(data.extension_boxes.size() / 4);
  // |P(t) - P0| >= |P(t)| - |P0| > radius wherever |P(t)| > |P0| + radius.
  const double beyond = std::sqrt(u0 * u0 + v0 * v0) + radius, beyond2 = beyond * beyond;
  for (int piece = 0; piece < pieces; ++piece) {
    if (beyond2 < data.extension_far2[piece]) break;  // and every piece after it (order_by_far_radius)
    if (!piece_clear(data, piece, q)) return false;
  }
  return true;
}

}  // namespace bezinv::detail
