// The linear formula of conics and cubics the formula path takes by default at degree 3
// (engine/src/formula/linear_inversion_formula.hpp): against Wang & Joe's worked examples (the
// paper's own formulae, as functions of the plane), against points made in exact arithmetic from a
// known t (tests/support/known_parameter.hpp), and against the general construction
// (bezinv/inversion_formula.hpp), which reaches the same formula another way.
#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <limits>
#include <random>
#include <string>
#include <vector>

#include "bezinv/datasets/random_curve.hpp"
#include "bezinv/inversion_formula.hpp"
#include "bezinv/kernels/batch.hpp"
#include "bezinv/plan.hpp"
#include "bezinv/tolerances.hpp"
#include "formula/linear_inversion_formula.hpp"
#include "pipeline/formula_path.hpp"
#include "plan_data.hpp"
#include "support/bits.hpp"
#include "support/known_parameter.hpp"

namespace bezinv {
namespace {

// The plan's linear formula as a function of the input's (x, y).
double linear_formula_at(const InversionPlan& plan, double x, double y) {
  const detail::PlanData& data = detail::plan_data(plan);
  const auto uv = data.normalize(x, y);
  return detail::formula_parameter(data.low_degree_formula, uv[0], uv[1]);
}

// Both formulae of one pencil are the same function of the plane (Theorem 4), so they are compared
// at points spread over it, away from the pencil's centre (where either is 0/0).
template <class Expected>
void expect_same_function(const InversionPlan& plan, Expected expected, double tolerance = 1e-11) {
  ASSERT_TRUE(detail::plan_data(plan).low_degree_formula.usable);
  std::mt19937_64 rng(17);
  std::uniform_real_distribution<double> coordinate(-3.0, 3.0);
  int compared = 0;
  for (int k = 0; k < 200; ++k) {
    const double x = coordinate(rng), y = coordinate(rng);
    const double want = expected(x, y), got = linear_formula_at(plan, x, y);
    if (!std::isfinite(want) || std::abs(want) > 1e3 || std::isnan(got)) continue;
    EXPECT_NEAR(got, want, tolerance * (1.0 + std::abs(want))) << "at (" << x << ", " << y << ")";
    ++compared;
  }
  EXPECT_GT(compared, 150);
}

TEST(LinearInversionFormula, PaperExample1TheSemicircleIsFormula12) {
  // Kind `rational` with one denominator written out for each coordinate: centre P(inf) = (-1, 0).
  const auto plan = make_plan(Curve::rational("semicircle", {0, 1, 0}, {1, 0, 1}, {1, 0, -1}, {1, 0, 1}));
  ASSERT_TRUE(detail::plan_data(plan).common_denominator);
  expect_same_function(plan, [](double x, double y) { return (x - y + 1) / (2 * (x + 1)); });
}

TEST(LinearInversionFormula, PaperExample2TheReparametrizedSemicircleIsFormula15) {
  const auto plan = make_plan(Curve::rational("14", {0, 0.5, 0}, {0.25, 0, 1}, {0.25, 0, -1}, {0.25, 0, 1}));
  expect_same_function(plan, [](double x, double y) { return (2 * x - y + 1) / (4 * x + 3 * y + 5); });
}

TEST(LinearInversionFormula, PaperExample3TheCubicsFormula) {
  const auto plan = make_plan(Curve::rational_bezier("example 3", {{0, 0}, {1, 1}, {0, 1}, {1, 0}}, {1, 2, 2, 1}));
  expect_same_function(plan, [](double x, double y) { return (5 * y - 6 * x) / (10 * y - 6); });
  // Its centre is the double point (1/2, 3/5), where N and M both vanish: no parameter there.
  EXPECT_TRUE(std::isnan(linear_formula_at(plan, 0.5, 0.6)));
}

// Conics and cubics of both one-denominator kinds, on two control polygons: N/M at a point made
// exactly from t is t, to the formula's accuracy (kFormulaPathMaxSegmentError bounds it on the
// samples; here within 1e-10 at random t).
TEST(LinearInversionFormula, GivesTheParameterOfAPointMadeFromIt) {
  std::mt19937_64 rng(20261204);
  std::uniform_real_distribution<double> parameter(0.0, 1.0);
  int checked = 0;
  for (const CurveKind kind : {CurveKind::bezier, CurveKind::rational_bezier})
    for (int n = 2; n <= 3; ++n)
      for (const auto polygon : {datasets::ControlPolygon::unit_square, datasets::ControlPolygon::perturbed_arc})
        for (int c = 0; c < 10; ++c) {
          const Curve curve = datasets::random_curve(kind, n, rng, polygon);
          const auto plan = make_plan(curve);
          const std::string name = std::string(to_string(kind)) + " degree " + std::to_string(n) + " curve " + std::to_string(c);
          ASSERT_TRUE(detail::plan_data(plan).low_degree_formula.usable) << name;
          const test_support::ExactCurve exact(curve);
          for (int k = 0; k < 20; ++k) {
            const test_support::KnownParameter known = test_support::known_at(exact, parameter(rng));
            const double t = linear_formula_at(plan, known.point.x, known.point.y);
            if (std::isnan(t)) continue;  // M too small there: a base point near (a loop's double point)
            EXPECT_NEAR(t, known.t, 1e-10) << name;
            ++checked;
          }
        }
  EXPECT_GT(checked, 700);
}

// The fast path's batch of the formula (the formula_parameter kernel, every implementation) gives
// formula_parameter's bits at every point: on the curve, off it, by the pencil's centre (M = 0:
// NaN), beyond kFormulaPathMaxCoordinate, and NaN and infinite coordinates.
TEST(LinearInversionFormula, ABatchOfPointsGetsFormulaParametersBits) {
  std::mt19937_64 rng(41);
  std::uniform_real_distribution<double> parameter(0.0, 1.0), spread(-4.0, 4.0);
  int defined = 0, undefined = 0;
  for (int n = 2; n <= 3; ++n)
    for (int c = 0; c < 8; ++c) {
      const Curve curve = datasets::random_curve(CurveKind::rational_bezier, n, rng,
                                                 datasets::ControlPolygon::perturbed_arc);
      const auto plan = make_plan(curve);
      const detail::PlanData& data = detail::plan_data(plan);
      const detail::FormulaPathData& f = data.low_degree_formula;
      ASSERT_TRUE(f.usable);
      const test_support::ExactCurve exact(curve);
      std::vector<double> u, v;
      for (int k = 0; k < 61; ++k) {
        const Point on = test_support::known_at(exact, parameter(rng)).point;
        const auto uv = data.normalize(on.x, on.y);
        u.push_back(uv[0] + (k % 3 == 0 ? 0.0 : 1e-3 * spread(rng)));
        v.push_back(uv[1] + (k % 3 == 0 ? 0.0 : 1e-3 * spread(rng)));
        u.push_back(spread(rng));
        v.push_back(spread(rng));
      }
      const double inf = std::numeric_limits<double>::infinity(), nan = std::numeric_limits<double>::quiet_NaN();
      const double big = 2 * kFormulaPathMaxCoordinate;
      for (const std::array<double, 2> odd : {std::array<double, 2>{f.centre_u, f.centre_v}, {big, 0.0}, {0.0, -big},
                                              {nan, 0.0}, {0.0, inf}, {-inf, inf}})
        u.push_back(odd[0]), v.push_back(odd[1]);
      for (const kernels::Implementation* implementation : kernels::available_implementations()) {
        std::vector<double> t(u.size(), -7.0);
        implementation->formula_parameter(detail::plane_formula(f), u.size(), u.data(), v.data(), t.data());
        for (std::size_t l = 0; l < u.size(); ++l) {
          const double want = detail::formula_parameter(f, u[l], v[l]);
          EXPECT_TRUE(test_support::same_bits(t[l], want))
              << implementation->name << " point " << l << ": " << t[l] << " " << want;
          if (implementation == kernels::available_implementations().front()) ++(std::isnan(want) ? undefined : defined);
        }
      }
    }
  EXPECT_GT(defined, 1500);
  EXPECT_GE(undefined, 16 * 5);  // the odd points but the centre, at least
}

// The general construction (sampled conditions, SVDs, its own frame) reaches the same formula: a
// cubic's is unique up to a factor, a conic's once its centre is P(inf), both's default.
TEST(LinearInversionFormula, IsTheGeneralConstructionsFormula) {
  std::mt19937_64 rng(3);
  for (const CurveKind kind : {CurveKind::bezier, CurveKind::rational_bezier})
    for (int n = 2; n <= 3; ++n)
      for (int c = 0; c < 5; ++c) {
        const auto plan = make_plan(datasets::random_curve(kind, n, rng, datasets::ControlPolygon::perturbed_arc));
        const InversionFormula general(plan);
        expect_same_function(plan, [&](double x, double y) { return general(x, y); }, 1e-9);
      }
}

TEST(LinearInversionFormula, OnlyConicsAndCubicsWithOneDenominator) {
  std::mt19937_64 rng(5);
  for (int n : {1, 4, 5}) {
    const auto plan = make_plan(datasets::random_curve(CurveKind::rational_bezier, n, rng));
    EXPECT_FALSE(detail::plan_data(plan).low_degree_formula.usable) << "degree " << n;
  }
  // Separate denominators: a cubic's formula has degree 4 (twice the degree, less 2).
  const auto separate = make_plan(datasets::random_curve(CurveKind::rational, 3, rng));
  ASSERT_FALSE(detail::plan_data(separate).common_denominator);
  EXPECT_FALSE(detail::plan_data(separate).low_degree_formula.usable);
  // A straight cubic has no formula of its own (the plan inverts lines from p's roots).
  const auto straight = make_plan(Curve::bezier("line", {{0, 0}, {1, 1}, {2, 2}, {4, 4}}));
  EXPECT_FALSE(detail::plan_data(straight).low_degree_formula.usable);
}

// The default takes a conic's or cubic's formula where its weights are moderate, and the Bezout
// path where they are not (tolerances.hpp, kFormulaPathMaxWeightRatio) or the kind is another.
TEST(LinearInversionFormula, TheDefaultTakesItOnConicsAndCubicsOfModerateWeights) {
  const std::vector<std::array<double, 2>> square{{0, 0}, {1, 2}, {3, 2}, {4, 0}};
  const InvertOptions automatic{};
  auto takes = [&](const Curve& curve) { return detail::takes_formula_path(detail::plan_data(make_plan(curve)), automatic); };
  EXPECT_TRUE(takes(Curve::bezier("cubic", square)));
  EXPECT_TRUE(takes(Curve::rational_bezier("weights", square, {1, 20, 0.5, 100})));
  EXPECT_FALSE(takes(Curve::rational_bezier("wide weights", square, {1e-4, 1, 1, 1})));
  EXPECT_FALSE(takes(Curve::rational_bezier("negative weight", square, {1, -1, 1, 1})));
  EXPECT_TRUE(takes(Curve::rational_bezier("quarter circle", {{1, 0}, {1, 1}, {0, 1}}, {1, std::sqrt(0.5), 1})));
  EXPECT_FALSE(takes(Curve::bezier("quartic", {{0, 0}, {1, 2}, {2, 3}, {3, 2}, {4, 0}})));
  // Asked for, the formula path takes it whatever the weights.
  EXPECT_TRUE(detail::takes_formula_path(detail::plan_data(make_plan(Curve::rational_bezier("wide weights", square, {1e-4, 1, 1, 1}))),
                                         {.algebraic = Algebraic::formula}));
}

}  // namespace
}  // namespace bezinv
