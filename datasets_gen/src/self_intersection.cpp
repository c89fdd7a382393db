#include "bezinv/datasets/self_intersection.hpp"

#include <cmath>
#include <numbers>
#include <stdexcept>
#include <string>

#include "bezinv/datasets/off_curve_points.hpp"
#include "bezinv/datasets/on_curve_points.hpp"
#include "bezinv/datasets/random_numbers.hpp"
#include "bezinv/datasets/reference_evaluation.hpp"
#include "linear_condition.hpp"

namespace bezinv::datasets {
namespace {

constexpr int kAttempts = 200;
constexpr double kCoincidence = 1e-14;    // |P(t1) - P(t2)| / diagonal
constexpr Real kMinSine = 0.2588190451L;  // sin 15 degrees
constexpr Real kMinSpeed = 0.01L;         // / diagonal

using detail::beta;

// Makes num(t1)/den(t1) = num(t2)/den(t2): g_i = beta_i(t1) den(t2) - beta_i(t2) den(t1).
void enforce_equal_values(std::vector<double>& num, const std::vector<double>& den, Real t1, Real t2) {
  const int n = static_cast<int>(num.size()) - 1;
  Real d1 = 0, d2 = 0;
  for (int i = 0; i <= n; ++i) { d1 += den[i] * beta(n, i, t1); d2 += den[i] * beta(n, i, t2); }
  std::vector<Real> g(n + 1);
  for (int i = 0; i <= n; ++i) g[i] = beta(n, i, t1) * d2 - beta(n, i, t2) * d1;
  detail::enforce_linear_condition(num, g);
}

}  // namespace

Curve with_self_intersection(CurveKind kind, int degree, double t1, double t2, std::mt19937_64& rng,
                             ControlPolygon polygon) {
  if (degree < 3) throw std::invalid_argument("with_self_intersection: degree must be at least 3");
  if (!(0 <= t1 && t1 < t2 && t2 <= 1)) throw std::invalid_argument("with_self_intersection: need 0 <= t1 < t2 <= 1");
  for (int attempt = 0; attempt < kAttempts; ++attempt) {
    Curve c = random_curve(kind, degree, rng, polygon);
    enforce_equal_values(c.x_num, c.x_den, t1, t2);
    enforce_equal_values(c.y_num, c.y_den, t1, t2);
    c.id += "-crossing";

    const double diagonal = control_diagonal(c);
    const auto j1 = reference_jet(c, t1), j2 = reference_jet(c, t2);
    if (!(distance(j1.p, j2.p) <= kCoincidence * diagonal)) continue;
    const Real s1 = std::hypot(j1.d1.x, j1.d1.y), s2 = std::hypot(j2.d1.x, j2.d1.y);
    if (!(s1 > kMinSpeed * diagonal && s2 > kMinSpeed * diagonal)) continue;
    const Real sine = std::abs(j1.d1.x * j2.d1.y - j1.d1.y * j2.d1.x) / (s1 * s2);
    if (sine < kMinSine) continue;
    const CurveSampling sampling(c);
    if (!isolated(sampling, rounded(j1.p), {t1, t2})) continue;
    return c;
  }
  throw std::runtime_error("with_self_intersection: no verified curve of degree " + std::to_string(degree) +
                           " in " + std::to_string(kAttempts) + " attempts");
}

std::vector<KnownPoint> crossing_points(const CurveSampling& sampling, double t1, double t2, int count,
                                        double radius_relative, std::mt19937_64& rng) {
  const Curve& curve = sampling.curve();
  std::vector<KnownPoint> points;
  auto add = [&](RealPoint centre, Real radius, Real angle) {
    KnownPoint k;
    k.point = rounded({centre.x + radius * std::cos(angle), centre.y + radius * std::sin(angle)});
    const RealPoint p{k.point.x, k.point.y};
    const Real a = radius == 0 ? t1 : nearest_parameter_near(curve, p, t1);
    const Real b = radius == 0 ? t2 : nearest_parameter_near(curve, p, t2);
    if (!(a >= 0 && b <= 1 && a < b)) return;
    const auto ja = reference_jet(curve, a), jb = reference_jet(curve, b);
    k.t = static_cast<double>(a);
    k.t2 = static_cast<double>(b);
    k.distance = static_cast<double>(std::max(distance(ja.p, k.point), distance(jb.p, k.point)));
    k.speed = static_cast<double>(std::min(std::hypot(ja.d1.x, ja.d1.y), std::hypot(jb.d1.x, jb.d1.y)));
    k.scale = static_cast<double>(std::max(evaluation_scale(curve, a), evaluation_scale(curve, b)));
    if (isolated(sampling, k.point, {k.t, k.t2})) points.push_back(k);
  };
  const RealPoint centre = reference_point(curve, static_cast<Real>(t1));
  add(centre, 0, 0);
  const Real radius = radius_relative * sampling.diagonal();
  for (int i = 0; i < count; ++i) add(centre, radius, uniform(rng, 0.0, 2 * std::numbers::pi));
  return points;
}

}  // namespace bezinv::datasets
