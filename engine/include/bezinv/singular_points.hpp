#pragma once
// The base points of an inversion formula on the curve, and among them the curve's singular
// points (Wang & Joe, Theorem 7: every singular point is a base point, N = M = 0). Found without
// the implicit equation: M(P(t)) W(t)^d is a polynomial of degree n d in t whose roots are the
// parameters of the base points on the curve (N(P(t)) = t M(P(t)) vanishes with it), and the roots
// whose points coincide are one point of the curve with several parameters:
//     double_point    two real parameters (a crunode: two branches cross)
//     isolated_point  two complex-conjugate parameters of a real point (an acnode)
//     cusp            one real parameter twice (P' = 0 there)
//     multiple_point  three or more parameters
//     simple          one parameter: a base point where the curve passes once, not singular (a
//                     conic's centre, a quartic's fourth base point)
// Points that are not real (complex base points, complex singular points) are counted, not listed.
#include <array>
#include <complex>
#include <vector>

#include "bezinv/inversion_formula.hpp"
#include "bezinv/plan.hpp"

namespace bezinv {

enum class BasePointKind { double_point, isolated_point, cusp, multiple_point, simple };
const char* to_string(BasePointKind kind);

struct BasePoint {
  BasePointKind kind = BasePointKind::simple;
  std::array<double, 2> point{};  // input coordinates
  // Its parameters, real ones first, increasing; t = infinity (P(infinity) a finite point) is
  // std::numeric_limits<double>::infinity().
  std::vector<std::complex<double>> parameters;
};

struct BasePoints {
  std::vector<BasePoint> points;  // real points of the curve, by their first parameter
  int complex_points = 0;         // base points off the real plane
  bool at_infinity = false;       // P(infinity) is a base point at infinity (W = 0 there)
};

// Throws FormulaError past the degree n d = kMaxBasePointDegree of M(P(t)) (its roots are then
// found too inaccurately to pair them).
BasePoints base_points(const InversionPlan& plan, const InversionFormula& formula);

// Up to degree 12 curves with a common denominator (n d = 120), 6 with separate ones.
inline constexpr int kMaxBasePointDegree = 120;

}  // namespace bezinv
