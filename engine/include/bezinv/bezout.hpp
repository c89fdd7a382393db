#pragma once
// The Bernstein-Bezout matrix (Bini & Gemignani 2004; Marco & Martinez Sect. 2.1).
// For p, q of degree n in the Bernstein basis, B = (b_ij) is the n x n matrix with
//     (p(t) q(s) - p(s) q(t)) / (t - s) = sum_{i,j} b_ij beta_i^{(n-1)}(t) beta_j^{(n-1)}(s).
// B is symmetric, bilinear and alternating in (p, q), and singular exactly when p and q share a
// root; then (beta_0^{(n-1)}(t0), ..., beta_{n-1}^{(n-1)}(t0)) is in its null space (Theorem 2).
#include <span>

namespace bezinv {

// Writes B (n x n, row-major, both triangles) for p, q with n+1 coefficients each.
//
// Numerics: the recurrence as printed in the paper runs over the whole matrix, and in the upper
// triangle its multiplier j(n-i)/(i(n-j)) reaches (n-1)^2, so rounding errors grow geometrically
// along each anti-diagonal (measured: 1e-8 to 1e-6 relative at n = 20 depending on the coefficients, O(1) at n = 30). In the lower
// triangle (row >= column) the multiplier is at most 1, so we compute only that triangle and
// mirror it, which keeps ~4e-16 relative to max|B| at every degree (tests/engine/bezout_test).
void bezout_matrix(std::span<const double> p, std::span<const double> q, std::span<double> out);

}  // namespace bezinv
