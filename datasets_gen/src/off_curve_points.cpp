#include "bezinv/datasets/off_curve_points.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>

#include "bezinv/datasets/on_curve_points.hpp"
#include "bezinv/datasets/random_numbers.hpp"
#include "bezinv/datasets/reference_evaluation.hpp"

namespace bezinv::datasets {
namespace {

// The offset may reach this fraction of the radius of curvature on its side: at d = rho the
// distance function is flat at t0 (the centre of curvature), below it t0 is a strict local minimum.
constexpr Real kCurvatureFraction = 0.5L;

// Fraction of candidates placed beyond an end of the segment.
constexpr int kEndOneIn = 8;

Real hypot(RealPoint v) { return std::hypot(v.x, v.y); }

}  // namespace

Real nearest_parameter_near(const Curve& curve, RealPoint p, Real t0) {
  Real t = t0;
  for (int iteration = 0; iteration < 50; ++iteration) {
    const auto j = reference_jet(curve, t);
    const Real ex = j.p.x - p.x, ey = j.p.y - p.y;
    const Real f = ex * j.d1.x + ey * j.d1.y;
    const Real df = j.d1.x * j.d1.x + j.d1.y * j.d1.y + ex * j.d2.x + ey * j.d2.y;
    if (!(df > 0)) break;
    const Real step = f / df;
    t -= step;
    if (std::abs(step) <= 1e-18L * std::max<Real>(1, std::abs(t))) break;
  }
  return t;
}

std::vector<KnownPoint> normal_offset_points(const CurveSampling& sampling, int count, double min_relative,
                                             double max_relative, std::mt19937_64& rng) {
  const Curve& curve = sampling.curve();
  const Real diagonal = sampling.diagonal();
  const Real isolation = kIsolation * diagonal;
  std::vector<KnownPoint> points;
  for (int attempt = 0; attempt < kAttemptsPerPoint * count && static_cast<int>(points.size()) < count; ++attempt) {
    const bool at_end = uniform_int(rng, 0, kEndOneIn - 1) == 0;
    const double t0 = at_end ? static_cast<double>(uniform_int(rng, 0, 1)) : uniform(rng, 0.0, 1.0);
    const Real d = log_uniform(rng, min_relative, max_relative) * diagonal;
    const Real side = uniform_int(rng, 0, 1) == 0 ? -1.0L : 1.0L;
    const auto j = reference_jet(curve, t0);
    const Real speed = hypot(j.d1);
    if (!(speed > 0)) continue;
    const RealPoint tangent{j.d1.x / speed, j.d1.y / speed};
    const RealPoint normal{-tangent.y, tangent.x};
    RealPoint direction;
    if (at_end) {
      // Outward tangent turned by 20..70 degrees towards one side: the segment's nearest point is
      // the end, the extension passes at about d sin(angle).
      const Real outward = t0 == 0.0 ? -1.0L : 1.0L;
      const Real angle = uniform(rng, 20.0, 70.0) * std::numbers::pi_v<Real> / 180;
      direction = {outward * std::cos(angle) * tangent.x + side * std::sin(angle) * normal.x,
                   outward * std::cos(angle) * tangent.y + side * std::sin(angle) * normal.y};
    } else {
      // Signed curvature towards `side`: positive when the normal offset heads for the centre.
      const Real curvature = side * (j.d1.x * j.d2.y - j.d1.y * j.d2.x) / (speed * speed * speed);
      if (curvature > 0 && d * curvature >= kCurvatureFraction) continue;
      direction = {side * normal.x, side * normal.y};
    }
    KnownPoint k;
    k.point = rounded({j.p.x + d * direction.x, j.p.y + d * direction.y});
    const RealPoint p{k.point.x, k.point.y};
    // The truth is for the point as rounded: re-solve the nearest-point condition from t0.
    const Real t = at_end ? static_cast<Real>(t0) : nearest_parameter_near(curve, p, t0);
    // Rounding moves the foot of the normal by ~1e-16 / speed; a jump means Newton left the basin.
    if (!(t >= 0 && t <= 1) || std::abs(t - t0) > 1e-3L) continue;
    const auto jt = reference_jet(curve, t);
    const Real dt = distance(jt.p, k.point);

    // The nearest point of the segment is t, clearly ahead of every other local minimum.
    const Real others = std::max((1 + kNearestGap) * dt, isolation);
    bool own_found = false, clear = true;
    for (const auto& m : sampling.segment_minima(p, 2 * others)) {
      // The refined minimum of the own basin lands within ~1e-9 of t (a smooth
      // minimum is resolved to about sqrt(2^-64) in t).
      if (std::abs(m.t - t) <= 1e-6L) { own_found = true; continue; }
      clear = clear && m.distance >= others;
    }
    // The extension stays away too (else the point would be within reach of outside_segment).
    for (const auto& m : sampling.line_minima(p, 2 * isolation))
      if (!m.on_segment) clear = clear && m.distance > isolation;
    if (!own_found || !clear) continue;

    k.t = static_cast<double>(t);
    k.distance = static_cast<double>(dt);
    k.speed = static_cast<double>(hypot(jt.d1));
    k.scale = static_cast<double>(evaluation_scale(curve, t));
    points.push_back(k);
  }
  return points;
}

}  // namespace bezinv::datasets
