#pragma once
// Inversion formulae (Wang & Joe): for a faithfully parametrized plane curve P(t) of degree n,
// polynomials N(x, y) and M(x, y) with
//     t = N(P(t)) / M(P(t))      for every t, except where N = M = 0 (the formula's base points),
// of degree d = 1 for n = 1, 2, 3 and d = n - 2 from n = 4 (Goldman et al. 1984 show that degree
// exists). The points where N = M = 0 on the curve include every singular point (Theorem 7).
//
// How they are found: N(P(t)) - t M(P(t)) is, after multiplying by W(t)^d, a polynomial of degree
// n d + 1 in t, and it vanishes identically exactly when (N, M) solves the linear system "it
// vanishes at n d + 2 parameters". Its solutions form a space of dimension 3 (n = 1), 2 (n = 2) or
// n - 2 (n >= 3): the free choices of the formula (a line's centre, a conic's centre on the curve,
// a quartic's fourth base point ...), fixed by FormulaChoice. A curve that is not faithful (every
// point traced twice or more) has no formula: the system has no solution.
//
// N and M are computed in the plan's normalized coordinates and stored in the Chebyshev basis
// there (bezinv/plane_polynomial.hpp), so a curve far from the origin keeps its digits.
#include <array>
#include <optional>
#include <stdexcept>
#include <vector>

#include "bezinv/plan.hpp"
#include "bezinv/plane_polynomial.hpp"

namespace bezinv {

// The formula's free choices. Every one names base points on the curve by their parameter: a
// base point at P(s) makes M(P(s)) = 0 (and so N(P(s)) = s M(P(s)) = 0); at s = infinity, N(P(inf)) = 0.
struct FormulaChoice {
  // Degree 2 (a conic): the centre of the pencil, a point of the curve. Default P(infinity), as
  // the paper recommends for a Bezier segment (formula (9)): outside the segment, where the
  // projection from it is closest to the nearest point. P(0) is formula (10).
  // Degree >= 4: extra base points (at most n - 3), in order; where they leave a choice, the
  // formula whose M is largest (least squares) over the segment's points is taken, which keeps
  // N / M well conditioned there. Degree 1: ignored (the centre is the point at infinity normal
  // to the line, so that N / M is the orthogonal projection onto it). Degree 3: no choice.
  std::vector<double> base_parameters;  // empty: the defaults above; infinity allowed
};

struct FormulaError : std::runtime_error {
  using std::runtime_error::runtime_error;
};

class InversionFormula {
 public:
  // N and M of degree d (see above), or throws FormulaError: the curve is not faithful (no
  // formula: report the smallest singular value's ratio), its degree n is past
  // kMaxFormulaCurveDegree, or a base point asked for is not a valid choice.
  InversionFormula(const InversionPlan& plan, const FormulaChoice& choice = {});
  // The same from a plan's data (the engine's formula path, which has no InversionPlan).
  InversionFormula(const detail::PlanData& data, const FormulaChoice& choice);

  int curve_degree() const { return curve_degree_; }  // n (2 x the plan's degree for separate denominators)
  int degree() const { return numerator_.degree(); }  // d
  const PlanePolynomial& numerator() const { return numerator_; }
  const PlanePolynomial& denominator() const { return denominator_; }

  // N(x, y) / M(x, y) (input coordinates): t on the curve; off it, the parameter of the curve
  // point the formula projects (x, y) to (for d = 1, the projection from the centre).
  double operator()(double x, double y) const;

  // d = 1: the centre of the pencil N - t M = 0, where both lines meet, in homogeneous input
  // coordinates (x, y, w): w = 0 for a centre at infinity (then (x, y) is its direction).
  std::optional<std::array<double, 3>> centre() const;

  // Evidence for the solution space: its singular values over the largest, the largest of the
  // solution space (rounding: ~1e-16 .. 1e-10) and the next one (how clearly the space is
  // separated from the rest, ~1e-3 or more on a faithful curve).
  double null_ratio() const { return null_ratio_; }
  double next_ratio() const { return next_ratio_; }
  // The formula checked where it is used: max |N/M(P(t)) - t| over 64 Chebyshev parameters of the
  // segment (P(t) rounded to doubles in input coordinates, N/M in double). ~1e-15 for degrees up
  // to 6; it grows with the degree, as the polynomials of degree n - 2 on the curve become
  // ill-conditioned (docs/inversion-formula.md, "How far the formula goes").
  double segment_error() const { return segment_error_; }

 private:
  int curve_degree_ = 0;
  PlanePolynomial numerator_, denominator_;
  double null_ratio_ = 0.0, next_ratio_ = 0.0, segment_error_ = 0.0;
};

// The largest curve degree n (homogeneous: 2 x the plan's degree for separate denominators) for
// which formulae and implicit equations are computed: every curve bezinv takes with a common
// denominator, separate ones up to degree 16. Its system has 2 x 496 unknowns and 1,924 rows.
inline constexpr int kMaxFormulaCurveDegree = 32;

}  // namespace bezinv
