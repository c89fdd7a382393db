#include "bezinv/bezout.hpp"

#include <cassert>

namespace bezinv {

void bezout_matrix(std::span<const double> p, std::span<const double> q, std::span<double> out) {
  const int n = static_cast<int>(p.size()) - 1;
  assert(n >= 1 && q.size() == p.size() && static_cast<int>(out.size()) >= n * n);
  // 1-based (r, c) as in the paper's Maple code; stored row-major at (r-1)*n + (c-1).
  auto at = [&](int r, int c) -> double& { return out[(r - 1) * n + (c - 1)]; };
  auto cross = [&](int i, int j) { return p[i] * q[j] - p[j] * q[i]; };

  // First column and last row come straight from the coefficients.
  for (int r = 1; r <= n; ++r) at(r, 1) = (static_cast<double>(n) / r) * cross(r, 0);
  // Column c of the lower triangle from column c-1 along anti-diagonals:
  //   b(r,c) = n^2/(r(n-c+1)) (p_r q_{c-1} - p_{c-1} q_r) + (c-1)(n-r)/(r(n-c+1)) b(r+1,c-1).
  // With r >= c both factors of the multiplier, (c-1)/r and (n-r)/(n-c+1), are below 1, so
  // errors do not grow along the anti-diagonal (the upper triangle would multiply them by up to
  // (n-1)^2 per step; see bezout.hpp).
  for (int c = 2; c <= n; ++c) {
    const double last = static_cast<double>(n) / (n - c + 1);
    at(n, c) = last * cross(n, c - 1);
    for (int r = c; r <= n - 1; ++r) {
      const double denom = static_cast<double>(r) * (n - c + 1);
      at(r, c) = (static_cast<double>(n) * n / denom) * cross(r, c - 1) +
                 (static_cast<double>(c - 1) * (n - r) / denom) * at(r + 1, c - 1);
    }
  }
  // B is symmetric (the defining kernel is symmetric in t and s): mirror the lower triangle.
  for (int r = 1; r <= n; ++r)
    for (int c = r + 1; c <= n; ++c) at(r, c) = at(c, r);
}

}  // namespace bezinv
