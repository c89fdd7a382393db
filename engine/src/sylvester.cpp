#include "bezinv/sylvester.hpp"

#include <cassert>

#include "bezinv/bernstein.hpp"

namespace bezinv {

void sylvester_matrix(std::span<const double> p, std::span<const double> q, std::span<double> out) {
  const int m = static_cast<int>(p.size()) - 1;
  const int k = static_cast<int>(q.size()) - 1;
  const int size = m + k;
  assert(m >= 1 && k >= 1 && static_cast<int>(out.size()) >= size * size);
  const int degree = size - 1;  // the product basis: beta^{(m+k-1)}
  for (int i = 0; i < size * size; ++i) out[i] = 0.0;
  // Columns 0..k-1: beta_j^{(k-1)} p, with beta_i^{(m)} beta_j^{(k-1)} = C(m,i)C(k-1,j)/C(m+k-1,i+j) beta_{i+j}.
  for (int j = 0; j < k; ++j)
    for (int i = 0; i <= m; ++i)
      out[(i + j) * size + j] = p[i] * binomial(m, i) * binomial(k - 1, j) / binomial(degree, i + j);
  // Columns k..k+m-1: beta_j^{(m-1)} q.
  for (int j = 0; j < m; ++j)
    for (int i = 0; i <= k; ++i)
      out[(i + j) * size + k + j] = q[i] * binomial(k, i) * binomial(m - 1, j) / binomial(degree, i + j);
}

}  // namespace bezinv
