// Inversion formulae, implicit equations and base points against Wang & Joe's worked examples
// (the paper's own formulae, centres, double points and parameters) and against construction
// (points made from a known t on random curves of every kind).
#include <gtest/gtest.h>

#include <cmath>
#include <complex>
#include <random>

#include "bezinv/implicit_equation.hpp"
#include "bezinv/inversion_formula.hpp"
#include "bezinv/singular_points.hpp"
#include "bezinv/datasets/cusp.hpp"
#include "bezinv/datasets/improper.hpp"
#include "bezinv/datasets/random_curve.hpp"
#include "bezinv/datasets/self_intersection.hpp"
#include "support/curve_kinds.hpp"
#include "support/sanitizers.hpp"

namespace {

using bezinv::BasePointKind;
using bezinv::Curve;
using bezinv::FormulaChoice;
using bezinv::InversionFormula;

constexpr double kInf = std::numeric_limits<double>::infinity();

// Example 1: the semicircle x^2 + y^2 = 1, x >= 0, as the paper writes it (kind `rational`).
Curve semicircle() { return Curve::rational("semicircle", {0, 1, 0}, {1, 0, 1}, {1, 0, -1}, {1, 0, 1}); }

// `formula` equals the paper's t = paper(x, y) wherever both are defined: two linear-over-linear
// (or quadratic) formulae of one pencil agree everywhere, not only on the curve (Theorem 4), so
// they are compared at points spread over the plane.
template <class Paper>
void expect_same_function(const InversionFormula& formula, Paper paper, double tolerance = 1e-12) {
  std::mt19937_64 rng(7);
  std::uniform_real_distribution<double> coordinate(-3.0, 3.0);
  for (int k = 0; k < 200; ++k) {
    const double x = coordinate(rng), y = coordinate(rng);
    const double expected = paper(x, y), got = formula(x, y);
    if (!std::isfinite(expected) || std::abs(expected) > 1e6) continue;  // near the pencil's centre
    EXPECT_NEAR(got, expected, tolerance * (1.0 + std::abs(expected))) << "at (" << x << ", " << y << ")";
  }
}

void expect_centre(const InversionFormula& formula, double x, double y) {
  const auto centre = formula.centre();
  ASSERT_TRUE(centre.has_value());
  ASSERT_NE((*centre)[2], 0.0) << "a finite centre";
  EXPECT_NEAR((*centre)[0] / (*centre)[2], x, 1e-13);
  EXPECT_NEAR((*centre)[1] / (*centre)[2], y, 1e-13);
}

TEST(InversionFormula, PaperExample1TheSemicircleFromInfinityIsFormula12) {
  const auto plan = bezinv::make_plan(semicircle());
  const InversionFormula formula(plan);  // default: centre P(infinity)
  EXPECT_EQ(formula.degree(), 1);
  expect_same_function(formula, [](double x, double y) { return (x - y + 1) / (2 * (x + 1)); });
  expect_centre(formula, -1.0, 0.0);
}

TEST(InversionFormula, PaperExample1TheSemicircleFromPZeroIsFormula13) {
  const auto plan = bezinv::make_plan(semicircle());
  const InversionFormula formula(plan, FormulaChoice{{0.0}});
  expect_same_function(formula, [](double x, double y) { return (1 - y) / (x - y + 1); });
  expect_centre(formula, 0.0, 1.0);
}

TEST(InversionFormula, PaperExample2TheReparametrizedSemicircleIsFormula15) {
  // (14): (P0 B0 / 4 + P1 B1 / 2 + P2 B2) / (B0 / 4 + B2).
  const auto plan = bezinv::make_plan(Curve::rational("14", {0, 0.5, 0}, {0.25, 0, 1}, {0.25, 0, -1}, {0.25, 0, 1}));
  const InversionFormula formula(plan);
  expect_same_function(formula, [](double x, double y) { return (2 * x - y + 1) / (4 * x + 3 * y + 5); });
  expect_centre(formula, -0.8, -0.6);
}

Curve example3() {
  return Curve::rational_bezier("example 3", {{0, 0}, {1, 1}, {0, 1}, {1, 0}}, {1, 2, 2, 1});
}

TEST(InversionFormula, PaperExample3TheCubicsFormulaIsCentredAtItsDoublePoint) {
  const auto plan = bezinv::make_plan(example3());
  const InversionFormula formula(plan);
  EXPECT_EQ(formula.degree(), 1);
  expect_same_function(formula, [](double x, double y) { return (5 * y - 6 * x) / (10 * y - 6); });
  expect_centre(formula, 0.5, 0.6);
  // N and M in the input's monomials (1, x, y): proportional to 5y - 6x and 10y - 6.
  const auto n = formula.numerator().monomials(), m = formula.denominator().monomials();
  const double k = m[0] / -6.0;
  EXPECT_NEAR(m[1] / k, 0.0, 1e-13);
  EXPECT_NEAR(m[2] / k, 10.0, 1e-13);
  EXPECT_NEAR(n[0] / k, 0.0, 1e-13);
  EXPECT_NEAR(n[1] / k, -6.0, 1e-13);
  EXPECT_NEAR(n[2] / k, 5.0, 1e-13);
}

TEST(InversionFormula, PaperExample3TheImplicitEquation) {
  const auto plan = bezinv::make_plan(example3());
  const auto implicit = bezinv::implicit_equation(plan);
  ASSERT_EQ(implicit.F.degree(), 3);
  // 1225y^3 - 756x^2y - 2520y^2 + 756xy + 1512x^2 + 1512y - 1512x, index (i, j) of x^i y^j.
  using P = bezinv::PlanePolynomial;
  std::vector<double> expected(P::size(3), 0.0);
  expected[P::index(0, 3)] = 1225;
  expected[P::index(2, 1)] = -756;
  expected[P::index(0, 2)] = -2520;
  expected[P::index(1, 1)] = 756;
  expected[P::index(2, 0)] = 1512;
  expected[P::index(0, 1)] = 1512;
  expected[P::index(1, 0)] = -1512;
  const auto got = implicit.F.monomials();
  const double k = got[P::index(0, 3)] / 1225.0;
  for (int e = 0; e < P::size(3); ++e) EXPECT_NEAR(got[e] / k, expected[e], 1e-9) << "term " << e;
}

TEST(InversionFormula, PaperExample3TheDoublePointAndItsParameters) {
  const auto plan = bezinv::make_plan(example3());
  const InversionFormula formula(plan);
  const auto base = bezinv::base_points(plan, formula);
  ASSERT_EQ(base.points.size(), 1u);
  const auto& p = base.points[0];
  EXPECT_EQ(p.kind, BasePointKind::double_point);
  EXPECT_NEAR(p.point[0], 0.5, 1e-12);
  EXPECT_NEAR(p.point[1], 0.6, 1e-12);
  ASSERT_EQ(p.parameters.size(), 2u);
  EXPECT_NEAR(p.parameters[0].real(), (7 - std::sqrt(21.0)) / 14, 1e-12);
  EXPECT_NEAR(p.parameters[1].real(), (7 + std::sqrt(21.0)) / 14, 1e-12);
}

// Example 4's quartic, in s = t + 1 so that its denominator has no root on the segment s in [0, 1]
// (t in [-1, 0]); its power form in t becomes, in the Bernstein basis of s (exact):
Curve example4() {
  return Curve::rational("example 4", {4, 3, 2, 1.5, 1}, {4, 2, 2, 2, 1}, {4, 1, 0, -0.5, -1}, {4, 2, 2, 2, 1});
}

TEST(InversionFormula, PaperExample4TheQuarticsQuadraticFormulaThroughItsFourthBasePoint) {
  const auto plan = bezinv::make_plan(example4());
  // The fourth base point (1, 1) = P(t = -1) = P(s = 0): the paper's t = x(x-1) / (y(y-1)), so
  // s = t + 1 = (x(x-1) + y(y-1)) / (y(y-1)).
  const InversionFormula formula(plan, FormulaChoice{{0.0}});
  EXPECT_EQ(formula.degree(), 2);
  expect_same_function(
      formula, [](double x, double y) { return (x * (x - 1) + y * (y - 1)) / (y * (y - 1)); }, 1e-10);
  // P* = (-1, 2/3): t* = -9 (s* = -8), and P(t*) ~ (-0.56314, 0.89012).
  const double s = formula(-1.0, 2.0 / 3.0);
  EXPECT_NEAR(s, -8.0, 1e-10);
  const auto p = example4().point(s);
  EXPECT_NEAR(p[0], -0.56314, 5e-6);
  EXPECT_NEAR(p[1], 0.89012, 5e-6);
}

TEST(InversionFormula, PaperExample4TheQuarticsThreeDoublePointsAreBasePoints) {
  const auto plan = bezinv::make_plan(example4());
  const InversionFormula formula(plan, FormulaChoice{{0.0}});
  const auto base = bezinv::base_points(plan, formula);
  auto find = [&](double x, double y) -> const bezinv::BasePoint* {
    for (const auto& p : base.points)
      if (std::hypot(p.point[0] - x, p.point[1] - y) < 1e-9) return &p;
    return nullptr;
  };
  const double r2 = std::sqrt(2.0);
  // (0, 1) at t = -1 +- sqrt 2, (1, 0) at t = 1 +- sqrt 2, (0, 0) at t = +-i; s = t + 1.
  const auto* a = find(0, 1);
  ASSERT_NE(a, nullptr);
  EXPECT_EQ(a->kind, BasePointKind::double_point);
  ASSERT_EQ(a->parameters.size(), 2u);
  EXPECT_NEAR(a->parameters[0].real(), -r2, 1e-10);
  EXPECT_NEAR(a->parameters[1].real(), r2, 1e-10);
  const auto* b = find(1, 0);
  ASSERT_NE(b, nullptr);
  EXPECT_EQ(b->kind, BasePointKind::double_point);
  ASSERT_EQ(b->parameters.size(), 2u);
  EXPECT_NEAR(b->parameters[0].real(), 2 - r2, 1e-10);
  EXPECT_NEAR(b->parameters[1].real(), 2 + r2, 1e-10);
  const auto* c = find(0, 0);
  ASSERT_NE(c, nullptr);
  EXPECT_EQ(c->kind, BasePointKind::isolated_point);
  ASSERT_EQ(c->parameters.size(), 2u);
  EXPECT_NEAR(c->parameters[0].real(), 1.0, 1e-10);
  EXPECT_NEAR(std::abs(c->parameters[0].imag()), 1.0, 1e-10);
  EXPECT_NEAR(std::abs(c->parameters[1] - std::conj(c->parameters[0])), 0.0, 1e-10);
  const auto* d = find(1, 1);
  ASSERT_NE(d, nullptr);
  EXPECT_EQ(d->kind, BasePointKind::simple);
  EXPECT_NEAR(d->parameters[0].real(), 0.0, 1e-10);
  EXPECT_EQ(base.points.size(), 4u);
}

TEST(InversionFormula, ALineIsInvertedByOrthogonalProjection) {
  // A rational line, unevenly parametrized: N / M of an off-line point is the parameter of its
  // foot on the line.
  const auto curve = Curve::rational_bezier("line", {{1, 2}, {4, 6}}, {1, 3});
  const InversionFormula formula(bezinv::make_plan(curve));
  for (double t : {-0.2, 0.0, 0.3, 0.9, 1.7}) {
    const auto p = curve.point(t);
    const double along = 0.7;  // off the line along its normal (-4, 3) / 5
    EXPECT_NEAR(formula(p[0] - 4 * along / 5, p[1] + 3 * along / 5), t, 1e-13);
  }
}

TEST(InversionFormula, EveryKindAndDegreeGivesTheParameterOfAPointMadeFromIt) {
  // Degrees 1-20 (separate denominators 1-10: their homogeneous degree is twice). Under the
  // sanitizers, where the SVD runs unoptimized (a degree-20 system takes seconds there), degrees
  // 1-8 (separate denominators 1-4).
  std::mt19937_64 rng(20261203);
  std::uniform_real_distribution<double> parameter(0.0, 1.0);
  for (const auto kind : bezinv::test_support::kAllKinds)
    for (int n = 1; n <= (kind == bezinv::CurveKind::rational ? 10 : 20); ++n) {
      const bool sanitized = bezinv::test_support::kSanitizerThinning > 1;
      if (sanitized && n > (kind == bezinv::CurveKind::rational ? 4 : 8)) continue;
      for (const auto polygon : {bezinv::datasets::ControlPolygon::unit_square, bezinv::datasets::ControlPolygon::perturbed_arc}) {
        const Curve curve = bezinv::datasets::random_curve(kind, n, rng, polygon);
        const auto plan = bezinv::make_plan(curve);
        const InversionFormula formula(plan);
        EXPECT_LE(formula.null_ratio(), 1e-11) << to_string(kind) << " degree " << n;
        EXPECT_LE(formula.segment_error(), 1e-8) << to_string(kind) << " degree " << n;
        for (int k = 0; k < 20; ++k) {
          const double t = parameter(rng);
          const auto p = curve.point(t);
          EXPECT_NEAR(formula(p[0], p[1]), t, 1e-8) << to_string(kind) << " degree " << n << " t " << t;
        }
      }
    }
}

TEST(InversionFormula, ACurveTracedTwiceHasNoFormula) {
  // P(t) = Q(t^2): every point has the parameters t and -t, so no N / M can give both.
  std::mt19937_64 rng(11);
  for (const auto kind : bezinv::test_support::kAllKinds)
    for (int m = 1; m <= 2; ++m) {  // beyond, see InversionFormula::segment_error
      const auto plan = bezinv::make_plan(bezinv::datasets::improper(bezinv::datasets::random_curve(kind, m, rng)));
      EXPECT_THROW(InversionFormula{plan}, bezinv::FormulaError) << to_string(kind) << " Q of degree " << m;
    }
}

TEST(InversionFormula, AConstructedDoublePointIsABasePointWithItsTwoParameters) {
  std::mt19937_64 rng(12);
  std::uniform_real_distribution<double> parameter(0.05, 0.95);
  for (const auto kind : {bezinv::CurveKind::bezier, bezinv::CurveKind::rational_bezier})
    for (int n = 3; n <= 7; ++n)
      for (int trial = 0; trial < 3; ++trial) {
        double t1 = parameter(rng), t2 = parameter(rng);
        if (std::abs(t1 - t2) < 0.1) continue;
        if (t1 > t2) std::swap(t1, t2);
        const Curve curve = bezinv::datasets::with_self_intersection(kind, n, t1, t2, rng);
        const auto plan = bezinv::make_plan(curve);
        const InversionFormula formula(plan);
        const auto base = bezinv::base_points(plan, formula);
        const auto p = curve.point(t1);
        bool found = false;
        for (const auto& b : base.points)
          if (b.kind == BasePointKind::double_point && std::abs(b.parameters[0].real() - t1) < 1e-7 &&
              std::abs(b.parameters[1].real() - t2) < 1e-7) {
            found = true;
            EXPECT_NEAR(b.point[0], p[0], 1e-8);
            EXPECT_NEAR(b.point[1], p[1], 1e-8);
          }
        EXPECT_TRUE(found) << to_string(kind) << " degree " << n << " t1 " << t1 << " t2 " << t2;
      }
}

TEST(InversionFormula, AConstructedCuspIsABasePointWithADoubleParameter) {
  std::mt19937_64 rng(13);
  std::uniform_real_distribution<double> parameter(0.1, 0.9);
  for (const auto kind : {bezinv::CurveKind::bezier, bezinv::CurveKind::rational_bezier})
    for (int n = 3; n <= 6; ++n) {
      const double tc = parameter(rng);
      const Curve curve = bezinv::datasets::with_cusp(kind, n, tc, rng);
      const auto plan = bezinv::make_plan(curve);
      const auto base = bezinv::base_points(plan, InversionFormula(plan));
      bool found = false;
      for (const auto& b : base.points)
        if (b.kind == BasePointKind::cusp && std::abs(b.parameters[0].real() - tc) < 1e-5) found = true;
      EXPECT_TRUE(found) << to_string(kind) << " degree " << n << " tc " << tc;
    }
}

}  // namespace
