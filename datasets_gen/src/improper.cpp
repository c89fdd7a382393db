#include "bezinv/datasets/improper.hpp"

#include <string>
#include <vector>

namespace bezinv::datasets {
namespace {

long double binomial_ld(int n, int k) {
  long double b = 1;
  for (int j = 1; j <= k; ++j) b = b * (n - k + j) / j;
  return b;
}

// Bernstein coefficients at degree 2m of q(t^2), q of degree m.
std::vector<double> composed_with_square(const std::vector<double>& q) {
  const int m = static_cast<int>(q.size()) - 1;
  std::vector<long double> p(2 * m + 1, 0.0L);
  for (int i = 0; i <= m; ++i)
    for (int k = 0; k <= m - i; ++k)
      p[2 * i + k] += q[i] * binomial_ld(m, i) * binomial_ld(m - i, k) * (1ULL << k) / binomial_ld(2 * m, 2 * i + k);
  return {p.begin(), p.end()};
}

}  // namespace

Curve improper(const Curve& curve) {
  Curve c = curve;
  c.id = curve.id + "-of-t-squared";
  c.x_num = composed_with_square(curve.x_num);
  c.x_den = composed_with_square(curve.x_den);
  c.y_num = composed_with_square(curve.y_num);
  c.y_den = composed_with_square(curve.y_den);
  return c;
}

}  // namespace bezinv::datasets
