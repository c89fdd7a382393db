#include "bezinv/datasets/on_curve_points.hpp"

#include <algorithm>
#include <array>
#include <cmath>

#include "bezinv/datasets/random_numbers.hpp"
#include "bezinv/datasets/reference_evaluation.hpp"

namespace bezinv::datasets {
namespace {

// A minimum of the distance belongs to the branch at parameter `own` when it is this close to it
// (the refinement of a minimum lands within ~1e-9).
bool same_parameter(Real t, double own) { return std::abs(t - own) <= 1e-6L * std::max<Real>(1, std::abs(own)); }

// Denominators on the extension: at least this fraction of their largest coefficient.
constexpr Real kExtensionDenominator = 0.05L;

Real max_abs(const std::vector<double>& v) {
  Real m = 0;
  for (double x : v) m = std::max<Real>(m, std::abs(x));
  return m;
}

}  // namespace

Point on_curve(const Curve& curve, double t) { return rounded(reference_point(curve, static_cast<Real>(t))); }

KnownPoint known_on_curve(const Curve& curve, double t) {
  const auto j = reference_jet(curve, t);
  KnownPoint k;
  k.point = rounded(j.p);
  k.t = t;
  k.distance = static_cast<double>(distance(j.p, k.point));
  k.speed = static_cast<double>(std::hypot(j.d1.x, j.d1.y));
  k.scale = static_cast<double>(evaluation_scale(curve, t));
  return k;
}

bool isolated(const CurveSampling& sampling, Point point, std::initializer_list<double> own) {
  const Real margin = kIsolation * sampling.diagonal();
  std::vector<bool> found(own.size(), false);
  for (const auto& m : sampling.line_minima({point.x, point.y}, margin)) {
    bool is_own = false;
    std::size_t i = 0;
    for (double t : own) {
      if (same_parameter(m.t, t)) { is_own = true; found[i] = true; }
      ++i;
    }
    if (!is_own && !(m.distance > margin)) return false;
  }
  // Each own branch must show up as a minimum: otherwise sampling missed it and proves nothing.
  return std::all_of(found.begin(), found.end(), [](bool f) { return f; });
}

std::vector<KnownPoint> segment_points(const CurveSampling& sampling, int count, std::mt19937_64& rng) {
  std::vector<KnownPoint> points;
  for (int attempt = 0; attempt < kAttemptsPerPoint * count && static_cast<int>(points.size()) < count; ++attempt) {
    const double t = uniform(rng, 0.0, 1.0);
    KnownPoint k = known_on_curve(sampling.curve(), t);
    if (isolated(sampling, k.point, {t})) points.push_back(k);
  }
  return points;
}

std::vector<KnownPoint> end_points(const CurveSampling& sampling) {
  std::vector<KnownPoint> points;
  for (double t : {0.0, 1e-12, 1e-9, 1e-6, 1 - 1e-6, 1 - 1e-9, 1 - 1e-12, 1.0}) {
    KnownPoint k = known_on_curve(sampling.curve(), t);
    if (isolated(sampling, k.point, {t})) points.push_back(k);
  }
  return points;
}

std::vector<KnownPoint> extension_points(const CurveSampling& sampling, int count, std::mt19937_64& rng) {
  const Curve& curve = sampling.curve();
  const Real x_den_size = max_abs(curve.x_den), y_den_size = max_abs(curve.y_den);
  const Real margin = kIsolation * sampling.diagonal();
  std::vector<KnownPoint> points;
  for (int attempt = 0; attempt < kAttemptsPerPoint * count && static_cast<int>(points.size()) < count; ++attempt) {
    const double u = uniform(rng, 0.0, 0.58);
    const double t = u < 0.29 ? -0.01 - u : 1.01 + (u - 0.29);
    const Real c = 1 - static_cast<Real>(t), s = t;
    if (std::abs(homogeneous_value(curve.x_den, c, s).value) < kExtensionDenominator * x_den_size ||
        std::abs(homogeneous_value(curve.y_den, c, s).value) < kExtensionDenominator * y_den_size)
      continue;
    KnownPoint k = known_on_curve(curve, t);
    if (!std::isfinite(k.point.x) || !std::isfinite(k.point.y)) continue;
    bool near_segment = false;
    for (const auto& m : sampling.segment_minima({k.point.x, k.point.y}, margin))
      near_segment = near_segment || !(m.distance > margin);
    if (!near_segment && isolated(sampling, k.point, {t})) points.push_back(k);
  }
  return points;
}

}  // namespace bezinv::datasets
