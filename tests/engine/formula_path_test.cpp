// The formula path's algebraic step (engine/src/pipeline/formula_path.hpp) on curves of degree 4..20,
// whose formula has degree n - 2: the lane-batched kernel the batches take
// (Implementation::formula_parameter) gives the scalar formula_parameter's bits on every
// implementation, at points on the curve (made exactly from a known t), near it, off it, and at
// the points where neither is used (beyond kFormulaPathMaxCoordinate, NaN, infinite). On the curve
// both are the known t to the formula's accuracy (its segment_error).
#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <limits>
#include <random>
#include <vector>

#include "bezinv/datasets/random_curve.hpp"
#include "bezinv/kernels/batch.hpp"
#include "bezinv/plan.hpp"
#include "bezinv/tolerances.hpp"
#include "pipeline/formula_path.hpp"
#include "plan_data.hpp"
#include "support/bits.hpp"
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

}  // namespace
}  // namespace bezinv
