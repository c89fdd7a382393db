#pragma once
// The implicit equation F(x, y) = 0 of a plan's curve: the polynomial of the curve's degree n that
// vanishes on it, unique up to a constant factor for a faithfully parametrized curve, and equal to
// det B(x, y) (the Bezout resultant, Wang & Joe Sect. 4) up to that factor. Found as the formula is
// (bezinv/inversion_formula.hpp): F(P(t)) W(t)^n is a polynomial of degree n^2 in t, and F solves
// the linear system "it vanishes at 2 (n^2 + 1) parameters of the segment". Stored in the
// Chebyshev basis of the plan's normalized coordinates, scaled to largest coefficient 1.
#include "bezinv/inversion_formula.hpp"
#include "bezinv/plan.hpp"
#include "bezinv/plane_polynomial.hpp"

namespace bezinv {

struct ImplicitEquation {
  PlanePolynomial F;
  double null_ratio = 0.0;  // the solution's singular value / the largest (rounding: ~1e-16 .. 1e-10)
  double next_ratio = 0.0;  // the next one up: how clearly F is the only solution
};

// Throws FormulaError past kMaxFormulaCurveDegree.
ImplicitEquation implicit_equation(const InversionPlan& plan);

}  // namespace bezinv
