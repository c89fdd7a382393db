// The formula path (engine/src/pipeline/formula_path.hpp) on curves of degree 4..20, whose formula
// has degree n - 2. Its algebraic step: the lane-batched kernel the batches take
// (Implementation::formula_parameter) gives the scalar formula_parameter's bits on every
// implementation, at points on the curve (made exactly from a known t), near it, off it, and at
// the points where neither is used (beyond kFormulaPathMaxCoordinate, NaN, infinite); on the curve
// both are the known t to the formula's accuracy (its segment_error). Where the default takes it:
// a call with enough points to repay making the formula. And a fast conic whose refinement on the
// formula path leaves points to the off-curve Newton kernel: every algebraic step within the
// accuracy model (tests/support/known_parameter.hpp).
#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <limits>
#include <random>
#include <span>
#include <string>
#include <utility>
#include <vector>

#include "bezinv/datasets/on_curve_points.hpp"
#include "bezinv/datasets/random_curve.hpp"
#include "bezinv/kernels/batch.hpp"
#include "bezinv/invert.hpp"
#include "bezinv/plan.hpp"
#include "bezinv/tolerances.hpp"
#include "pipeline/formula_path.hpp"
#include "plan_data.hpp"
#include "support/bits.hpp"
#include "support/same_row.hpp"
#include "support/known_parameter.hpp"

namespace bezinv {
namespace {

using test_support::same_bits;

TEST(FormulaPath, TheKernelGivesFormulaParametersBitsAtEveryDegree) {
  std::mt19937_64 rng(23);
  std::uniform_real_distribution<double> parameter(0.0, 1.0), spread(-1.0, 1.0);
  const double inf = std::numeric_limits<double>::infinity(), nan = std::numeric_limits<double>::quiet_NaN();
  int defined = 0, undefined = 0, curves = 0;
  for (const int n : {4, 5, 6, 8, 11, 14, 17, 20}) {
    const Curve curve =
        datasets::random_curve(CurveKind::rational_bezier, n, rng, datasets::ControlPolygon::perturbed_arc);
    const auto plan = make_plan(curve);
    const detail::PlanData& data = detail::plan_data(plan);
    const detail::FormulaPathData& f = detail::formula_path_data(data);
    if (!f.usable) continue;  // no formula accurate enough on this segment: the Bezout path's
    ++curves;
    ASSERT_EQ(f.degree, n - 2);
    const test_support::ExactCurve exact(curve);
    std::vector<double> u, v, known;
    for (int k = 0; k < 67; ++k) {
      const auto at = test_support::known_at(exact, parameter(rng));
      const auto uv = data.normalize(at.point.x, at.point.y);
      const double off = k % 3 == 0 ? 0.0 : std::pow(10.0, -1 - k % 7);
      u.push_back(uv[0] + off * spread(rng));
      v.push_back(uv[1] + off * spread(rng));
      known.push_back(k % 3 == 0 ? at.t : nan);
    }
    const double big = 2 * kFormulaPathMaxCoordinate;
    for (const std::array<double, 2> odd : {std::array<double, 2>{big, 0.0}, {0.0, -big}, {nan, 0.0}, {0.0, inf}})
      u.push_back(odd[0]), v.push_back(odd[1]), known.push_back(nan);
    for (const kernels::Implementation* implementation : kernels::available_implementations()) {
      std::vector<double> t(u.size(), -7.0);
      implementation->formula_parameter(detail::plane_formula(f), u.size(), u.data(), v.data(), t.data());
      for (std::size_t l = 0; l < u.size(); ++l) {
        const double want = detail::formula_parameter(f, u[l], v[l]);
        EXPECT_TRUE(same_bits(t[l], want)) << implementation->name << " n " << n << " point " << l << ": " << t[l]
                                           << " against " << want;
        if (!std::isnan(known[l]) && !std::isnan(want)) {
          EXPECT_NEAR(want, known[l], 1e-7) << "n " << n;
        }
        if (implementation == kernels::available_implementations().front()) ++(std::isnan(want) ? undefined : defined);
      }
    }
  }
  EXPECT_GE(curves, 6);
  EXPECT_GT(defined, 6 * 60);
  EXPECT_GE(undefined, 6 * 4);
}

// Algebraic::automatic takes the curve's own formula for a call of at least
// kCurveFormulaMinPoints[n] points (its making then repaid), and the Bezout path for fewer, with
// the same statuses and t to the accuracy bound either way; the rows do not depend on the thread
// count. Points made from known parameters.
// A conic with weights 1e-4 to 1e2 apart and x and y each their own denominator (the stress tool
// drew it): near its light end it moves fast (|P'| ~3e3 at t = 2e-5, the diagonal ~0.7) and bends
// faster (|P''| ~2.5e8). A point there that the formula path's refinement leaves to the off-curve
// Newton kernel (its first distance beyond 1e-10) must still end where its rounding puts it, on
// every algebraic step; the point at 1.9930388346245394e-05 ended 9.5e-16 off in t (10x the bound),
// residual 2.7e-12, when that kernel's last step of up to 1e-9 did not ask how much the curve
// bends over it (docs/kernels.md, nearest_newton).
TEST(FormulaPath, AFastConicNearItsLightEndOnEveryAlgebraicStep) {
  Curve curve;
  curve.kind = CurveKind::rational;
  curve.x_num = {1.5235207977554004e-05, 28.289328656690962, 0.00012186585351739298};
  curve.x_den = {0.0002863833741572606, 49.46298107028977, 0.00016343760945792746};
  curve.y_num = {0.6694301138497353, 5.8761194841126345e-06, 93.99434020080926};
  curve.y_den = {0.7671702712751561, 0.00012677404638355, 106.67998163362664};
  const test_support::ExactCurve exact(curve);
  const auto plan = make_plan(curve);
  ASSERT_TRUE(plan.usable()) << plan.reason();
  std::vector<double> parameters{1.9930388346245394e-05};
  for (int k = 0; k < 40; ++k) {
    const double from_end = std::pow(10.0, -6.0 + 3.0 * k / 40.0);
    parameters.push_back(k % 2 ? 1.0 - from_end : from_end);
  }
  std::vector<Point> points;
  std::vector<test_support::KnownParameter> known;
  for (const double t : parameters) {
    known.push_back(test_support::known_at(exact, t));
    points.push_back(known.back().point);
  }
  const std::pair<Algebraic, const char*> steps[] = {
      {Algebraic::formula, "formula"}, {Algebraic::automatic, "automatic"}, {Algebraic::bezout, "bezout"}};
  for (const auto& [algebraic, step] : steps) {
    test_support::Findings findings(std::string("fast conic, algebraic ") + step);
    std::vector<PointResult> rows(points.size());
    invert(plan, points, rows, {.threads = 1, .algebraic = algebraic});
    for (std::size_t k = 0; k < points.size(); ++k) test_support::expect_known(findings, "conic", exact, known[k], rows[k]);
  }
}

TEST(FormulaPath, AutomaticTakesTheCurvesFormulaForACallThatRepaysMakingIt) {
  std::mt19937_64 rng(29);
  std::uniform_real_distribution<double> parameter(0.0, 1.0);
  for (const int n : {4, 6}) {
    const Curve curve =
        datasets::random_curve(CurveKind::rational_bezier, n, rng, datasets::ControlPolygon::perturbed_arc);
    const auto plan = make_plan(curve);
    ASSERT_TRUE(detail::formula_path_data(detail::plan_data(plan)).usable);
    const std::size_t enough = detail::kCurveFormulaMinPoints[static_cast<std::size_t>(n)];
    std::vector<Point> points;
    std::vector<double> known;
    for (std::size_t k = 0; k < enough; ++k) {
      known.push_back(parameter(rng));
      points.push_back(datasets::on_curve(curve, known.back()));
    }
    auto run = [&](std::size_t count, InvertOptions options) {
      std::vector<PointResult> rows(count);
      invert(plan, std::span<const Point>(points.data(), count), rows, options);
      return rows;
    };
    auto formula_rows = [](const std::vector<PointResult>& rows) {
      std::size_t k = 0;
      for (const PointResult& r : rows) k += r.path == Path::formula;
      return k;
    };
    const auto automatic = run(enough, {.threads = 1});
    const auto two_threads = run(enough, {.threads = 2});
    const auto bezout = run(enough, {.threads = 1, .algebraic = Algebraic::bezout});
    EXPECT_GT(formula_rows(automatic), enough * 99 / 100) << "n " << n;
    for (std::size_t k = 0; k < enough; ++k) {
      ASSERT_TRUE(test_support::same_row(automatic[k], two_threads[k])) << "n " << n << " point " << k;
      ASSERT_EQ(automatic[k].status, bezout[k].status) << "n " << n << " point " << k;
      ASSERT_EQ(automatic[k].status, Status::ok) << "n " << n << " point " << k;
      EXPECT_NEAR(automatic[k].t, known[k], 1e-10) << "n " << n << " point " << k;
      EXPECT_NEAR(automatic[k].t, bezout[k].t, 1e-12) << "n " << n << " point " << k;
    }
    // One point fewer, or unrefined: the Bezout path, as bezout gives it.
    const auto fewer = run(enough - 1, {.threads = 1});
    EXPECT_EQ(formula_rows(fewer), 0u) << "n " << n;
    for (std::size_t k = 0; k < enough - 1; ++k)
      ASSERT_TRUE(test_support::same_row(fewer[k], bezout[k])) << "n " << n << " point " << k;
    EXPECT_EQ(formula_rows(run(enough, {.refine = false, .threads = 1})), 0u) << "n " << n;
  }
}

}  // namespace
}  // namespace bezinv
