#include "degree_drop.hpp"

#include <algorithm>
#include <array>
#include <cmath>

#include "bezinv/bernstein.hpp"
#include "bezinv/tolerances.hpp"

namespace bezinv::detail {

// The leading power coefficient is affine in the point, from the plan's four; the bound is
// power_leading_bound of p and q, sum_i C(n,i) |X_i - u0 W_i|.
bool degree_drops(const PlanData& plan, double u0, double v0) {
  double bound_p = 0.0, bound_q = 0.0;
  for (int i = 0; i <= plan.degree; ++i) {
    const double c = binomial(plan.degree, i);
    bound_p += c * std::abs(plan.x_num[i] - u0 * plan.x_den[i]);
    bound_q += c * std::abs(plan.y_num[i] - v0 * plan.y_den[i]);
  }
  const double lead_p = plan.lead_x_num - u0 * plan.lead_x_den;
  const double lead_q = plan.lead_y_num - v0 * plan.lead_y_den;
  return std::abs(lead_p) <= kDegreeDropRatio * bound_p && std::abs(lead_q) <= kDegreeDropRatio * bound_q;
}

// The cheap test: bound_p <= sum_i C(n,i) (|X_i| + |u0| |W_i|) = a + |u0| b with a and b per curve,
// so a point whose |lead_p| exceeds kDegreeDropRatio times twice that cannot drop (twice: room for
// the rounding of both sums, ~n eps relative). Only where some point passes it are the exact bounds
// computed, lanes innermost so that the loops vectorize (docs/accuracy-model.md, "Degree drops").
void degree_drops_batch(const PlanData& plan, const double* u, const double* v, std::size_t count,
                        std::uint8_t* drops) {
  const int n = plan.degree;
  double ax = 0, bx = 0, ay = 0, by = 0;
  for (int i = 0; i <= n; ++i) {
    const double c = binomial(n, i);
    ax += c * std::abs(plan.x_num[i]);
    bx += c * std::abs(plan.x_den[i]);
    ay += c * std::abs(plan.y_num[i]);
    by += c * std::abs(plan.y_den[i]);
  }
  bool any = false;
  for (std::size_t l = 0; l < count; ++l) {
    const double lead_p = plan.lead_x_num - u[l] * plan.lead_x_den;
    const double lead_q = plan.lead_y_num - v[l] * plan.lead_y_den;
    // Written so that NaN passes on to the exact test, which decides it as the reference does.
    const bool maybe = !(std::abs(lead_p) > 2 * kDegreeDropRatio * (ax + std::abs(u[l]) * bx)) &&
                       !(std::abs(lead_q) > 2 * kDegreeDropRatio * (ay + std::abs(v[l]) * by));
    drops[l] = maybe;
    any |= maybe;
  }
  if (!any) return;

  constexpr std::size_t kChunk = 64;
  std::array<double, kChunk> bound_p, bound_q;
  for (std::size_t first = 0; first < count; first += kChunk) {
    const std::size_t m = std::min(kChunk, count - first);
    const double* uc = u + first;
    const double* vc = v + first;
    std::fill_n(bound_p.begin(), m, 0.0);
    std::fill_n(bound_q.begin(), m, 0.0);
    for (int i = 0; i <= n; ++i) {
      const double c = binomial(n, i);
      const double xn = plan.x_num[i], xd = plan.x_den[i], yn = plan.y_num[i], yd = plan.y_den[i];
      for (std::size_t l = 0; l < m; ++l) {
        bound_p[l] += c * std::abs(xn - uc[l] * xd);
        bound_q[l] += c * std::abs(yn - vc[l] * yd);
      }
    }
    for (std::size_t l = 0; l < m; ++l) {
      const double lead_p = plan.lead_x_num - uc[l] * plan.lead_x_den;
      const double lead_q = plan.lead_y_num - vc[l] * plan.lead_y_den;
      drops[first + l] =
          std::abs(lead_p) <= kDegreeDropRatio * bound_p[l] && std::abs(lead_q) <= kDegreeDropRatio * bound_q[l];
    }
  }
}

}  // namespace bezinv::detail
