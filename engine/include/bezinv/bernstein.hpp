#pragma once
// Polynomials in the Bernstein basis of degree n on [0,1]:
//     p(t) = sum_{i=0}^{n} p_i * beta_i^{(n)}(t),   beta_i^{(n)}(t) = C(n,i) (1-t)^{n-i} t^i.
// Everything bezinv does stays in this basis (Bini & Gemignani: conversions to the power basis
// lose accuracy). The only power-basis quantity used is the leading coefficient, to detect
// degree drops; it is computed from the Bernstein coefficients by a finite difference.
#include <span>

namespace bezinv {

// Binomial coefficient C(n, k) as a double (exact for n <= 64 as long as it fits in 53 bits,
// which holds for every n bezinv accepts).
double binomial(int n, int k);

// beta_0^{(n)}(t) ... beta_n^{(n)}(t) into out (size n+1). Valid for any real t, also outside [0,1].
void bernstein_basis(int n, double t, std::span<double> out);

// p(t) by de Casteljau's algorithm (stable on [0,1], usable by extrapolation outside it).
double bernstein_value(std::span<const double> coefficients, double t);

// p(t), p'(t), p''(t) in one pass (derivatives by differences of the coefficients).
struct BernsteinJet { double value, first, second; };
BernsteinJet bernstein_jet(std::span<const double> coefficients, double t);

// The end of bernstein_jet, for callers that run de Casteljau themselves (several polynomials in
// one pass): after n-2 steps on a degree-n polynomial (n >= 1) three points b0, b1, b2 remain (b2
// unused when n = 1). They are the coefficients of a quadratic whose second difference, first
// difference and value give p'', p', p (Farin, Ch. 5).
inline BernsteinJet bernstein_jet_from_last_points(int n, double t, double b0, double b1, double b2) {
  const double s = 1.0 - t;
  double second = 0.0;
  if (n >= 2) {
    second = n * (n - 1.0) * (b2 - 2.0 * b1 + b0);
    b0 = s * b0 + t * b1;
    b1 = s * b1 + t * b2;
  }
  return {s * b0 + t * b1, n * (b1 - b0), second};
}

// Coefficient of t^n in the power basis: sum_i (-1)^{n-i} C(n,i) p_i (the n-th forward difference).
double power_leading_coefficient(std::span<const double> coefficients);

// sum_i C(n,i) |p_i|: the bound on |power_leading_coefficient| and the scale against which it is
// judged to vanish.
double power_leading_bound(std::span<const double> coefficients);

// Degree elevation n -> n+1: q_i = (i/(n+1)) p_{i-1} + (1 - i/(n+1)) p_i.
void elevate_degree(std::span<const double> coefficients, std::span<double> out);

// Degree reduction n -> n-1 of a polynomial whose true degree is below n (its leading power
// coefficient ~ 0). Runs the elevation recurrence forwards from the left end and backwards from
// the right end and blends the two halves, so neither end's rounding is amplified by the
// n/(n-i) factors across the whole range. out has size n.
void reduce_degree(std::span<const double> coefficients, std::span<double> out);

}  // namespace bezinv
