#include "formula/homogeneous_curve.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <utility>
#include <numbers>

#include "bernstein_arithmetic.hpp"
#include "bezinv/bernstein.hpp"

namespace bezinv::detail {
namespace {

std::array<double, 3> unit(std::array<double, 3> h) {
  const double m = std::max({std::abs(h[0]), std::abs(h[1]), std::abs(h[2])});
  if (m > 0.0 && std::isfinite(m))
    for (double& e : h) e /= m;
  return h;
}

}  // namespace

FrameCurve formula_curve(const PlanData& plan) {
  HomogeneousCurve curve;
  if (plan.common_denominator)
    curve = {plan.x_num, plan.y_num, plan.x_den};
  else
    curve = {product(plan.x_num, plan.y_den), product(plan.y_num, plan.x_den), product(plan.x_den, plan.y_den)};
  // The box of the segment: from dense samples (the control points' box can be much larger than
  // the curve's for extreme weights).
  constexpr int kBoxSamples = 256;
  double u_lo = std::numeric_limits<double>::infinity(), u_hi = -u_lo, v_lo = u_lo, v_hi = -u_lo;
  for (int k = 0; k <= kBoxSamples; ++k) {
    const auto h = curve.at(static_cast<double>(k) / kBoxSamples);
    const double u = h[0] / h[2], v = h[1] / h[2];
    u_lo = std::min(u_lo, u), u_hi = std::max(u_hi, u), v_lo = std::min(v_lo, v), v_hi = std::max(v_hi, v);
  }
  // Half-widths, none below 1e-3 of the other (a straight segment has a box of width 0).
  double hu = 0.5 * (u_hi - u_lo), hv = 0.5 * (v_hi - v_lo);
  const double floor = 1e-3 * std::max(hu, hv);
  hu = std::max(hu, floor), hv = std::max(hv, floor);
  if (!(hu > 0.0)) hu = hv = 1.0;  // a curve of one point (the plan refuses to invert on it)
  const double cu = 0.5 * (u_lo + u_hi), cv = 0.5 * (v_lo + v_hi);
  // U' = (U - cu W) / hu, V' = (V - cv W) / hv: linear in the coefficients.
  for (std::size_t i = 0; i < curve.w.size(); ++i) {
    curve.u[i] = (curve.u[i] - cu * curve.w[i]) / hu;
    curve.v[i] = (curve.v[i] - cv * curve.w[i]) / hv;
  }
  // The plan's frame is u = R (x - c) / s; this one is ((u - cu) / hu, (v - cv) / hv), i.e. centred
  // at the input point of plan-frame (cu, cv), scales s hu and s hv.
  PlaneFrame plan_frame{plan.centre, plan.scale, plan.scale, plan.cos_rotation, plan.sin_rotation};
  PlaneFrame frame = plan_frame;
  frame.centre = plan_frame.from_frame(cu, cv);
  frame.scale_u = plan.scale * hu;
  frame.scale_v = plan.scale * hv;
  return {std::move(curve), frame};
}

std::array<double, 3> HomogeneousCurve::at(double t) const {
  return unit({bernstein_value(u, t), bernstein_value(v, t), bernstein_value(w, t)});
}

std::array<double, 3> HomogeneousCurve::at_infinity() const {
  // The coefficient of t^k in the power basis is C(D, k) times the k-th forward difference of
  // the first k + 1 Bernstein coefficients; its rounding is bounded by the same sum of |p_i|.
  const int degree_d = degree();
  for (int k = degree_d; k >= 1; --k) {
    std::array<double, 3> lead{}, bound{};
    const std::vector<double>* polys[3] = {&u, &v, &w};
    for (int c = 0; c < 3; ++c) {
      double sum = 0.0, size = 0.0;
      for (int i = 0; i <= k; ++i) {
        const double term = binomial(k, i) * (*polys[c])[static_cast<std::size_t>(i)];
        sum += ((k - i) % 2 == 0 ? term : -term);
        size += std::abs(term);
      }
      lead[static_cast<std::size_t>(c)] = sum;
      bound[static_cast<std::size_t>(c)] = size;
    }
    const double size = std::max({bound[0], bound[1], bound[2]});
    // Negligible: within rounding of what the differences cancel (64 ulps of the terms).
    if (std::max({std::abs(lead[0]), std::abs(lead[1]), std::abs(lead[2])}) > 64.0 * 0x1p-52 * size) return unit(lead);
  }
  return at(0.0);  // a constant curve (the plan refuses it before this is asked)
}

std::array<double, 3> HomogeneousCurve::at_homogeneous(double a, double b) const {
  auto casteljau = [&](std::vector<double> c) {
    for (std::size_t r = 1; r < c.size(); ++r)
      for (std::size_t i = 0; i + r < c.size(); ++i) c[i] = a * c[i] + b * c[i + 1];
    return c[0];
  };
  return unit({casteljau(u), casteljau(v), casteljau(w)});
}

std::vector<CurveSample> curve_samples(const HomogeneousCurve& curve, int count) {
  std::vector<CurveSample> out;
  const int on_segment = (count + 1) / 2, beyond = count - on_segment;
  for (int k = 0; k < on_segment; ++k) {
    const double t = 0.5 - 0.5 * std::cos(std::numbers::pi * (k + 0.5) / on_segment);
    const double size = std::hypot(1.0 - t, t);
    out.push_back({(1.0 - t) / size, t / size, curve.at(t)});
  }
  // The rest of the projective line: angles in (pi/2, pi), (a, b) = (cos, sin), at Chebyshev
  // points of that interval.
  for (int k = 0; k < beyond; ++k) {
    const double angle = std::numbers::pi * (0.75 - 0.25 * std::cos(std::numbers::pi * (k + 0.5) / beyond));
    const double a = std::cos(angle), b = std::sin(angle);
    out.push_back({a, b, curve.at_homogeneous(a, b)});
  }
  return out;
}

}  // namespace bezinv::detail
