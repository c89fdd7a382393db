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
constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

// Brent's minimization in the angle: stops when the bracket is within kAngleTolerance (relative,
// about 2^-50: the squared distance resolves the angle of a minimum to about the square root of
// long double's 2^-64, and better where the minimum is a zero, a point on the curve), or after
// kBrentIterations evaluations (golden section alone would take ~70 from two sample spacings).
constexpr Real kAngleTolerance = 0x1p-50L;
constexpr int kBrentIterations = 200;

// The sampling is made denser where a chord on the segment is longer than kLongChord times the
// typical one (diagonal / (samples per degree x degree)), down to kDensifyDepth halvings.
constexpr Real kLongChord = 8;
constexpr int kDensifyDepth = 24;

}  // namespace

Real parameter_of_angle(Real a) {
  const Real c = std::cos(a), s = std::sin(a);
  if (c + s == 0) return kInf;
  return s / (c + s);
}

CurveSampling::CurveSampling(Curve curve, int samples_per_degree)
    : curve_(std::move(curve)), diagonal_(control_diagonal(curve_)) {
  // Uniform in the angle, then denser on the segment wherever the curve moves fast: between two
  // samples of [0, pi/2] whose chord is longer than kLongChord typical chords, the midpoint is
  // added, again and again (extreme weights crowd a long stretch of the curve into a sliver of
  // parameter next to an end, which uniform samples would step over).
  const int uniform = 2 * samples_per_degree * std::max(curve_.degree(), 1);
  const Real long_chord = kLongChord * diagonal_ / (samples_per_degree * std::max(curve_.degree(), 1));
  auto sample = [&](Real a) {
    const auto p = point_at_angle(a);
    angles_.push_back(a);
    samples_.push_back(p ? Sample{*p, true} : Sample{});
  };
  auto uniform_angle = [&](int k) { return 2 * k == uniform ? kPi / 2 : kPi * k / uniform; };
  sample(uniform_angle(0));
  for (int k = 1; k < uniform; ++k) {
    const Real a = uniform_angle(k);
    if (2 * k <= uniform) densify(angles_.back(), samples_.back(), a, point_at_angle(a), long_chord, 0);
    if (2 * k == uniform) last_ = static_cast<int>(angles_.size());
    sample(a);
  }
  count_ = static_cast<int>(angles_.size());
  for (const Sample& s : samples_)
    if (s.valid) {
      origin_ = s.p;
      break;
    }
  x_.resize(count_);
  y_.resize(count_);
  chord_.resize(count_);
  for (int k = 0; k < count_; ++k) {
    x_[k] = samples_[k].valid ? static_cast<double>(samples_[k].p.x - origin_.x) : kNaN;
    y_[k] = samples_[k].valid ? static_cast<double>(samples_[k].p.y - origin_.y) : kNaN;
    Real chord = 0;
    for (int j : {(k + count_ - 1) % count_, (k + 1) % count_})
      chord = std::max(chord, samples_[j].valid && samples_[k].valid ? distance(samples_[j].p, samples_[k].p) : kInf);
    chord_[k] = chord;
  }
}

void CurveSampling::squared_distances(RealPoint p0, std::vector<double>& d2) const {
  const double x0 = static_cast<double>(p0.x - origin_.x), y0 = static_cast<double>(p0.y - origin_.y);
  d2.resize(count_);
  for (int k = 0; k < count_; ++k) {
    const double dx = x_[k] - x0, dy = y_[k] - y0, d = dx * dx + dy * dy;
    d2[k] = d == d ? d : std::numeric_limits<double>::infinity();  // NaN: not a point
  }
}

void CurveSampling::densify(Real a0, Sample s0, Real a1, std::optional<RealPoint> p1, Real long_chord, int depth) {
  if (depth >= kDensifyDepth || !s0.valid || !p1 || !(distance(s0.p, *p1) > long_chord)) return;
  const Real middle = (a0 + a1) / 2;
  const auto p = point_at_angle(middle);
  densify(a0, s0, middle, p, long_chord, depth + 1);
  angles_.push_back(middle);
  samples_.push_back(p ? Sample{*p, true} : Sample{});
  densify(middle, samples_.back(), a1, p1, long_chord, depth + 1);
}

// The sample's angle; next to the ends of the closed line, the neighbour's angle a turn away.
Real CurveSampling::angle(int k) const {
  if (k < 0) return angles_[count_ + k] - kPi;
  if (k >= count_) return angles_[k - count_] + kPi;
  return angles_[k];
}

std::optional<RealPoint> CurveSampling::point_at_angle(Real a) const {
  // The two ends of the segment exactly (cos(pi/2) is not 0 in floating point).
  if (a == 0) return reference_point(curve_, 1.0L, 0.0L);
  if (a == kPi / 2) return reference_point(curve_, 0.0L, 1.0L);
  return reference_point(curve_, std::cos(a), std::sin(a));
}

DistanceMinimum CurveSampling::refine(RealPoint p0, Real a_lo, Real a_hi, Real sampled_distance,
                                      Real sampled_angle) const {
  // Brent's minimization (golden section, with parabolic steps where they are safe) of the squared
  // distance: near a minimum it is a parabola in the angle, on the curve (distance ~0) and off it,
  // so parabolic steps converge in a few evaluations where golden section alone needs ~70.
  auto f = [&](Real a) {
    const auto p = point_at_angle(a);
    if (!p) return kInf;
    const Real dx = p->x - p0.x, dy = p->y - p0.y;
    return dx * dx + dy * dy;
  };
  constexpr Real kGolden = 0.3819660112501051518L;  // (3 - sqrt 5) / 2
  Real lo = a_lo, hi = a_hi;
  Real x = sampled_angle, w = x, v = x;
  Real fx = f(x), fw = fx, fv = fx;
  Real step = 0, previous = 0;  // the last step and the one before it
  for (int iteration = 0; iteration < kBrentIterations; ++iteration) {
    const Real middle = (lo + hi) / 2, tol1 = kAngleTolerance * (1 + std::abs(x)), tol2 = 2 * tol1;
    if (std::abs(x - middle) <= tol2 - (hi - lo) / 2) break;
    bool golden = true;
    if (std::abs(previous) > tol1 && std::isfinite(fx) && std::isfinite(fw) && std::isfinite(fv)) {
      // The parabola through (x, fx), (w, fw), (v, fv): its vertex is x + p / q.
      Real r = (x - w) * (fx - fv), q = (x - v) * (fx - fw), p = (x - v) * q - (x - w) * r;
      q = 2 * (q - r);
      if (q > 0) p = -p;
      q = std::abs(q);
      // Accepted only inside the bracket and shorter than half the step before last (else the
      // parabola is not converging).
      if (std::abs(p) < std::abs(q * previous / 2) && p > q * (lo - x) && p < q * (hi - x)) {
        previous = step;
        step = p / q;
        const Real u = x + step;
        if (u - lo < tol2 || hi - u < tol2) step = middle > x ? tol1 : -tol1;
        golden = false;
      }
    }
    if (golden) {
      previous = x >= middle ? lo - x : hi - x;
      step = kGolden * previous;
    }
    const Real u = std::abs(step) >= tol1 ? x + step : x + (step > 0 ? tol1 : -tol1);
    const Real fu = f(u);
    if (fu <= fx) {
      (u >= x ? lo : hi) = x;
      v = w, fv = fw;
      w = x, fw = fx;
      x = u, fx = fu;
    } else {
      (u < x ? lo : hi) = u;
      if (fu <= fw || w == x) {
        v = w, fv = fw;
        w = u, fw = fu;
      } else if (fu <= fv || v == x || v == w) {
        v = u, fv = fu;
      }
    }
  }
  Real best_a = x, best = std::sqrt(fx);
  if (sampled_distance <= best) { best = sampled_distance; best_a = sampled_angle; }
  DistanceMinimum m;
  m.distance = best;
  m.t = best_a == 0 ? 0.0L : best_a == kPi / 2 ? 1.0L : parameter_of_angle(best_a);
  m.on_segment = m.t >= 0 && m.t <= 1;
  return m;
}

std::vector<DistanceMinimum> CurveSampling::line_minima(RealPoint p0, Real cutoff) const {
  thread_local std::vector<double> d2;
  squared_distances(p0, d2);
  std::vector<DistanceMinimum> minima;
  for (int k = 0; k < count_; ++k) {
    // The line is closed: a = pi is a = 0 again ([cos : sin] is projective).
    const int before = (k + count_ - 1) % count_, after = (k + 1) % count_;
    if (!std::isfinite(d2[k]) || !(d2[k] <= d2[before] && d2[k] < d2[after])) continue;
    const Real d = distance(samples_[k].p, p0), chord = chord_[k];
    if (d - chord > cutoff) {
      const Real a = angle(k);
      const Real t = a == kPi / 2 ? 1.0L : parameter_of_angle(a);
      minima.push_back({t, d - chord, t >= 0 && t <= 1});
      continue;
    }
    minima.push_back(refine(p0, angle(k - 1), angle(k + 1), d, angle(k)));
  }
  return minima;
}

std::vector<DistanceMinimum> CurveSampling::segment_minima(RealPoint p0, Real cutoff) const {
  const int last = last_;  // a = pi/2, t = 1
  thread_local std::vector<double> d2;
  squared_distances(p0, d2);
  std::vector<DistanceMinimum> minima;
  for (int k = 0; k <= last; ++k) {
    const bool left = k == 0 || d2[k] <= d2[k - 1];
    const bool right = k == last || d2[k] < d2[k + 1];
    if (!std::isfinite(d2[k]) || !left || !right) continue;
    const int lo = std::max(k - 1, 0), hi = std::min(k + 1, last);
    Real chord = 0;
    for (int j : {lo, hi}) chord = std::max(chord, distance(samples_[j].p, samples_[k].p));
    const Real d = distance(samples_[k].p, p0);
    if (d - chord > cutoff) {
      minima.push_back({k == last ? 1.0L : parameter_of_angle(angle(k)), d - chord, true});
      continue;
    }
    DistanceMinimum m = refine(p0, angle(lo), angle(hi), d, angle(k));
    m.on_segment = true;
    minima.push_back(m);
  }
  return minima;
}

}  // namespace bezinv::datasets
