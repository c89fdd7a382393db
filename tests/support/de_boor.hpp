#pragma once
// NURBS curves evaluated here and not by the engine, for the tests of NURBS and composite curves:
// the B-spline basis by the Cox-de Boor recursion (N_{i,0} the indicator of the knot interval,
// N_{i,r} = (u - u_i)/(u_{i+r} - u_i) N_{i,r-1} + (u_{i+r+1} - u)/(u_{i+r+1} - u_{i+1}) N_{i+1,r-1},
// 0/0 = 0), then P(u) = sum N_i w_i P_i / sum N_i w_i. The interval is the one holding u among the
// domain's non-empty ones (the first before the domain, the last from its end on), so u outside the
// domain gives the end pieces' polynomials: the curve's extension.
#include <array>
#include <cmath>
#include <cstddef>
#include <vector>

namespace bezinv::test_support {

struct Nurbs {
  int degree = 0;
  std::vector<double> knots;
  std::vector<std::array<double, 3>> points;  // z = 0 for a plane curve
  std::vector<double> weights;                 // empty: all 1

  double domain_start() const { return knots[degree]; }
  double domain_end() const { return knots[knots.size() - 1 - degree]; }
};

// The index k of the knot interval [u_k, u_{k+1}) used at u.
inline std::size_t nurbs_interval(const Nurbs& c, double u) {
  const std::size_t p = static_cast<std::size_t>(c.degree), last = c.knots.size() - 1 - p;
  std::size_t k = p;
  while (k + 1 < last && !(c.knots[k] < c.knots[k + 1])) ++k;  // the first non-empty interval
  for (std::size_t j = k; j < last; ++j)
    if (c.knots[j] < c.knots[j + 1] && c.knots[j] <= u) k = j;
  return k;
}

// N_{i,p}(u) for every i, with the interval k fixed.
inline std::vector<double> nurbs_basis(const Nurbs& c, double u) {
  const std::size_t k = nurbs_interval(c, u), m = c.knots.size() - 1;
  const auto& U = c.knots;
  std::vector<double> N(m, 0.0);
  N[k] = 1.0;
  for (int r = 1; r <= c.degree; ++r)
    for (std::size_t i = 0; i + r < m; ++i) {
      double left = 0, right = 0;
      if (U[i + r] != U[i]) left = (u - U[i]) / (U[i + r] - U[i]) * N[i];
      if (U[i + r + 1] != U[i + 1]) right = (U[i + r + 1] - u) / (U[i + r + 1] - U[i + 1]) * N[i + 1];
      N[i] = left + right;
    }
  N.resize(c.points.size());
  return N;
}

inline std::array<double, 3> nurbs_point(const Nurbs& c, double u) {
  const std::vector<double> N = nurbs_basis(c, u);
  std::array<double, 3> p{0, 0, 0};
  double w = 0;
  for (std::size_t i = 0; i < N.size(); ++i) {
    const double wi = c.weights.empty() ? 1.0 : c.weights[i];
    for (int k = 0; k < 3; ++k) p[k] += N[i] * wi * c.points[i][k];
    w += N[i] * wi;
  }
  for (double& x : p) x /= w;
  return p;
}

// P'(u) by central differences (for directions, not for accuracy).
inline std::array<double, 3> nurbs_tangent(const Nurbs& c, double u, double h = 1e-6) {
  const auto a = nurbs_point(c, u - h), b = nurbs_point(c, u + h);
  return {(b[0] - a[0]) / (2 * h), (b[1] - a[1]) / (2 * h), (b[2] - a[2]) / (2 * h)};
}

}  // namespace bezinv::test_support
