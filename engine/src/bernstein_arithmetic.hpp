#pragma once
// Arithmetic on polynomials in the Bernstein basis of [0, 1], for what the plan precomputes (the
// distance's derivative, the clearance of the extension): products, derivatives, subdivision.
// Each operation has a `bound` form that applies it to absolute values with every difference a
// sum: a bound of the terms that round, from which the callers size the slack of a sign test.
#include <span>
#include <vector>

#include "bezinv/tolerances.hpp"

namespace bezinv::detail {

using BernsteinPoly = std::vector<double>;  // coefficients; the degree is size - 1

// p'(t) = n sum (p_{i+1} - p_i) B_i^{n-1}.
BernsteinPoly derivative(const BernsteinPoly& p, bool bound);

// (p q)_k = sum_{i+j=k} C(a,i) C(b,j) / C(a+b,k) p_i q_j. With non-negative p and q (the bound
// form) this is already a bound of the terms.
BernsteinPoly product(const BernsteinPoly& p, const BernsteinPoly& q);

// p + sign q, or with `bound` |p| + |q| for inputs that are already bounds.
BernsteinPoly combine(const BernsteinPoly& p, const BernsteinPoly& q, double sign, bool bound = false);

// c * p.
BernsteinPoly scaled(const BernsteinPoly& p, double c);

// The largest degree the engine's Bernstein arithmetic meets: g of degree 6n - 1 with separate
// denominators (stationary_points.hpp).
inline constexpr int kMaxBernsteinDegree = 6 * kMaxDegree;

// de Casteljau at s: the coefficients on [0, s] (left) and [s, 1] (right) of the degree-m
// polynomial c[0..m]. `right` may be `c` (halving in place); `left` must be other storage.
void split(const double* c, int m, double s, double* left, double* right);

// The coefficients of p on [0, 1/2] (left) and [1/2, 1] (right), each a polynomial of [0, 1]
// again. Each entry of the triangle is (x + y) / 2: exact halvings and one rounding, so nested
// halvings round no more per level than one split does.
void halve(const BernsteinPoly& p, BernsteinPoly& left, BernsteinPoly& right);

double max_abs(std::span<const double> p);

}  // namespace bezinv::detail
