#pragma once
// The Sylvester resultant matrix in the Bernstein basis (Winkler & Goldman 2003), used where the
// Bezout matrix of formal degree n fails because p and q both have lower true degree
// (Marco & Martinez Sect. 4, Example 1 at x0 = 1/2).
//
// For p of degree m and q of degree k (m, k >= 1), S is the (m+k) x (m+k) matrix whose columns are
// the Bernstein coefficients, in the basis of degree m+k-1, of
//     beta_j^{(k-1)}(t) p(t)   (j = 0..k-1)   and   beta_j^{(m-1)}(t) q(t)   (j = 0..m-1),
// using beta_i^{(a)} beta_j^{(b)} = C(a,i) C(b,j) / C(a+b,i+j) beta_{i+j}^{(a+b)}.
// If p(t0) = q(t0) = 0, every column is a polynomial vanishing at t0, so the row vector
// (beta_0^{(m+k-1)}(t0), ..., beta_{m+k-1}^{(m+k-1)}(t0)) is a left null vector: v^T S = 0.
#include <span>

namespace bezinv {

// Writes S ((m+k) x (m+k), row-major) for p (m+1 coefficients) and q (k+1 coefficients).
void sylvester_matrix(std::span<const double> p, std::span<const double> q, std::span<double> out);

}  // namespace bezinv
