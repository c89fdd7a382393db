#include "refine.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>

#include "bezinv/bernstein.hpp"
#include "bezinv/tolerances.hpp"
#include "stationary_points.hpp"

namespace bezinv::detail {

namespace {

// The four Bernstein polynomials of the normalized curve (x_num, x_den, y_num, y_den) go through
// de Casteljau together: one pass over four independent chains, with fixed-size storage. The
// arithmetic per polynomial is exactly bernstein_value's / bernstein_jet's (same operations in
// the same order), so every caller sees the same numbers whichever way it evaluates.
struct Four {
  std::array<double, kMaxDegree + 1> a, b, c, d;
};

void load(const PlanData& plan, Four& f) {
  const std::size_t count = plan.x_num.size();
  std::copy_n(plan.x_num.begin(), count, f.a.begin());
  std::copy_n(plan.x_den.begin(), count, f.b.begin());
  std::copy_n(plan.y_num.begin(), count, f.c.begin());
  std::copy_n(plan.y_den.begin(), count, f.d.begin());
}

// `steps` rounds of de Casteljau on the first `top + 1` coefficients.
void de_casteljau(Four& f, int top, int steps, double t) {
  const double s = 1.0 - t;
  for (int r = 1; r <= steps; ++r)
    for (int i = 0; i <= top - r; ++i) {
      f.a[i] = s * f.a[i] + t * f.a[i + 1];
      f.b[i] = s * f.b[i] + t * f.b[i + 1];
      f.c[i] = s * f.c[i] + t * f.c[i + 1];
      f.d[i] = s * f.d[i] + t * f.d[i + 1];
    }
}

// |(dx, dy)|: the plain formula when it can neither overflow nor underflow (the common case, and
// several times cheaper than std::hypot), hypot otherwise.
double length(double dx, double dy) {
  const double h = std::sqrt(dx * dx + dy * dy);
  return (h < 1e150 && h > 1e-150) ? h : std::hypot(dx, dy);
}

}  // namespace

std::array<double, 2> curve_point(const PlanData& plan, double t) {
  Four f;
  load(plan, f);
  de_casteljau(f, plan.degree, plan.degree, t);
  return {f.a[0] / f.b[0], f.c[0] / f.d[0]};
}

CurveJet curve_jet(const PlanData& plan, double t) {
  // Run de Casteljau until three points remain, then read the jet off them (as bernstein_jet).
  const int n = plan.degree;
  Four f;
  load(plan, f);
  de_casteljau(f, n, n - 2, t);
  const auto jet = [&](const std::array<double, kMaxDegree + 1>& b) {
    return bernstein_jet_from_last_points(n, t, b[0], b[1], n >= 2 ? b[2] : 0.0);  // b[2] unset at n = 1
  };
  const BernsteinJet N = jet(f.a), D = jet(f.b), M = jet(f.c), E = jet(f.d);
  CurveJet j;
  j.x = N.value / D.value;
  j.dx = (N.first - D.first * j.x) / D.value;
  j.ddx = (N.second - 2 * D.first * j.dx - D.second * j.x) / D.value;
  j.y = M.value / E.value;
  j.dy = (M.first - E.first * j.y) / E.value;
  j.ddy = (M.second - 2 * E.first * j.dy - E.second * j.y) / E.value;
  return j;
}

double distance(const PlanData& plan, double u0, double v0, double t) {
  const auto p = curve_point(plan, t);
  return length(p[0] - u0, p[1] - v0);
}

Refined refine_parameter(const PlanData& plan, double u0, double v0, double t0, bool stay_on_segment) {
  constexpr double kEpsilon = std::numeric_limits<double>::epsilon();
  if (!std::isfinite(t0)) return {t0, std::nan("")};
  double t = stay_on_segment ? std::clamp(t0, 0.0, 1.0) : t0;
  // d is |P(t) - P0| at the current t whenever `d_current`; the jet at t gives it for free.
  double d = 0.0;
  bool d_current = false;
  for (int iteration = 0; iteration < kNewtonMaxIterations; ++iteration) {
    const CurveJet j = curve_jet(plan, t);
    const double ex = j.x - u0, ey = j.y - v0;
    d = length(ex, ey);
    d_current = true;
    if (!std::isfinite(d)) return {t, d};
    const double g1 = ex * j.dx + ey * j.dy;                          // f(t)
    const double speed2 = j.dx * j.dx + j.dy * j.dy;
    const double slope = speed2 + ex * j.ddx + ey * j.ddy;            // f'(t)
    // Where the distance is locally concave (far from the curve, inside the evolute) Newton would
    // head for a maximum; Gauss-Newton (f' ~ |P'|^2) still descends.
    double g2 = slope;
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
      // The last step (kNewtonFinalStep says why), not cut short by the clamp: the distance at the
      // new t by the first-order update of the one at hand.
      // Where the curve bends hard for its size (a tiny or huge weight makes |P''| ~ 1e24), s^2 |P''|
      // is not below the rounding, and the update would misstate the distance: measured instead.
      const double s = next - t;
      if (moved <= kNewtonFinalStep && next == t + step && slope >= 0.5 * speed2 &&
          s * s * (std::abs(j.ddx) + std::abs(j.ddy)) <= kEpsilon) {
        return {next, length(ex + j.dx * s, ey + j.dy * s)};
      }
      // Converged when the step moves t by a few ulps: d, measured at the t before it, is then
      // |P(t) - P0| to rounding (it differs by at most |P'| moved), and measuring it again at the
      // new t would cost a third of the refinement of an on-curve point; unless the curve is so
      // fast there (|P'| ~ 1e12 next to a tiny weight) that those ulps of t move P by more than
      // a few ulps of its size: then it is measured at the new t.
      t = next;
      if (moved <= kNewtonStopUlps * kEpsilon * std::max(1.0, std::abs(t)))
        return {t, moved * moved * speed2 <= 16 * kEpsilon * kEpsilon ? d : distance(plan, u0, v0, t)};
      d_current = false;
      continue;
    }
    bool accepted = false;
    for (int halving = 0; halving < kNewtonMaxHalvings; ++halving) {
      double next = t + step;
      if (stay_on_segment) next = std::clamp(next, 0.0, 1.0);
      const double dn = distance(plan, u0, v0, next);
      if (dn <= d) {
        accepted = next != t;
        const double moved = std::abs(next - t);
        t = next;
        d = dn;
        if (moved <= kNewtonStopUlps * kEpsilon * std::max(1.0, std::abs(t))) return {t, d};
        break;
      }
      step *= 0.5;
    }
    if (!accepted) break;
  }
  return {t, d_current ? d : distance(plan, u0, v0, t)};
}

void horner_coefficients(PlanData& plan) {
  // Per polynomial c (degree n): c_i C(n,i); n (c_{i+1} - c_i) C(n-1,i); n (n-1) (c_{i+2} - 2 c_{i+1}
  // + c_i) C(n-2,i): the value, first and second derivative as sums of c'_i (1-t)^(m-i) t^i.
  const int n = plan.degree;
  plan.horner.clear();
  for (const std::vector<double>* c : {&plan.x_num, &plan.x_den, &plan.y_num, &plan.y_den}) {
    const std::vector<double>& p = *c;
    for (int i = 0; i <= n; ++i) plan.horner.push_back(p[i] * binomial(n, i));
    for (int i = 0; i < n; ++i) plan.horner.push_back(n * (p[i + 1] - p[i]) * binomial(n - 1, i));
    for (int i = 0; i + 1 < n; ++i) plan.horner.push_back(n * (n - 1.0) * (p[i + 2] - 2 * p[i + 1] + p[i]) * binomial(n - 2, i));
  }
}

namespace {

// curve_jet_horner's work, the second derivatives only where kSecond.
template <bool kSecond>
CurveJet horner_jet(const PlanData& plan, double t) {
  // sum a_i (1-t)^(m-i) t^i = (1-t)^m sum a_i r^i with r = t / (1-t) for t <= 1/2, and
  // t^m sum a_i r^(m-i) with r = (1-t) / t above: Horner's rule in r <= 1, O(m) instead of de
  // Casteljau's O(m^2). The four polynomials go through each level together (four independent
  // chains of multiply-adds, not one after another).
  const int n = plan.degree;
  const bool low = t <= 0.5;
  const double r = low ? t / (1 - t) : (1 - t) / t, base = low ? 1 - t : t;
  double base_n2 = 1.0;  // base^(n-2), then base^(n-1) and base^n (n >= 1)
  for (int k = 2; k < n; ++k) base_n2 *= base;
  const double base_n1 = n >= 2 ? base_n2 * base : 1.0, base_n = n >= 2 ? base_n1 * base : base;
  // Level 0: the values (degree n), 1: first derivatives (n - 1), 2: second (n - 2); polynomial p
  // of level j starts at horner[p * 3n + offset_j].
  std::array<std::array<double, 4>, 3> jet{};
  const double* a = plan.horner.data();
  const int offsets[3] = {0, n + 1, 2 * n + 1}, stride = 3 * n;
  const double scale[3] = {base_n, base_n1, base_n2};
  constexpr int kLevels = kSecond ? 3 : 2;
  for (int level = 0; level < kLevels && level <= n; ++level) {
    const int m = n - level;
    std::array<double, 4> value;
    for (int p = 0; p < 4; ++p) value[p] = a[p * stride + offsets[level] + (low ? m : 0)];
    for (int k = 1; k <= m; ++k)
      for (int p = 0; p < 4; ++p) value[p] = value[p] * r + a[p * stride + offsets[level] + (low ? m - k : k)];
    for (int p = 0; p < 4; ++p) jet[level][p] = value[p] * scale[level];
  }
  const auto quotient = [&](int num, int den, double& x, double& dx, double& ddx) {
    x = jet[0][num] / jet[0][den];
    dx = (jet[1][num] - jet[1][den] * x) / jet[0][den];
    if constexpr (kSecond) ddx = (jet[2][num] - 2 * jet[1][den] * dx - jet[2][den] * x) / jet[0][den];
  };
  CurveJet j{};
  quotient(0, 1, j.x, j.dx, j.ddx);
  quotient(2, 3, j.y, j.dy, j.ddy);
  return j;
}

}  // namespace

CurveJet curve_jet_horner(const PlanData& plan, double t) { return horner_jet<true>(plan, t); }

CurveJet curve_slope_horner(const PlanData& plan, double t) { return horner_jet<false>(plan, t); }

namespace {
// cos(P - P0, P') <= kStationaryCosine, from P = (x, y) and P' = (dx, dy).
bool stationary_slope(double x, double y, double dx, double dy, double u0, double v0, double distance) {
  const double along = (x - u0) * dx + (y - v0) * dy;
  return std::abs(along) <= kStationaryCosine * distance * length(dx, dy);
}
}  // namespace

bool stationary_point(const PlanData& plan, double u0, double v0, double t, double distance) {
  const CurveJet jet = curve_slope_horner(plan, t);
  return stationary_slope(jet.x, jet.y, jet.dx, jet.dy, u0, v0, distance);
}

void stationary_point_lanes(const PlanData& plan, std::size_t count, const double* u, const double* v,
                            const double* t, const double* distance, std::uint8_t* stationary) {
  // P and P' of the lanes by the kernels' copy of curve_slope_horner (the same doubles), a chunk of
  // them at a time, then stationary_point's test on them.
  constexpr std::size_t kChunk = 64;
  std::array<double, kChunk> x, y, dx, dy;
  const kernels::RationalCurve curve = kernel_curve(plan, /*horner=*/true);
  for (std::size_t first = 0; first < count; first += kChunk) {
    const std::size_t lanes = std::min(kChunk, count - first);
    kernels::active_implementation().rational_slope(curve, lanes, t + first, x.data(), y.data(), dx.data(), dy.data());
    for (std::size_t k = 0; k < lanes; ++k) {
      const std::size_t l = first + k;
      stationary[l] = stationary_slope(x[k], y[k], dx[k], dy[k], u[l], v[l], distance[l]);
    }
  }
}

int nearest_sample_count(int degree) { return std::max(32, kNearestSamplesPerDegree * degree); }

double nearest_parameter_on_segment(const PlanData& plan, double u0, double v0, double hint) {
  // The certified search first: it proves its answer the nearest point for nearly every point.
  // Sampling stands behind it for the rest (a sign it cannot trust, a piece it could not split
  // into parts of one sign change).
  // A point so far that the distances to the curve's points agree to every bit is looked at from
  // a stand-in on its ray at kFarStandIn (as a far point is, pipeline/far_point.cpp), where they
  // still tell the curve's points apart.
  const double far = std::max(std::abs(u0), std::abs(v0));
  if (far > kFarEqualDistances && std::isfinite(far)) {
    const double shrink = kFarStandIn / std::hypot(u0, v0);
    u0 *= shrink;
    v0 *= shrink;
  }
  const NearestOnSegment proved = certified_nearest_on_segment(plan, u0, v0, hint);
  return proved.certified ? proved.t : nearest_parameter_by_sampling(plan, u0, v0, hint);
}

double nearest_parameter_by_sampling(const PlanData& plan, double u0, double v0, double hint) {
  // Fixed-size workspaces: the search runs per point, so it must not allocate.
  constexpr int kMaxSamples = kNearestSamplesPerDegree * kMaxDegree;
  const int samples = nearest_sample_count(plan.degree);
  std::array<double, kMaxSamples + 1> d;
  // The same numbers as distance() at k / S: P(k / S) was computed by curve_point in make_plan.
  const double* p = plan.nearest_samples.data();
  for (int k = 0; k <= samples; ++k) d[k] = length(p[2 * k] - u0, p[2 * k + 1] - v0);
  // Local minima of the sampled distance; each marks a basin to refine in (the best kMaxBasins).
  constexpr int kMaxBasins = kNearestMaxBasins;
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
    const Refined r = refine_parameter(plan, u0, v0, t0, /*stay_on_segment=*/true);
    if (r.distance < best_d) { best_d = r.distance; best_t = r.t; }
  };
  // One at a time, not through the lane-batched kernel: 2-4 starts fill few lanes, and a group
  // runs as long as its slowest lane (docs/accuracy-model.md, "The nearest point of the segment").
  if (hint >= 0.0 && hint <= 1.0) consider(hint);
  for (int i = 0; i < found; ++i) consider(static_cast<double>(minima[i].second) / samples);
  return best_t;
}

}  // namespace bezinv::detail
