#include "refine.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>

#include "bezinv/bernstein.hpp"
#include "bezinv/tolerances.hpp"

namespace bezinv::detail {

CurveJet curve_jet(const InversionPlan& plan, double t) {
  const auto N = bernstein_jet(plan.x_num, t), D = bernstein_jet(plan.x_den, t);
  const auto M = bernstein_jet(plan.y_num, t), E = bernstein_jet(plan.y_den, t);
  CurveJet j;
  j.x = N.value / D.value;
  j.dx = (N.first - D.first * j.x) / D.value;
  j.ddx = (N.second - 2 * D.first * j.dx - D.second * j.x) / D.value;
  j.y = M.value / E.value;
  j.dy = (M.first - E.first * j.y) / E.value;
  j.ddy = (M.second - 2 * E.first * j.dy - E.second * j.y) / E.value;
  return j;
}

double distance(const InversionPlan& plan, double u0, double v0, double t) {
  const auto p = plan.normalized_point(t);
  return std::hypot(p[0] - u0, p[1] - v0);
}

double refine_parameter(const InversionPlan& plan, double u0, double v0, double t0, bool stay_on_segment) {
  if (!std::isfinite(t0)) return t0;
  double t = stay_on_segment ? std::clamp(t0, 0.0, 1.0) : t0;
  double d = distance(plan, u0, v0, t);
  if (!std::isfinite(d)) return t;
  for (int iteration = 0; iteration < kNewtonMaxIterations; ++iteration) {
    const CurveJet j = curve_jet(plan, t);
    const double ex = j.x - u0, ey = j.y - v0;
    const double g1 = ex * j.dx + ey * j.dy;                          // f(t)
    const double speed2 = j.dx * j.dx + j.dy * j.dy;
    double g2 = speed2 + ex * j.ddx + ey * j.ddy;                     // f'(t)
    // Where the distance is locally concave (far from the curve, inside the evolute) Newton would
    // head for a maximum; Gauss-Newton (f' ~ |P'|^2) still descends.
    if (!(g2 > 0)) g2 = speed2;
    if (!(g2 > 0) || !std::isfinite(g1)) break;
    double step = std::clamp(-g1 / g2, -kNewtonMaxStep, kNewtonMaxStep);
    if (std::abs(step) <= kNewtonTrustedStep) {
      // Converging: off the curve the distance is flat to second order at its minimum, so
      // comparing distances cannot resolve t below ~sqrt(eps); f(t) = 0 can. A step this small
      // cannot leave the basin, so take it as Newton gives it.
      double next = t + step;
      if (stay_on_segment) next = std::clamp(next, 0.0, 1.0);
      const double moved = std::abs(next - t);
      t = next;
      d = distance(plan, u0, v0, t);
      if (moved <= 4 * std::numeric_limits<double>::epsilon() * std::max(1.0, std::abs(t))) return t;
      continue;
    }
    bool accepted = false;
    for (int halving = 0; halving < 40; ++halving) {
      double next = t + step;
      if (stay_on_segment) next = std::clamp(next, 0.0, 1.0);
      const double dn = distance(plan, u0, v0, next);
      if (dn <= d) {
        accepted = next != t;
        const double moved = std::abs(next - t);
        t = next;
        d = dn;
        if (moved <= 4 * std::numeric_limits<double>::epsilon() * std::max(1.0, std::abs(t))) return t;
        break;
      }
      step *= 0.5;
    }
    if (!accepted) break;
  }
  return t;
}

double nearest_parameter_on_segment(const InversionPlan& plan, double u0, double v0, double hint) {
  // Fixed-size workspaces: the search runs per point, so it must not allocate.
  constexpr int kMaxSamples = kNearestSamplesPerDegree * kMaxDegree;
  const int samples = std::max(32, kNearestSamplesPerDegree * plan.degree);
  std::array<double, kMaxSamples + 1> d;
  for (int k = 0; k <= samples; ++k) d[k] = distance(plan, u0, v0, static_cast<double>(k) / samples);
  // Local minima of the sampled distance; each marks a basin to refine in. The best kMaxBasins
  // are kept (a curve of degree n has at most 2n-1 of them, and only the nearest few can win).
  constexpr int kMaxBasins = 8;
  std::array<std::pair<double, int>, kMaxBasins + 1> minima;
  int found = 0;
  for (int k = 0; k <= samples; ++k) {
    const bool left_ok = k == 0 || d[k] <= d[k - 1];
    const bool right_ok = k == samples || d[k] <= d[k + 1];
    if (!(left_ok && right_ok)) continue;
    // Insertion into the sorted list of the best ones so far (NaN distances never enter it).
    if (!(d[k] < (found == kMaxBasins ? minima[found - 1].first : std::numeric_limits<double>::infinity())))
      continue;
    int at = std::min(found, kMaxBasins - 1);
    while (at > 0 && minima[at - 1].first > d[k]) { minima[at] = minima[at - 1]; --at; }
    minima[at] = {d[k], k};
    found = std::min(found + 1, kMaxBasins);
  }

  double best_t = 0.0, best_d = std::numeric_limits<double>::infinity();
  auto consider = [&](double t0) {
    const double t = refine_parameter(plan, u0, v0, t0, /*stay_on_segment=*/true);
    const double dt = distance(plan, u0, v0, t);
    if (dt < best_d) { best_d = dt; best_t = t; }
  };
  if (hint >= 0.0 && hint <= 1.0) consider(hint);
  for (int i = 0; i < found; ++i) consider(static_cast<double>(minima[i].second) / samples);
  return best_t;
}

}  // namespace bezinv::detail
