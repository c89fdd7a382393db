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
  bool positive = false;        // every weight of the piece > 0
  Coefficients x{}, y{}, w{};   // the piece's homogeneous control points
};

}  // namespace

void isolation_pieces(InversionPlan& plan) {
  plan.isolation_boxes.clear();
  plan.isolation_monotone.clear();
  const int n = plan.degree;
  if (n < 2 || !plan.common_denominator) return;
  constexpr int K = kIsolationPieces;
  std::vector<Piece> pieces(K);
  plan.isolation_boxes.assign(4 * K, std::numeric_limits<double>::quiet_NaN());
  for (int j = 0; j < K; ++j) {
    Piece& piece = pieces[j];
    const double a = static_cast<double>(j) / K, b = static_cast<double>(j + 1) / K;  // exact
    piece.x = split(plan.x_num, a, b);
    piece.y = split(plan.y_num, a, b);
    piece.w = split(plan.x_den, a, b);
    piece.positive = true;
    double x_min = std::numeric_limits<double>::infinity(), x_max = -x_min, y_min = x_min, y_max = x_max;
    for (int i = 0; i <= n; ++i) {
      if (!(piece.w[i] > 0)) piece.positive = false;
      const double x = piece.x[i] / piece.w[i], y = piece.y[i] / piece.w[i];
      x_min = std::min(x_min, x); x_max = std::max(x_max, x);
      y_min = std::min(y_min, y); y_max = std::max(y_max, y);
    }
    if (!piece.positive || !std::isfinite(x_min + x_max + y_min + y_max)) continue;
    // Room for the rounding of the split and the divisions (~n eps of the coordinates; 1e-12 is
    // far above it and far below any tolerance a point would be judged by).
    const double margin = 1e-12 * (1.0 + std::max({std::abs(x_min), std::abs(x_max), std::abs(y_min), std::abs(y_max)}));
    plan.isolation_boxes[4 * j] = x_min - margin;
    plan.isolation_boxes[4 * j + 1] = x_max + margin;
    plan.isolation_boxes[4 * j + 2] = y_min - margin;
    plan.isolation_boxes[4 * j + 3] = y_max + margin;
  }

  // Per piece j, over N = pieces j-1..j+1: cos(2 alpha) v (header), 0 where it does not apply.
  plan.isolation_monotone.assign(K, 0.0);
  for (int j = 0; j < K; ++j) {
    const int first = std::max(0, j - 1), last = std::min(K - 1, j + 1);
    bool usable = true;
    for (int q = first; q <= last; ++q) usable = usable && pieces[q].positive;
    if (!usable) continue;
    // c: the chord of N.
    const Piece& p0 = pieces[first];
    const Piece& p1 = pieces[last];
    double cx = p1.x[n] / p1.w[n] - p0.x[0] / p0.w[0], cy = p1.y[n] / p1.w[n] - p0.y[0] / p0.w[0];
    const double chord = std::hypot(cx, cy);
    if (!(chord > 0)) continue;
    cx /= chord;
    cy /= chord;
    double cos_alpha = 1.0, speed = std::numeric_limits<double>::infinity();
    for (int q = first; q <= last; ++q) {
      const Piece& p = pieces[q];
      // The angle of every difference of control points with c.
      for (int i = 0; i <= n; ++i)
        for (int k = i + 1; k <= n; ++k) {
          const double dx = p.x[k] / p.w[k] - p.x[i] / p.w[i], dy = p.y[k] / p.w[k] - p.y[i] / p.w[i];
          const double length = std::hypot(dx, dy);
          if (length == 0) continue;  // adds nothing to the combination
          cos_alpha = std::min(cos_alpha, (dx * cx + dy * cy) / length);
        }
      // v: P' . c = (H . c) / W^2 with H = X'W - XW' (degree 2n - 1 here), at least the smallest
      // Bernstein coefficient of H . c over the largest of W^2 (W lies between its coefficients).
      std::array<double, kMaxDegree> dx{}, dy{}, dw{};
      for (int i = 0; i < n; ++i) {
        dx[i] = n * (p.x[i + 1] - p.x[i]);
        dy[i] = n * (p.y[i + 1] - p.y[i]);
        dw[i] = n * (p.w[i + 1] - p.w[i]);
      }
      std::array<double, 2 * kMaxDegree> hx{}, hy{};
      multiply_add(dx.data(), n - 1, p.w.data(), n, 1.0, hx.data());
      multiply_add(p.x.data(), n, dw.data(), n - 1, -1.0, hx.data());
      multiply_add(dy.data(), n - 1, p.w.data(), n, 1.0, hy.data());
      multiply_add(p.y.data(), n, dw.data(), n - 1, -1.0, hy.data());
      double h_min = std::numeric_limits<double>::infinity(), w_max = 0.0;
      for (int k = 0; k <= 2 * n - 1; ++k) h_min = std::min(h_min, hx[k] * cx + hy[k] * cy);
      for (int i = 0; i <= n; ++i) w_max = std::max(w_max, p.w[i]);
      speed = std::min(speed, h_min / (w_max * w_max));
    }
    const double cos_2alpha = 2 * cos_alpha * cos_alpha - 1;
    // Half of it: room for the rounding of all the above (relative errors ~n^2 eps).
    if (cos_alpha > 0 && cos_2alpha > 0 && speed > 0 && std::isfinite(speed))
      plan.isolation_monotone[j] = 0.5 * cos_2alpha * speed;
  }
}

bool isolated(const InversionPlan& plan, double u0, double v0, double t, double distance, double tolerance) {
  constexpr int K = kIsolationPieces;
  if (plan.isolation_monotone.empty() || !(t >= 0.0 && t <= 1.0)) return false;
  const int j = std::min(K - 1, static_cast<int>(t * K));
  // Around t: a stationary point of the distance lies within distance / monotone of t.
  if (!(distance < plan.isolation_monotone[j] * kDistinctParameterGap)) return false;
  // Far from t: every other box farther than the tolerance (a NaN box fails the comparison).
  const double limit = tolerance * (1 + 1e-12);
  const double limit2 = limit * limit;
  bool far = true;
  for (int q = 0; q < K; ++q) {
    const double* b = plan.isolation_boxes.data() + 4 * q;
    const double dx = std::max({b[0] - u0, u0 - b[1], 0.0}), dy = std::max({b[2] - v0, v0 - b[3], 0.0});
    const bool next_to_t = q >= j - 1 && q <= j + 1;
    const bool box = !std::isnan(b[0]);  // NaN: a piece with a weight that is not positive
    far = far && (next_to_t || (box && dx * dx + dy * dy > limit2));
  }
  return far;
}

}  // namespace bezinv::detail
