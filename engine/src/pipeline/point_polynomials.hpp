#pragma once
// p = X_num - u0 X_den and q = Y_num - v0 Y_den, the two polynomials whose common root is the
// point's parameter (paper Sect. 2), in fixed-size storage: no allocation per point.
#include <array>
#include <cstddef>
#include <span>

#include "plan_data.hpp"
#include "bezinv/tolerances.hpp"

namespace bezinv::detail {

using Coefficients = std::array<double, kMaxDegree + 1>;

// p = X_num - u0 X_den and q = Y_num - v0 Y_den at the plan's degree.
struct PointPolynomials {
  int n;
  Coefficients p, q;
  std::span<const double> p_span() const { return {p.data(), static_cast<std::size_t>(n + 1)}; }
  std::span<const double> q_span() const { return {q.data(), static_cast<std::size_t>(n + 1)}; }
};

inline PointPolynomials point_polynomials(const PlanData& plan, double u0, double v0) {
  PointPolynomials pq;
  pq.n = plan.degree;
  for (int i = 0; i <= pq.n; ++i) {
    pq.p[i] = plan.x_num[i] - u0 * plan.x_den[i];
    pq.q[i] = plan.y_num[i] - v0 * plan.y_den[i];
  }
  return pq;
}

}  // namespace bezinv::detail
