#include "isolation.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <span>
#include <vector>

#include "bezinv/bernstein.hpp"
#include "bezinv/tolerances.hpp"

namespace bezinv::detail {
namespace {

using Coefficients = std::array<double, kMaxDegree + 1>;

// The Bernstein coefficients of c (degree n) on [a, b] (as a curve of its own on [0, 1]) into
// piece[0..n]: de Casteljau at a keeps the right part, then at (b - a) / (1 - a) the left part of
// that. (Only the n + 1 entries are touched: make_plan runs this 4 K times, and clearing
// kMaxDegree-sized arrays each time was a sixth of make_plan at degree 3.)
void split(std::span<const double> c, double a, double b, Coefficients& piece) {
  const int n = static_cast<int>(c.size()) - 1;
  Coefficients f, right;
  std::copy(c.begin(), c.end(), f.begin());
  for (int k = 0; k <= n; ++k) {  // after k rounds, f[n - k] is the right part's coefficient n - k
    right[n - k] = f[n - k];
    for (int i = 0; i < n - k; ++i) f[i] = (1 - a) * f[i] + a * f[i + 1];
  }
  const double s = a < 1 ? (b - a) / (1 - a) : 1.0;
  std::copy_n(right.begin(), n + 1, f.begin());
  for (int k = 0; k <= n; ++k) {  // after k rounds, f[0] is the left part's coefficient k
    piece[k] = f[0];
    for (int i = 0; i < n - k; ++i) f[i] = (1 - s) * f[i] + s * f[i + 1];
  }
}

// The Bernstein coefficients (degree p + q) of the product of f (degree p) and g (degree q):
// B^p_i B^q_j = C(p,i) C(q,j) / C(p+q,i+j) B^{p+q}_{i+j}. The weights C(p,i) C(q,j) / C(p+q,i+j)
// are tabulated once per plan: computed per product, their binomial() calls and divisions were
// most of make_plan (perf: binomial 56%), and each piece takes four products per coordinate.
struct ProductWeights {
  int p, q;
  std::array<double, (kMaxDegree + 1) * (kMaxDegree + 1)> w;
  ProductWeights(int p_, int q_) : p(p_), q(q_) {
    for (int i = 0; i <= p; ++i)
      for (int j = 0; j <= q; ++j) w[i * (q + 1) + j] = binomial(p, i) * binomial(q, j) / binomial(p + q, i + j);
  }
};

void multiply_add(const double* f, const double* g, const ProductWeights& weights, double sign, double* out) {
  const int p = weights.p, q = weights.q;
  for (int i = 0; i <= p; ++i)
    for (int j = 0; j <= q; ++j) out[i + j] += sign * weights.w[i * (q + 1) + j] * f[i] * g[j];
}

// The four products coordinate() takes at degree n: F'W and FW' (degree 2n - 1), F''W and FW''.
struct CoordinateProducts {
  ProductWeights first_by_value, value_by_first, second_by_value, value_by_second;
  explicit CoordinateProducts(int n)
      : first_by_value(n - 1, n), value_by_first(n, n - 1), second_by_value(n - 2, n), value_by_second(n, n - 2) {}
};

// One coordinate f = F / W of a piece (Bernstein coefficients of F and W, degree n, W > 0):
// the coefficients of H = F'W - FW' (degree 2n - 1) and the bounds that |f''| needs.
// (Sized for kMaxDegree, filled to the degree's: 2n coefficients of H.)
struct Coordinate {
  std::array<double, 2 * kMaxDegree> h;
  double w_min, w_max;
  double bend;  // |f''| <= (|G| W + 2 |W'| |H|) / W^3, G = H' = F''W - FW'' (degree 2n - 2)
};
Coordinate coordinate(const Coefficients& f, const Coefficients& w, int n, const CoordinateProducts& products) {
  Coordinate c;
  std::array<double, kMaxDegree> df, dw, ddf, ddw;
  for (int i = 0; i < n; ++i) df[i] = n * (f[i + 1] - f[i]), dw[i] = n * (w[i + 1] - w[i]);
  for (int i = 0; i + 1 < n; ++i) ddf[i] = (n - 1) * (df[i + 1] - df[i]), ddw[i] = (n - 1) * (dw[i + 1] - dw[i]);
  std::fill_n(c.h.begin(), 2 * n, 0.0);
  multiply_add(df.data(), w.data(), products.first_by_value, 1.0, c.h.data());
  multiply_add(f.data(), dw.data(), products.value_by_first, -1.0, c.h.data());
  std::array<double, 2 * kMaxDegree> g;
  std::fill_n(g.begin(), 2 * n - 1, 0.0);
  multiply_add(ddf.data(), w.data(), products.second_by_value, 1.0, g.data());
  multiply_add(f.data(), ddw.data(), products.value_by_second, -1.0, g.data());
  // Each polynomial is bounded by its largest Bernstein coefficient, W from below by its smallest.
  double h_max = 0, g_max = 0, dw_max = 0;
  for (int k = 0; k <= 2 * n - 1; ++k) h_max = std::max(h_max, std::abs(c.h[k]));
  for (int k = 0; k <= 2 * n - 2; ++k) g_max = std::max(g_max, std::abs(g[k]));
  for (int i = 0; i < n; ++i) dw_max = std::max(dw_max, std::abs(dw[i]));
  c.w_min = *std::min_element(w.begin(), w.begin() + n + 1);
  c.w_max = *std::max_element(w.begin(), w.begin() + n + 1);
  c.bend = (g_max * c.w_max + 2 * dw_max * h_max) / (c.w_min * c.w_min * c.w_min);
  return c;
}

// What the bounds around a piece need of it: its ends, and the generators of its tangent cone.
// (Filled in place by piece(), to the degree's size: make_plan keeps three.)
struct Piece {
  bool positive;               // every weight of the piece > 0
  double x0, y0, x1, y1;       // P at its ends
  // P' = (Hx / Wx^2, Hy / Wy^2) = (Hx, r Hy) / Wx^2 with r = Wx^2 / Wy^2 in [r_lo, r_hi] (r = 1 for
  // a common denominator), and (Hx, r Hy) = sum_k B_k (hx_k, r hy_k): every tangent lies in the
  // cone of the generators (hx_k, r hy_k), r = r_lo or r_hi (2 of them per k, 4n in all).
  int generators;
  std::array<double, 8 * kMaxDegree> gx, gy, length;
  double wx_max;     // for the speed: P' . c >= min_k generator_k . c / max Wx^2
  double bend;       // a bound of |P''| on the piece
};

// Piece j of K of the normalized curve into p: its box (written into the plan's) and what the
// bounds around it need.
void piece(PlanData& plan, int j, int K, const CoordinateProducts& products, Piece& p) {
  const int n = plan.degree;
  const double inf = std::numeric_limits<double>::infinity();
  const double a = static_cast<double>(j) / K, b = static_cast<double>(j + 1) / K;  // exact
  Coefficients x, y, wx, wy;
  split(plan.x_num, a, b, x);
  split(plan.y_num, a, b, y);
  split(plan.x_den, a, b, wx);
  if (plan.common_denominator)
    wy = wx;
  else
    split(plan.y_den, a, b, wy);
  p.positive = true;
  p.generators = 0;
  double x_min = inf, x_max = -inf, y_min = inf, y_max = -inf;
  for (int i = 0; i <= n; ++i) {
    // x = X / Wx is a convex combination of the x[i] / wx[i] (weights wx[i] B_i / Wx), and so is
    // y of its own ratios: the box holds the piece for separate denominators too.
    if (!(wx[i] > 0 && wy[i] > 0)) p.positive = false;
    const double xi = x[i] / wx[i], yi = y[i] / wy[i];
    x_min = std::min(x_min, xi); x_max = std::max(x_max, xi);
    y_min = std::min(y_min, yi); y_max = std::max(y_max, yi);
  }
  // A piece with a weight that is not positive keeps the whole plane (isolation_pieces).
  if (!p.positive || !std::isfinite(x_min + x_max + y_min + y_max)) {
    p.positive = false;
    return;
  }
  // Room for the rounding of the split and the divisions (~n eps of the coordinates).
  const double size = std::max({std::abs(x_min), std::abs(x_max), std::abs(y_min), std::abs(y_max)});
  const double margin = kIsolationMargin * (1.0 + size);
  double* const box = plan.isolation_boxes.data();  // x centres, x half-widths, y centres, y half-widths
  box[j] = 0.5 * (x_min + x_max);
  box[K + j] = 0.5 * (x_max - x_min) + margin;
  box[2 * K + j] = 0.5 * (y_min + y_max);
  box[3 * K + j] = 0.5 * (y_max - y_min) + margin;
  // With one denominator the piece is in the convex hull of its control points, and so in the
  // capsule about the chord between its ends that reaches every control point (the same margin
  // for their rounding). Separate denominators keep none (isolation_capsules: NaN reach), nor
  // does a plan of fewer than kIsolationCapsuleMinPieces pieces.
  if (plan.common_denominator && K >= kIsolationCapsuleMinPieces) {
    const double ax = x[0] / wx[0], ay = y[0] / wy[0], bx = x[n] / wx[n], by = y[n] / wy[n];
    double reach2 = 0.0;
    for (int i = 0; i <= n; ++i)
      reach2 = std::max(reach2, chord_distance2(ax, ay, bx, by, x[i] / wx[i], y[i] / wy[i]).distance2);
    double* const capsule = plan.isolation_capsules.data();  // a x, a y, b x, b y, reach: K each
    capsule[j] = ax, capsule[K + j] = ay, capsule[2 * K + j] = bx, capsule[3 * K + j] = by;
    capsule[4 * K + j] = std::sqrt(reach2) + 2 * margin;
  }

  p.x0 = x[0] / wx[0];
  p.y0 = y[0] / wy[0];
  p.x1 = x[n] / wx[n];
  p.y1 = y[n] / wy[n];
  const Coordinate fx = coordinate(x, wx, n, products), fy = coordinate(y, wy, n, products);
  const double r_lo = plan.common_denominator ? 1.0 : (fx.w_min * fx.w_min) / (fy.w_max * fy.w_max);
  const double r_hi = plan.common_denominator ? 1.0 : (fx.w_max * fx.w_max) / (fy.w_min * fy.w_min);
  for (int k = 0; k <= 2 * n - 1; ++k)
    for (double r : {r_lo, r_hi}) {
      p.gx[p.generators] = fx.h[k];
      p.gy[p.generators] = r * fy.h[k];
      // (hypot only where the squares could underflow, which would drop a tiny generator from the
      // cone: it is slow. A normalized curve's generators are far from overflow, and the bounds
      // keep a factor 2 for rounding.)
      const double gx = p.gx[p.generators], gy = p.gy[p.generators], squares = gx * gx + gy * gy;
      p.length[p.generators++] = squares > 1e-280 ? std::sqrt(squares) : std::hypot(gx, gy);
    }
  p.wx_max = fx.w_max;
  p.bend = std::hypot(fx.bend, fy.bend);
}

// The bounds of piece j over N, the pieces first..last around it (isolation.hpp): cos(2 alpha) v
// into isolation_monotone[j], and the distance below which the distance has one stationary point
// on N into isolation_unique[j]; 0 where they do not apply.
void bounds_around(PlanData& plan, int j, int K, const Piece* const* around, int count) {
  for (int q = 0; q < count; ++q)
    if (!around[q]->positive) return;
  // c: the chord of N.
  double cx = around[count - 1]->x1 - around[0]->x0, cy = around[count - 1]->y1 - around[0]->y0;
  const double chord = std::hypot(cx, cy);
  if (!(chord > 0)) return;
  cx /= chord;
  cy /= chord;
  // speed and bend in the piece's own parameter s = K t - q: dP/ds = dP/dt / K.
  double cos_alpha = 1.0, speed = std::numeric_limits<double>::infinity(), bend = 0.0;
  for (int q = 0; q < count; ++q) {
    const Piece& p = *around[q];
    // P' . c is at least the generators' smallest component along c over the largest Wx^2 (when
    // that is positive).
    double along_min = std::numeric_limits<double>::infinity();
    for (int k = 0; k < p.generators; ++k) {
      const double along = p.gx[k] * cx + p.gy[k] * cy;
      along_min = std::min(along_min, along);
      if (p.length[k] > 0) cos_alpha = std::min(cos_alpha, along / p.length[k]);  // 0 adds nothing to the cone
    }
    speed = std::min(speed, along_min / (p.wx_max * p.wx_max));
    bend = std::max(bend, p.bend);
  }
  const double cos_2alpha = 2 * cos_alpha * cos_alpha - 1;
  // Half of each: room for the rounding of all the above (relative errors ~n^2 eps). In t:
  // dP/dt = K dP/ds, d2P/dt2 = K^2 d2P/ds2, so the ratio below is the same in s and in t.
  if (cos_alpha > 0 && cos_2alpha > 0 && speed > 0 && std::isfinite(speed)) {
    plan.isolation_monotone[j] = 0.5 * cos_2alpha * K * speed;
    const double unique = 0.5 * speed * speed / ((1 + 1 / cos_2alpha) * bend);
    if (std::isfinite(unique)) plan.isolation_unique[j] = unique;
  }
}

}  // namespace

int isolation_piece_count(int degree) {
  // A curve of higher degree turns more, and a piece whose tangents turn by 45 degrees or more
  // certifies nothing around it; more pieces cost make_plan O(K n^2 + K^2). Speed only: a lane
  // the certificate refuses goes on to the gap pass. The refusal rates per K and degree behind
  // these counts: docs/fast-path.md, "The isolation certificate". Above kLaneBatchedSvdMaxDegree a
  // refused lane that ends on the SVD path costs the most (Eigen's, one matrix at a time, ~20 us at
  // degree 20): there K doubles again, for about 1 ms more of make_plan at degree 20.
  if (degree <= 9) return 32;
  if (degree <= 14) return 128;
  if (degree <= kLaneBatchedSvdMaxDegree) return 256;
  return kIsolationMaxPieces;
}

// plan.isolation_far_floor and isolation_around_floor (plan_data.hpp): the least of each piece's
// bound, -inf where one is NaN (a NaN bound refuses every lane of its piece; the floors must not
// pass them).
void isolation_floors(PlanData& plan) {
  const double inf = std::numeric_limits<double>::infinity();
  double far = inf, monotone = inf, unique = inf;
  for (int j = 0; j < plan.isolation_pieces; ++j) {
    far = std::isnan(plan.isolation_far[j]) ? -inf : std::min(far, plan.isolation_far[j]);
    const double m = plan.isolation_monotone[j] * kDistinctParameterGap;
    monotone = std::isnan(m) ? -inf : std::min(monotone, m);
    unique = std::isnan(plan.isolation_unique[j]) ? -inf : std::min(unique, plan.isolation_unique[j]);
  }
  plan.isolation_far_floor = far;
  plan.isolation_around_floor = std::max(monotone, unique);
}

void isolation_pieces(PlanData& plan) {
  plan.isolation_pieces = 0;
  plan.isolation_boxes.clear();
  plan.isolation_far.clear();
  plan.isolation_monotone.clear();
  plan.isolation_unique.clear();
  plan.isolation_groups.clear();
  plan.isolation_far_wide.clear();
  plan.isolation_capsules.clear();
  const int n = plan.degree;
  if (n < 2) return;
  const int K = isolation_piece_count(n);
  plan.isolation_pieces = K;
  // x centres, x half-widths, y centres, y half-widths, K each (the distance from a point to a box
  // along x is then |x - centre| - half-width, or 0 inside). A piece with a weight that is not
  // positive gets the whole plane: never farther than any tolerance.
  const double inf = std::numeric_limits<double>::infinity();
  plan.isolation_boxes.assign(4 * K, 0.0);
  std::fill_n(plan.isolation_boxes.data() + K, K, inf);
  std::fill_n(plan.isolation_boxes.data() + 3 * K, K, inf);
  plan.isolation_monotone.assign(K, 0.0);
  plan.isolation_capsules.assign(5 * K, std::numeric_limits<double>::quiet_NaN());
  plan.isolation_unique.assign(K, 0.0);

  // The pieces in order, three at a time (pieces j-1, j, j+1 for the bounds around j), so that
  // the plan's memory does not grow with K beyond its boxes and bounds.
  const CoordinateProducts products(n);
  std::array<Piece, 3> window;
  auto at = [&](int q) -> Piece& { return window[q % 3]; };
  piece(plan, 0, K, products, at(0));
  for (int j = 0; j < K; ++j) {
    if (j + 1 < K) piece(plan, j + 1, K, products, at(j + 1));
    const int first = std::max(0, j - 1), last = std::min(K - 1, j + 1);
    const Piece* around[3];
    for (int q = first; q <= last; ++q) around[q - first] = &at(q);
    bounds_around(plan, j, K, around, last - first + 1);
  }

  const double* const x_centre = plan.isolation_boxes.data();
  const double* const x_half = x_centre + K;
  const double* const y_centre = x_centre + 2 * K;
  const double* const y_half = x_centre + 3 * K;

  // The groups' boxes, widened as the pieces' own (kIsolationMargin) for the rounding of their
  // ends: a point they clear is cleared by every box of the group.
  static_assert(32 % kIsolationGroup == 0 && kIsolationMaxPieces % kIsolationGroup == 0);
  const int groups = K / kIsolationGroup;
  plan.isolation_groups.assign(4 * groups, 0.0);
  for (int g = 0; g < groups; ++g) {
    double box[4] = {inf, -inf, inf, -inf};
    bool whole_plane = false;  // a box with a NaN in it (never certifies): the group's too
    for (int q = g * kIsolationGroup; q < (g + 1) * kIsolationGroup; ++q) {
      const double lo_x = x_centre[q] - x_half[q], hi_x = x_centre[q] + x_half[q];
      const double lo_y = y_centre[q] - y_half[q], hi_y = y_centre[q] + y_half[q];
      whole_plane = whole_plane || std::isnan(lo_x + hi_x + lo_y + hi_y);
      box[0] = std::min(box[0], lo_x), box[1] = std::max(box[1], hi_x);
      box[2] = std::min(box[2], lo_y), box[3] = std::max(box[3], hi_y);
    }
    if (whole_plane) box[0] = box[2] = -inf, box[1] = box[3] = inf;
    for (int k = 0; k < 4; ++k) {
      const double outward = (k % 2 == 0 ? -1.0 : 1.0) * kIsolationMargin * std::abs(box[k]);
      plan.isolation_groups[4 * g + k] = box[k] + outward;
    }
  }

  // Per piece j, the distance from its box to the nearest box not next to it: P(t) lies in the box
  // of t's piece, so no point of those pieces is nearer P0 than that less |P(t) - P0|. Most lanes
  // are certified by this one comparison; the others test P0 against the boxes one by one.
  // (Squared, one square root per piece: K^2 calls of hypot were most of make_plan at K = 256.)
  // The same beyond kIsolationWide pieces either side (isolation_far_wide): a point that fails the
  // first comparison then tests only the boxes of the pieces between.
  // The groups from j's own outwards, and only those whose box could hold a box nearer than the
  // nearest found so far: about K^2 / kIsolationGroup pairs rather than K^2 (at K = 512 every
  // pair was a quarter of make_plan). A group's bound is lowered by far more than the rounding of
  // either distance, so a group it skips holds no box whose distance, as computed below, is
  // smaller: both minima are those over every pair, to the bit.
  plan.isolation_far.assign(K, inf);
  plan.isolation_far_wide.assign(K, inf);
  const double* const group_box = plan.isolation_groups.data();  // x min, x max, y min, y max
  // The distance along one axis from [lo, hi] to the group's [g_lo, g_hi], from below (NaN and
  // infinite boxes: 0, never skipped).
  auto axis_gap_below = [](double lo, double hi, double g_lo, double g_hi) {
    const double gap = std::max(g_lo - hi, lo - g_hi);
    const double slack = kIsolationMargin * (1.0 + std::abs(lo) + std::abs(hi) + std::abs(g_lo) + std::abs(g_hi));
    return std::max(0.0, gap - slack);  // std::max(0, NaN) is 0
  };
  for (int j = 0; j < K; ++j) {
    double nearest2 = inf, wide2 = inf;
    const int own = j / kIsolationGroup;
    for (int step = 0; step < 2 * groups; ++step) {
      const int g = own + (step % 2 == 0 ? step / 2 : -(step + 1) / 2);  // own, own - 1, own + 1, ...
      if (g < 0 || g >= groups) continue;
      const double* gb = group_box + 4 * g;
      const double gx = axis_gap_below(x_centre[j] - x_half[j], x_centre[j] + x_half[j], gb[0], gb[1]);
      const double gy = axis_gap_below(y_centre[j] - y_half[j], y_centre[j] + y_half[j], gb[2], gb[3]);
      if (gx * gx + gy * gy > wide2) continue;  // wide2 >= nearest2: nothing nearer in it
      for (int q = g * kIsolationGroup; q < (g + 1) * kIsolationGroup; ++q) {
        if (q >= j - 1 && q <= j + 1) continue;
        double dx = std::abs(x_centre[j] - x_centre[q]) - x_half[j] - x_half[q];
        double dy = std::abs(y_centre[j] - y_centre[q]) - y_half[j] - y_half[q];
        dx = dx > 0 ? dx : 0.0;  // NaN (an infinite box) -> 0
        dy = dy > 0 ? dy : 0.0;
        const double d2 = dx * dx + dy * dy;
        nearest2 = std::min(nearest2, d2);
        if (q < j - kIsolationWide || q > j + kIsolationWide) wide2 = std::min(wide2, d2);
      }
    }
    plan.isolation_far[j] = std::sqrt(nearest2);
    plan.isolation_far_wide[j] = std::sqrt(wide2);
  }
  isolation_floors(plan);
  segment_far_grid(plan);
}

void segment_far_grid(PlanData& plan) {
  plan.segment_far_near.clear();
  const int K = plan.isolation_pieces;
  if (plan.degree < kSegmentFarMinDegree || K == 0) return;
  const double* const x_centre = plan.isolation_boxes.data();
  const double* const x_half = x_centre + K;
  const double* const y_centre = x_centre + 2 * K;
  const double* const y_half = x_centre + 3 * K;
  const double* const capsule = plan.isolation_capsules.data();  // a x, a y, b x, b y, reach: K each
  // The grid's extent: the pieces' boxes, widened by the reach and a cell either way (a point
  // outside it is never called far).
  double lo_x = std::numeric_limits<double>::infinity(), hi_x = -lo_x, lo_y = lo_x, hi_y = -lo_x;
  for (int j = 0; j < K; ++j) {
    lo_x = std::min(lo_x, x_centre[j] - x_half[j]), hi_x = std::max(hi_x, x_centre[j] + x_half[j]);
    lo_y = std::min(lo_y, y_centre[j] - y_half[j]), hi_y = std::max(hi_y, y_centre[j] + y_half[j]);
  }
  if (!std::isfinite(lo_x + hi_x + lo_y + hi_y)) return;  // a piece without a box (or a NaN)
  const double reach = kSegmentFarDistance * plan.normalized_diagonal;
  const double cell_u = (hi_x - lo_x + 2 * reach) / (kSegmentFarGrid - 2);
  const double cell_v = (hi_y - lo_y + 2 * reach) / (kSegmentFarGrid - 2);
  if (!(cell_u > 0 && cell_v > 0 && reach > 0)) return;
  plan.segment_far_reach = reach;
  plan.segment_far_u = lo_x - reach - cell_u;
  plan.segment_far_v = lo_y - reach - cell_v;
  plan.segment_far_inverse_cell_u = 1.0 / cell_u;
  plan.segment_far_inverse_cell_v = 1.0 / cell_v;
  plan.segment_far_near.assign(kSegmentFarGrid * kSegmentFarGrid / 64, 0);
  // A point's cell is computed in doubles: at an edge it may be the neighbour's. Each cell is
  // taken as its square widened by `slack` (far more than that rounding).
  const double slack = 1e-9 * (1.0 + std::max({std::abs(lo_x), std::abs(hi_x), std::abs(lo_y), std::abs(hi_y)}));
  const double half_diagonal = 0.5 * std::hypot(cell_u, cell_v) + slack;
  auto cells = [](double lo, double hi, double origin, double inverse_cell) {
    const double first = std::floor((lo - origin) * inverse_cell), last = std::floor((hi - origin) * inverse_cell);
    return std::array<int, 2>{static_cast<int>(std::max(0.0, first)),
                              static_cast<int>(std::min(kSegmentFarGrid - 1.0, last))};
  };
  auto mark = [&](int gu, int gv) {
    const std::size_t bit = segment_far_bit(static_cast<std::size_t>(gu), static_cast<std::size_t>(gv));
    plan.segment_far_near[bit / 64] |= std::uint64_t{1} << (bit % 64);
  };
  for (int j = 0; j < K; ++j) {
    const double capsule_reach = capsule[4 * K + j];
    // The cells that meet the box widened by the reach (and the slack)...
    const double grow = reach + slack;
    const auto iu = cells(x_centre[j] - x_half[j] - grow, x_centre[j] + x_half[j] + grow, plan.segment_far_u,
                          plan.segment_far_inverse_cell_u);
    const auto iv = cells(y_centre[j] - y_half[j] - grow, y_centre[j] + y_half[j] + grow, plan.segment_far_v,
                          plan.segment_far_inverse_cell_v);
    for (int gv = iv[0]; gv <= iv[1]; ++gv)
      for (int gu = iu[0]; gu <= iu[1]; ++gu) {
        // ... and, where the piece has a capsule, whose centre is within the capsule's reach, the
        // grid's and the cell's half diagonal of its chord (the box of a slanted piece holds many
        // cells its capsule does not come near).
        if (capsule_reach >= 0) {
          const double cu = plan.segment_far_u + (gu + 0.5) * cell_u, cv = plan.segment_far_v + (gv + 0.5) * cell_v;
          const double limit = capsule_reach + reach + half_diagonal;
          if (chord_distance2(capsule[j], capsule[K + j], capsule[2 * K + j], capsule[3 * K + j], cu, cv).distance2 >
              limit * limit)
            continue;
        }
        mark(gu, gv);
      }
  }
}

namespace {
// The piece [j/K, (j+1)/K] that holds t in [0, 1] (t = 1 in the last).
int piece_of(const PlanData& plan, double t) {
  return std::min(plan.isolation_pieces - 1, static_cast<int>(t * plan.isolation_pieces));
}

// The margin on the tolerance of both tests: room for the rounding of the distances.
double isolation_limit(double tolerance) { return tolerance * (1 + kIsolationMargin); }

// Whether piece q's capsule is farther than `limit` from (u0, v0), for a piece whose box is not:
// a box stands off a slanted piece by up to half its width, the capsule's reach by the piece's
// sagitta. The distance is to some point of the chord (the computed projection), a few ulps of the
// coordinates from the nearest: the margin covers it. (Out of the loops over the boxes, which
// call it only where a box fails: at 32 pieces, inlined, it cost the loops 1-2%.)
[[gnu::noinline]] bool capsule_farther(const PlanData& plan, int q, double u0, double v0, double limit) {
  const int K = plan.isolation_pieces;
  if (K < kIsolationCapsuleMinPieces) return false;  // no capsules
  const double* c = plan.isolation_capsules.data();
  const auto [distance2, scale] = chord_distance2(c[q], c[K + q], c[2 * K + q], c[3 * K + q], u0, v0);
  const double reach = (c[4 * K + q] + limit) * (1 + kIsolationMargin) + kIsolationMargin * scale;
  return distance2 > reach * reach;  // false for a NaN reach
}

// Around t (in piece j): every stationary point of the distance on N lies within
// distance / monotone of t, and below isolation_unique there is only one, t itself.
bool isolated_around(const PlanData& plan, int j, double distance) {
  return distance < plan.isolation_monotone[j] * kDistinctParameterGap || distance < plan.isolation_unique[j];
}
}  // namespace

void isolated_by_far_boxes(const PlanData& plan, const double* t, const double* distance, double tolerance,
                           std::size_t count, std::uint8_t* certified) {
  if (plan.isolation_monotone.empty()) {
    std::fill_n(certified, count, std::uint8_t{0});
    return;
  }
  const double limit = isolation_limit(tolerance);
  for (std::size_t l = 0; l < count; ++l) {
    const bool inside = t[l] >= 0.0 && t[l] <= 1.0;  // false for NaN
    const int j = inside ? piece_of(plan, t[l]) : 0;
    certified[l] = inside && isolated_around(plan, j, distance[l]) && plan.isolation_far[j] - distance[l] > limit;
  }
}

kernels::PieceCertificate far_boxes_certificate(const PlanData& plan, double tolerance) {
  return {.pieces = plan.isolation_pieces,
          .monotone = plan.isolation_monotone.data(),
          .monotone_factor = kDistinctParameterGap,
          .unique = plan.isolation_unique.data(),
          .far = plan.isolation_far.data(),
          .limit = isolation_limit(tolerance),
          .around_floor = plan.isolation_around_floor,
          .far_floor = plan.isolation_far_floor};
}

bool isolated(const PlanData& plan, double u0, double v0, double t, double distance, double tolerance) {
  const int K = plan.isolation_pieces;
  if (plan.isolation_monotone.empty() || !(t >= 0.0 && t <= 1.0)) return false;
  const int j = piece_of(plan, t);
  if (!isolated_around(plan, j, distance)) return false;
  const double limit = isolation_limit(tolerance);
  if (plan.isolation_far[j] - distance > limit) return true;
  const double limit2 = limit * limit;
  // Every box beyond kIsolationWide pieces of t's is as far by the same argument: then P0 itself
  // against the boxes between (not next to t's), all farther than the tolerance.
  if (plan.isolation_far_wide[j] - distance > limit) {
    bool near = false;
    for (int q = std::max(0, j - kIsolationWide); q <= std::min(K - 1, j + kIsolationWide); ++q)
      near |= (q < j - 1 || q > j + 1) && !(isolation_box_distance2(plan, q, u0, v0) > limit2) &&
              !capsule_farther(plan, q, u0, v0, limit);
    return !near;
  }
  // Otherwise P0 itself against every box not next to t's: all farther than the tolerance. A
  // group's box holds the boxes of its pieces, so a group farther than that is done with; the
  // pieces of the few others one by one. (A NaN point is inside every box: never certified.)
  const double* groups = plan.isolation_groups.data();
  for (int g = 0; g < K / kIsolationGroup; ++g) {
    if (box_distance2(groups + 4 * g, u0, v0) > limit2) continue;
    for (int q = g * kIsolationGroup; q < (g + 1) * kIsolationGroup; ++q)
      if (!(isolation_box_distance2(plan, q, u0, v0) > limit2) && (q < j - 1 || q > j + 1) &&
          !capsule_farther(plan, q, u0, v0, limit))
        return false;
  }
  return true;
}

bool nearest_on_segment(const PlanData& plan, double u0, double v0, double t, double distance) {
  if (plan.isolation_unique.empty() || !(t >= 0.0 && t <= 1.0)) return false;
  return distance < plan.isolation_unique[piece_of(plan, t)] && isolated(plan, u0, v0, t, distance, distance);
}

}  // namespace bezinv::detail
