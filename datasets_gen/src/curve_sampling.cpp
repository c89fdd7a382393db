#include "bezinv/datasets/curve_sampling.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>
#include <utility>

namespace bezinv::datasets {
namespace {

constexpr Real kPi = std::numbers::pi_v<Real>;
constexpr Real kInf = std::numeric_limits<Real>::infinity();

// Golden-section steps: the bracket (two sample spacings, >= 1e-5 rad) shrinks by 0.618 per step,
// to below long double resolution after 80.
constexpr int kGoldenSteps = 80;

}  // namespace

Real parameter_of_angle(Real a) {
  const Real c = std::cos(a), s = std::sin(a);
  if (c + s == 0) return kInf;
  return s / (c + s);
}

CurveSampling::CurveSampling(Curve curve, int samples_per_degree)
    : curve_(std::move(curve)), diagonal_(control_diagonal(curve_)) {
  count_ = 2 * samples_per_degree * std::max(curve_.degree(), 1);
  samples_.resize(count_);
  for (int k = 0; k < count_; ++k) {
    const auto p = point_at_angle(angle(k));
    if (p) samples_[k] = {*p, true};
  }
}

Real CurveSampling::angle(int k) const {
  if (2 * k == count_) return kPi / 2;  // exactly, so point_at_angle recognizes t = 1
  return kPi * k / count_;
}

std::optional<RealPoint> CurveSampling::point_at_angle(Real a) const {
  // The two ends of the segment exactly (cos(pi/2) is not 0 in floating point).
  if (a == 0) return reference_point(curve_, 1.0L, 0.0L);
  if (a == kPi / 2) return reference_point(curve_, 0.0L, 1.0L);
  return reference_point(curve_, std::cos(a), std::sin(a));
}

DistanceMinimum CurveSampling::refine(RealPoint p0, Real a_lo, Real a_hi, Real sampled_distance,
                                      Real sampled_angle) const {
  auto f = [&](Real a) {
    const auto p = point_at_angle(a);
    return p ? distance(*p, p0) : kInf;
  };
  const Real g = (std::sqrt(5.0L) - 1) / 2;
  Real lo = a_lo, hi = a_hi;
  Real x1 = hi - g * (hi - lo), x2 = lo + g * (hi - lo);
  Real f1 = f(x1), f2 = f(x2);
  for (int step = 0; step < kGoldenSteps; ++step) {
    if (f1 <= f2) { hi = x2; x2 = x1; f2 = f1; x1 = hi - g * (hi - lo); f1 = f(x1); }
    else          { lo = x1; x1 = x2; f1 = f2; x2 = lo + g * (hi - lo); f2 = f(x2); }
  }
  Real best_a = f1 <= f2 ? x1 : x2, best = std::min(f1, f2);
  if (sampled_distance <= best) { best = sampled_distance; best_a = sampled_angle; }
  DistanceMinimum m;
  m.distance = best;
  m.t = best_a == 0 ? 0.0L : best_a == kPi / 2 ? 1.0L : parameter_of_angle(best_a);
  m.on_segment = m.t >= 0 && m.t <= 1;
  return m;
}

std::vector<DistanceMinimum> CurveSampling::line_minima(RealPoint p0, Real cutoff) const {
  std::vector<Real> d(count_);
  for (int k = 0; k < count_; ++k) d[k] = samples_[k].valid ? distance(samples_[k].p, p0) : kInf;
  std::vector<DistanceMinimum> minima;
  for (int k = 0; k < count_; ++k) {
    // The line is closed: a = pi is a = 0 again ([cos : sin] is projective).
    const int before = (k + count_ - 1) % count_, after = (k + 1) % count_;
    if (!std::isfinite(d[k]) || !(d[k] <= d[before] && d[k] < d[after])) continue;
    Real chord = 0;
    for (int j : {before, after})
      chord = std::max(chord, samples_[j].valid ? distance(samples_[j].p, samples_[k].p) : kInf);
    if (d[k] - chord > cutoff) {
      const Real a = angle(k);
      const Real t = a == kPi / 2 ? 1.0L : parameter_of_angle(a);
      minima.push_back({t, d[k] - chord, t >= 0 && t <= 1});
      continue;
    }
    minima.push_back(refine(p0, angle(k) - kPi / count_, angle(k) + kPi / count_, d[k], angle(k)));
  }
  return minima;
}

std::vector<DistanceMinimum> CurveSampling::segment_minima(RealPoint p0, Real cutoff) const {
  const int last = count_ / 2;  // a = pi/2, t = 1
  std::vector<Real> d(last + 1);
  for (int k = 0; k <= last; ++k) d[k] = samples_[k].valid ? distance(samples_[k].p, p0) : kInf;
  std::vector<DistanceMinimum> minima;
  for (int k = 0; k <= last; ++k) {
    const bool left = k == 0 || d[k] <= d[k - 1];
    const bool right = k == last || d[k] < d[k + 1];
    if (!std::isfinite(d[k]) || !left || !right) continue;
    const int lo = std::max(k - 1, 0), hi = std::min(k + 1, last);
    Real chord = 0;
    for (int j : {lo, hi}) chord = std::max(chord, distance(samples_[j].p, samples_[k].p));
    if (d[k] - chord > cutoff) {
      minima.push_back({k == last ? 1.0L : parameter_of_angle(angle(k)), d[k] - chord, true});
      continue;
    }
    DistanceMinimum m = refine(p0, angle(lo), angle(hi), d[k], angle(k));
    m.on_segment = true;
    minima.push_back(m);
  }
  return minima;
}

}  // namespace bezinv::datasets
