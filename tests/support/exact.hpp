#pragma once
// Exact rational references for the tests (GMP's mpq_class).
//
// Every function here is written from the mathematical definition and shares no code with
// engine/src, so agreement between the two is evidence, not an echo. Doubles convert to mpq
// exactly (a double is a dyadic rational), so "the exact answer for the engine's input" is well
// defined and every error the tests measure is the engine's own.
//
// Where a quantity has two classical formulas, the reference deliberately takes the other route
// from the engine: power-basis coefficients are found by expanding (1-t)^{n-i} t^i, not by the
// forward difference; products, derivatives and degree elevation go through the power basis; the
// Bernstein-Bezout matrix is built twice, once by the paper's recurrence and once by solving its
// defining identity.
#include <gmpxx.h>

#include <array>
#include <span>
#include <vector>

namespace bezinv::exact {

// Bernstein coefficients p_0..p_n of a polynomial of degree (formal) n = size - 1.
using Poly = std::vector<mpq_class>;

// Dense matrix of rationals, row-major.
struct Matrix {
  int rows = 0, cols = 0;
  std::vector<mpq_class> a;

  Matrix() = default;
  Matrix(int r, int c) : rows(r), cols(c), a(static_cast<std::size_t>(r) * c) {}
  mpq_class& operator()(int i, int j) { return a[static_cast<std::size_t>(i) * cols + j]; }
  const mpq_class& operator()(int i, int j) const { return a[static_cast<std::size_t>(i) * cols + j]; }
  bool operator==(const Matrix& other) const = default;
};

// ---- conversions -------------------------------------------------------------------------------

Poly to_exact(std::span<const double> c);
std::vector<double> to_double(const Poly& c);
// The double nearest to x (GMP's mpq -> double truncates; this rounds to nearest, so the
// reference itself adds at most half an ulp).
double nearest_double(const mpq_class& x);
mpq_class abs(const mpq_class& x);
mpq_class max_abs(const Matrix& m);

// ---- Bernstein basis (paper Sect. 2.1) ---------------------------------------------------------

mpz_class binomial(int n, int k);

// beta_i^{(n)}(t) = C(n,i) (1-t)^{n-i} t^i, i = 0..n, each as the product (any rational t).
std::vector<mpq_class> bernstein_basis(int n, const mpq_class& t);

// p(t) = sum_i p_i beta_i^{(n)}(t).
mpq_class bernstein_value(const Poly& p, const mpq_class& t);

// Power-basis coefficients a_0..a_n of p, by expanding each (1-t)^{n-i} with the binomial theorem.
Poly power_from_bernstein(const Poly& p);

// Bernstein coefficients at degree n (n >= a.size() - 1) of sum_k a_k t^k, from
// t^k = sum_{i=k}^{n} C(i,k)/C(n,k) beta_i^{(n)}(t).
Poly bernstein_from_power(const Poly& a, int n);

// Coefficient of t^n (n = formal degree) in the power basis.
mpq_class power_leading_coefficient(const Poly& p);

// p' at degree n-1 (degree 0 for a constant: the zero polynomial), through the power basis.
Poly derivative(const Poly& p);

// p at degree `degree` >= n, through the power basis.
Poly elevate(const Poly& p, int degree);

// a(t) b(t) at degree deg(a) + deg(b), through the power basis.
Poly product(const Poly& a, const Poly& b);

// ---- resultant matrices ------------------------------------------------------------------------

// (a) The paper's recurrence (Sect. 2.1, Maple code of Bini & Gemignani), run exactly over the
// whole n x n matrix, transcribed with its 1-based indices.
Matrix bezout_recurrence(const Poly& p, const Poly& q);

// (b) The Bernstein-Bezout matrix from its definition
//     (p(t) q(s) - p(s) q(t)) / (t - s) = sum_{i,j} b_ij beta_i^{(n-1)}(t) beta_j^{(n-1)}(s):
// both sides at the n x n node pairs (t_k, s_l) = (k, -1-l) give L = Bt B Bs^T with
// Bt[k][i] = beta_i^{(n-1)}(t_k) and Bs[l][j] = beta_j^{(n-1)}(s_l), which exact Gaussian
// elimination solves for B. No symmetry is assumed.
Matrix bezout_from_definition(const Poly& p, const Poly& q);

// (d) The Bernstein Sylvester matrix as sylvester.hpp defines it: for p of degree m and q of
// degree k, column j < k holds beta_j^{(k-1)} p and column k + j holds beta_j^{(m-1)} q, both at
// degree m+k-1 (the products formed through the power basis, not by the product formula).
Matrix sylvester(const Poly& p, const Poly& q);

// X with A X = R, by exact Gaussian elimination (A square and regular).
Matrix solve(Matrix a, Matrix r);

// ---- curves ------------------------------------------------------------------------------------

// P(t) = (x_num(t) / x_den(t), y_num(t) / y_den(t)) and P'(t), exactly.
struct RationalCurve {
  Poly x_num, x_den, y_num, y_den;
  std::array<mpq_class, 2> point(const mpq_class& t) const;
  std::array<mpq_class, 2> tangent(const mpq_class& t) const;
};

}  // namespace bezinv::exact
