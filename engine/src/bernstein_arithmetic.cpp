#include "bernstein_arithmetic.hpp"

#include <algorithm>
#include <array>
#include <cassert>
#include <cmath>

#include "bezinv/bernstein.hpp"

namespace bezinv::detail {

BernsteinPoly derivative(const BernsteinPoly& p, bool bound) {
  const int n = static_cast<int>(p.size()) - 1;
  if (n == 0) return BernsteinPoly{0.0};
  BernsteinPoly out(n);
  for (int i = 0; i < n; ++i) out[i] = n * (bound ? p[i + 1] + p[i] : p[i + 1] - p[i]);
  return out;
}

BernsteinPoly product(const BernsteinPoly& p, const BernsteinPoly& q) {
  const int a = static_cast<int>(p.size()) - 1, b = static_cast<int>(q.size()) - 1;
  BernsteinPoly out(a + b + 1, 0.0);
  // The three rows of binomials once: above the table's rows each binomial() is a loop of its own,
  // which in the double loop made the product O((a + b)^3).
  assert(a >= 0 && b >= 0 && a + b <= kMaxBernsteinDegree);
  std::array<double, kMaxBernsteinDegree + 1> ca, cb, cab;
  for (int i = 0; i <= a; ++i) ca[i] = binomial(a, i);
  for (int j = 0; j <= b; ++j) cb[j] = binomial(b, j);
  for (int k = 0; k <= a + b; ++k) cab[k] = binomial(a + b, k);
  for (int i = 0; i <= a; ++i)
    for (int j = 0; j <= b; ++j) out[i + j] += ca[i] * cb[j] / cab[i + j] * p[i] * q[j];
  return out;
}

BernsteinPoly combine(const BernsteinPoly& p, const BernsteinPoly& q, double sign, bool bound) {
  BernsteinPoly out(p.size());
  for (std::size_t i = 0; i < p.size(); ++i) out[i] = p[i] + (bound ? std::abs(sign) : sign) * q[i];
  return out;
}

BernsteinPoly scaled(const BernsteinPoly& p, double c) {
  BernsteinPoly out(p.size());
  for (std::size_t i = 0; i < p.size(); ++i) out[i] = c * p[i];
  return out;
}

void split(const double* c, int m, double s, double* left, double* right) {
  // In place in `right`: after round r its entries 0..m-r are the current row of the triangle,
  // and entry m - r is final (the right half's coefficient), so no other storage is needed and
  // `right` may be `c` itself.
  if (right != c) std::copy_n(c, m + 1, right);
  left[0] = right[0];
  for (int r = 1; r <= m; ++r) {
    for (int i = 0; i <= m - r; ++i) right[i] = (1 - s) * right[i] + s * right[i + 1];
    left[r] = right[0];
  }
}

void halve(const BernsteinPoly& p, BernsteinPoly& left, BernsteinPoly& right) {
  const int m = static_cast<int>(p.size()) - 1;
  left.resize(p.size());
  right.resize(p.size());
  split(p.data(), m, 0.5, left.data(), right.data());
}

double max_abs(std::span<const double> p) {
  double m = 0.0;
  for (double v : p) m = std::max(m, std::abs(v));
  return m;
}

}  // namespace bezinv::detail
