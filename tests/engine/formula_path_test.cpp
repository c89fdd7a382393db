// The formula path (engine/src/pipeline/formula_path.hpp) on curves of degree 4..20, whose formula
// has degree n - 2. Its algebraic step: the lane-batched kernel the batches take
// (Implementation::formula_parameter) gives the scalar formula_parameter's bits on every
// implementation, at points on the curve (made exactly from a known t), near it, off it, and at
// the points where neither is used (beyond kFormulaPathMaxCoordinate, NaN, infinite); on the curve
// both are the known t to the formula's accuracy (its segment_error). Where the default takes it:
// a call with enough points to repay making the formula.
#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <limits>
#include <random>
#include <span>
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
