#include "bezinv/datasets/cusp.hpp"

#include <cmath>
#include <stdexcept>
#include <string>

#include "bezinv/datasets/on_curve_points.hpp"
#include "bezinv/datasets/random_numbers.hpp"
#include "bezinv/datasets/reference_evaluation.hpp"
#include "linear_condition.hpp"

namespace bezinv::datasets {
namespace {

constexpr int kAttempts = 200;
constexpr Real kStationary = 1e-12L;      // |P'(tc)| / diagonal
constexpr Real kMinCurvature = 0.01L;     // |P''(tc)| / diagonal
constexpr Real kMinSine = 0.2588190451L;  // sin 15 degrees, between P''(tc) and P'''(tc)
constexpr Real kCuspWindow = 0.05L;       // parameters this near tc are the cusp's own branches

using detail::beta;

// d/dt beta_i^n(t) = n (beta_{i-1}^{n-1}(t) - beta_i^{n-1}(t)).
Real beta_derivative(int n, int i, Real t) {
  const Real left = i > 0 ? beta(n - 1, i - 1, t) : 0, right = i < n ? beta(n - 1, i, t) : 0;
  return n * (left - right);
}

// Makes (num / den)'(tc) = 0: g_i = beta_i'(tc) den(tc) - beta_i(tc) den'(tc).
void enforce_stationary(std::vector<double>& num, const std::vector<double>& den, Real tc) {
  const int n = static_cast<int>(num.size()) - 1;
  Real d = 0, dd = 0;
  for (int i = 0; i <= n; ++i) { d += den[i] * beta(n, i, tc); dd += den[i] * beta_derivative(n, i, tc); }
  std::vector<Real> g(n + 1);
  for (int i = 0; i <= n; ++i) g[i] = beta_derivative(n, i, tc) * d - beta(n, i, tc) * dd;
  detail::enforce_linear_condition(num, g);
}

// No branch of the curve but the cusp's own comes within kIsolation * diagonal of `point`.
bool isolated_but_the_cusp(const CurveSampling& sampling, Point point, double tc) {
  const Real margin = kIsolation * sampling.diagonal();
  for (const DistanceMinimum& m : sampling.line_minima({point.x, point.y}, margin))
    if (!(std::abs(m.t - tc) <= kCuspWindow) && !(m.distance > margin)) return false;
  return true;
}

}  // namespace

Curve with_cusp(CurveKind kind, int degree, double tc, std::mt19937_64& rng, ControlPolygon polygon) {
  if (degree < 3) throw std::invalid_argument("with_cusp: degree must be at least 3");
  if (!(0 < tc && tc < 1)) throw std::invalid_argument("with_cusp: need 0 < tc < 1");
  for (int attempt = 0; attempt < kAttempts; ++attempt) {
    Curve c = random_curve(kind, degree, rng, polygon);
    enforce_stationary(c.x_num, c.x_den, tc);
    enforce_stationary(c.y_num, c.y_den, tc);
    c.id += "-cusp";

    const Real diagonal = control_diagonal(c);
    const ReferenceJet j = reference_jet(c, tc);
    if (!(std::hypot(j.d1.x, j.d1.y) <= kStationary * diagonal)) continue;
    const Real curvature = std::hypot(j.d2.x, j.d2.y);
    if (!(curvature >= kMinCurvature * diagonal)) continue;
    // P''' by a central difference of P'' (long double: h = 1e-4 leaves ~1e-8 relative).
    constexpr Real h = 1e-4L;
    const ReferenceJet a = reference_jet(c, tc - h), b = reference_jet(c, tc + h);
    const RealPoint d3{(b.d2.x - a.d2.x) / (2 * h), (b.d2.y - a.d2.y) / (2 * h)};
    const Real sine = std::abs(j.d2.x * d3.y - j.d2.y * d3.x) / (curvature * std::hypot(d3.x, d3.y));
    if (!(sine >= kMinSine)) continue;
    if (!isolated_but_the_cusp(CurveSampling(c), rounded(j.p), tc)) continue;
    return c;
  }
  throw std::runtime_error("with_cusp: no verified curve of degree " + std::to_string(degree) + " in " +
                           std::to_string(kAttempts) + " attempts");
}

std::vector<KnownPoint> near_cusp_points(const CurveSampling& sampling, double tc, int count, std::mt19937_64& rng) {
  std::vector<KnownPoint> points;
  for (int attempt = 0; attempt < 20 * count && static_cast<int>(points.size()) < count; ++attempt) {
    const double s = std::pow(10.0, uniform(rng, -4.0, -2.0));
    const double t = uniform(rng, 0.0, 1.0) < 0.5 ? tc - s : tc + s;
    KnownPoint k = known_on_curve(sampling.curve(), t);
    if (isolated_but_the_cusp(sampling, k.point, tc)) points.push_back(k);
  }
  return points;
}

}  // namespace bezinv::datasets
