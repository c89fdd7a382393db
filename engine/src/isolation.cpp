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

// The Bernstein coefficients of c (degree n) on [a, b] (as a curve of its own on [0, 1]): de
// Casteljau at a keeps the right part, then at (b - a) / (1 - a) the left part of that.
Coefficients split(std::span<const double> c, double a, double b) {
  const int n = static_cast<int>(c.size()) - 1;
  Coefficients f{}, right{}, piece{};
  std::copy(c.begin(), c.end(), f.begin());
  for (int k = 0; k <= n; ++k) {  // after k rounds, f[n - k] is the right part's coefficient n - k
    right[n - k] = f[n - k];
    for (int i = 0; i < n - k; ++i) f[i] = (1 - a) * f[i] + a * f[i + 1];
  }
  const double s = a < 1 ? (b - a) / (1 - a) : 1.0;
  f = right;
  for (int k = 0; k <= n; ++k) {  // after k rounds, f[0] is the left part's coefficient k
    piece[k] = f[0];
    for (int i = 0; i < n - k; ++i) f[i] = (1 - s) * f[i] + s * f[i + 1];
  }
  return piece;
}

// The Bernstein coefficients (degree p + q) of the product of f (degree p) and g (degree q):
// B^p_i B^q_j = C(p,i) C(q,j) / C(p+q,i+j) B^{p+q}_{i+j}.
void multiply_add(const double* f, int p, const double* g, int q, double sign, double* out) {
  for (int i = 0; i <= p; ++i)
    for (int j = 0; j <= q; ++j)
      out[i + j] += sign * binomial(p, i) * binomial(q, j) / binomial(p + q, i + j) * f[i] * g[j];
}

struct Piece {
  bool positive = false;             // every weight of the piece > 0
  Coefficients x{}, wx{}, y{}, wy{};  // numerators and denominators (wy = wx for a common one)
};

// One coordinate f = F / W of a piece (Bernstein coefficients of F and W, degree n, W > 0):
// the coefficients of H = F'W - FW' (degree 2n - 1) and the bounds that |f''| needs.
struct Coordinate {
  std::array<double, 2 * kMaxDegree> h{};
  double w_min = 0, w_max = 0;
  double bend = 0;  // |f''| <= (|G| W + 2 |W'| |H|) / W^3, G = H' = F''W - FW'' (degree 2n - 2)
};
Coordinate coordinate(const Coefficients& f, const Coefficients& w, int n) {
  Coordinate c;
  std::array<double, kMaxDegree> df{}, dw{}, ddf{}, ddw{};
  for (int i = 0; i < n; ++i) df[i] = n * (f[i + 1] - f[i]), dw[i] = n * (w[i + 1] - w[i]);
  for (int i = 0; i + 1 < n; ++i) ddf[i] = (n - 1) * (df[i + 1] - df[i]), ddw[i] = (n - 1) * (dw[i + 1] - dw[i]);
  multiply_add(df.data(), n - 1, w.data(), n, 1.0, c.h.data());
  multiply_add(f.data(), n, dw.data(), n - 1, -1.0, c.h.data());
  std::array<double, 2 * kMaxDegree> g{};
  multiply_add(ddf.data(), n - 2, w.data(), n, 1.0, g.data());
  multiply_add(f.data(), n, ddw.data(), n - 2, -1.0, g.data());
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

}  // namespace

void isolation_pieces(InversionPlan& plan) {
  plan.isolation_boxes.clear();
  plan.isolation_far.clear();
  plan.isolation_monotone.clear();
  plan.isolation_unique.clear();
  const int n = plan.degree;
  if (n < 2) return;
  constexpr int K = kIsolationPieces;
  std::vector<Piece> pieces(K);
  // x centres, x half-widths, y centres, y half-widths, K each (the distance from a point to a box
  // along x is then |x - centre| - half-width, or 0 inside). A piece with a weight that is not
  // positive gets the whole plane: never farther than any tolerance.
  const double inf = std::numeric_limits<double>::infinity();
  plan.isolation_boxes.assign(4 * K, 0.0);
  double* const x_centre = plan.isolation_boxes.data();
  double* const x_half = x_centre + K;
  double* const y_centre = x_centre + 2 * K;
  double* const y_half = x_centre + 3 * K;
  std::fill_n(x_half, K, inf);
  std::fill_n(y_half, K, inf);
  for (int j = 0; j < K; ++j) {
    Piece& piece = pieces[j];
    const double a = static_cast<double>(j) / K, b = static_cast<double>(j + 1) / K;  // exact
    piece.x = split(plan.x_num, a, b);
    piece.y = split(plan.y_num, a, b);
    piece.wx = split(plan.x_den, a, b);
    piece.wy = plan.common_denominator ? piece.wx : split(plan.y_den, a, b);
    piece.positive = true;
    double x_min = inf, x_max = -inf, y_min = inf, y_max = -inf;
    for (int i = 0; i <= n; ++i) {
      // x = X / Wx is a convex combination of the x[i] / wx[i] (weights wx[i] B_i / Wx), and so is
      // y of its own ratios: the box holds the piece for separate denominators too.
      if (!(piece.wx[i] > 0 && piece.wy[i] > 0)) piece.positive = false;
      const double x = piece.x[i] / piece.wx[i], y = piece.y[i] / piece.wy[i];
      x_min = std::min(x_min, x); x_max = std::max(x_max, x);
      y_min = std::min(y_min, y); y_max = std::max(y_max, y);
    }
    if (!piece.positive || !std::isfinite(x_min + x_max + y_min + y_max)) continue;
    // Room for the rounding of the split and the divisions (~n eps of the coordinates; 1e-12 is
    // far above it and far below any tolerance a point would be judged by).
    const double size = std::max({std::abs(x_min), std::abs(x_max), std::abs(y_min), std::abs(y_max)});
    const double margin = 1e-12 * (1.0 + size);
    x_centre[j] = 0.5 * (x_min + x_max);
    x_half[j] = 0.5 * (x_max - x_min) + margin;
    y_centre[j] = 0.5 * (y_min + y_max);
    y_half[j] = 0.5 * (y_max - y_min) + margin;
  }

  // Per piece j, the distance from its box to the nearest box not next to it: P(t) lies in the box
  // of t's piece, so no point of those pieces is nearer P0 than that less |P(t) - P0|. Most lanes
  // are certified by this one comparison; the others test P0 against the boxes one by one.
  plan.isolation_far.assign(K, inf);
  for (int j = 0; j < K; ++j)
    for (int q = 0; q < K; ++q) {
      if (q >= j - 1 && q <= j + 1) continue;
      double dx = std::abs(x_centre[j] - x_centre[q]) - x_half[j] - x_half[q];
      double dy = std::abs(y_centre[j] - y_centre[q]) - y_half[j] - y_half[q];
      dx = dx > 0 ? dx : 0.0;  // NaN (an infinite box) -> 0
      dy = dy > 0 ? dy : 0.0;
      plan.isolation_far[j] = std::min(plan.isolation_far[j], std::hypot(dx, dy));
    }

  // Per piece j, over N = pieces j-1..j+1: cos(2 alpha) v and the distance below which the
  // distance has one stationary point on N (header), 0 where they do not apply.
  plan.isolation_monotone.assign(K, 0.0);
  plan.isolation_unique.assign(K, 0.0);
  for (int j = 0; j < K; ++j) {
    const int first = std::max(0, j - 1), last = std::min(K - 1, j + 1);
    bool usable = true;
    for (int q = first; q <= last; ++q) usable = usable && pieces[q].positive;
    if (!usable) continue;
    // c: the chord of N.
    const Piece& p0 = pieces[first];
    const Piece& p1 = pieces[last];
    double cx = p1.x[n] / p1.wx[n] - p0.x[0] / p0.wx[0], cy = p1.y[n] / p1.wy[n] - p0.y[0] / p0.wy[0];
    const double chord = std::hypot(cx, cy);
    if (!(chord > 0)) continue;
    cx /= chord;
    cy /= chord;
    // speed and bend in the piece's own parameter s = K t - q: dP/ds = dP/dt / K.
    double cos_alpha = 1.0, speed = std::numeric_limits<double>::infinity(), bend = 0.0;
    for (int q = first; q <= last; ++q) {
      const Piece& p = pieces[q];
      const Coordinate fx = coordinate(p.x, p.wx, n), fy = coordinate(p.y, p.wy, n);
      // P' = (Hx / Wx^2, Hy / Wy^2) = (Hx, r Hy) / Wx^2 with r = Wx^2 / Wy^2 in [r_lo, r_hi] (r = 1
      // for a common denominator), and (Hx, r Hy) = sum_k B_k (hx_k, r hy_k): every tangent lies in
      // the cone of the generators (hx_k, r hy_k), r = r_lo or r_hi, and P' . c is at least their
      // smallest component along c over the largest Wx^2 (when that is positive).
      const double r_lo = plan.common_denominator ? 1.0 : (fx.w_min * fx.w_min) / (fy.w_max * fy.w_max);
      const double r_hi = plan.common_denominator ? 1.0 : (fx.w_max * fx.w_max) / (fy.w_min * fy.w_min);
      double along_min = std::numeric_limits<double>::infinity();
      for (int k = 0; k <= 2 * n - 1; ++k)
        for (double r : {r_lo, r_hi}) {
          const double gx = fx.h[k], gy = r * fy.h[k];
          const double along = gx * cx + gy * cy, length = std::hypot(gx, gy);
          along_min = std::min(along_min, along);
          if (length > 0) cos_alpha = std::min(cos_alpha, along / length);  // 0 adds nothing to the cone
        }
      speed = std::min(speed, along_min / (fx.w_max * fx.w_max));
      bend = std::max(bend, std::hypot(fx.bend, fy.bend));
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
}

namespace {
// The piece [j/K, (j+1)/K] that holds t in [0, 1] (t = 1 in the last).
int piece_of(double t) { return std::min(kIsolationPieces - 1, static_cast<int>(t * kIsolationPieces)); }
}  // namespace

bool isolated(const InversionPlan& plan, double u0, double v0, double t, double distance, double tolerance) {
  constexpr int K = kIsolationPieces;
  if (plan.isolation_monotone.empty() || !(t >= 0.0 && t <= 1.0)) return false;
  const int j = piece_of(t);
  // Around t: every stationary point of the distance on N lies within distance / monotone of t,
  // and below isolation_unique there is only one, t itself.
  if (!(distance < plan.isolation_monotone[j] * kDistinctParameterGap) && !(distance < plan.isolation_unique[j]))
    return false;
  const double limit = tolerance * (1 + 1e-12);
  if (plan.isolation_far[j] - distance > limit) return true;
  // Otherwise P0 itself against every box not next to t's: all farther than the tolerance. (Box by
  // box, this is what took 8% of the pipeline at degree 8 before the comparison above, perf.)
  const double* x_centre = plan.isolation_boxes.data();
  const double* x_half = x_centre + K;
  const double* y_centre = x_centre + 2 * K;
  const double* y_half = x_centre + 3 * K;
  std::array<double, K> distance2;
  for (int q = 0; q < K; ++q) {
    double dx = std::abs(u0 - x_centre[q]) - x_half[q], dy = std::abs(v0 - y_centre[q]) - y_half[q];
    dx = dx > 0 ? dx : 0.0;  // NaN (a NaN point) -> 0: inside every box, never certified
    dy = dy > 0 ? dy : 0.0;
    distance2[q] = dx * dx + dy * dy;
  }
  const double limit2 = limit * limit;
  for (int q = 0; q < K; ++q)
    if (!(distance2[q] > limit2) && (q < j - 1 || q > j + 1)) return false;
  return true;
}

bool nearest_on_segment(const InversionPlan& plan, double u0, double v0, double t, double distance) {
  if (plan.isolation_unique.empty() || !(t >= 0.0 && t <= 1.0)) return false;
  return distance < plan.isolation_unique[piece_of(t)] && isolated(plan, u0, v0, t, distance, distance);
}

}  // namespace bezinv::detail
