// engine/src/plan.cpp: make_plans, the plans of many curves in parallel, against make_plan one at
// a time (the same numbers, in order) and its error for curves that fail validation.
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstring>
#include <string>
#include <limits>
#include <random>
#include <vector>

#include "support/bits.hpp"
#include "bezinv/datasets/random_curve.hpp"
#include "plan_data.hpp"
#include "bezinv/plan.hpp"

namespace bezinv {
namespace {

using test_support::same_bits;

std::vector<Curve> random_curves(std::size_t count, std::mt19937_64& rng) {
  std::vector<Curve> curves;
  for (std::size_t i = 0; i < count; ++i) {
    const CurveKind kind = i % 3 == 0 ? CurveKind::rational : CurveKind::rational_bezier;
    curves.push_back(datasets::random_curve(kind, 2 + static_cast<int>(i % 19), rng,
                                            i % 2 ? datasets::ControlPolygon::perturbed_arc
                                                  : datasets::ControlPolygon::unit_square));
    curves.back().id = std::to_string(i);
  }
  return curves;
}

TEST(MakePlans, TheSamePlansAsOneAtATimeInOrder) {
  std::mt19937_64 rng(31);
  const std::vector<Curve> curves = random_curves(120, rng);
  for (int threads : {1, 2, 0}) {
    const std::vector<InversionPlan> plans = make_plans(curves, threads);
    ASSERT_EQ(plans.size(), curves.size());
    for (std::size_t i = 0; i < curves.size(); ++i) {
      SCOPED_TRACE(testing::Message() << "threads " << threads << ", curve " << i);
      const detail::PlanData one = detail::plan_data(make_plan(curves[i]));
      EXPECT_EQ(plans[i].curve().id, curves[i].id);
      EXPECT_EQ(plans[i].degree(), one.degree);
      EXPECT_EQ(bezinv::detail::plan_data(plans[i]).isolation_pieces, one.isolation_pieces);
      EXPECT_TRUE(same_bits(bezinv::detail::plan_data(plans[i]).B0, one.B0));
      EXPECT_TRUE(same_bits(bezinv::detail::plan_data(plans[i]).By, one.By));
      EXPECT_TRUE(same_bits(bezinv::detail::plan_data(plans[i]).isolation_boxes, one.isolation_boxes));
      EXPECT_TRUE(same_bits(bezinv::detail::plan_data(plans[i]).isolation_far, one.isolation_far));
      EXPECT_TRUE(same_bits(bezinv::detail::plan_data(plans[i]).isolation_unique, one.isolation_unique));
    }
  }
  EXPECT_TRUE(make_plans({}, 2).empty());
}

// What a user sees of a plan: a cubic given elevated to degree 5 (in double, rounded as a CAD system would) is
// inverted at degree 3; the diagonal is that of its control points' box, from the points as given.
TEST(InversionPlan, AccessorsSayWhatThePlanIsFor) {
  // (0,0) (1,2) (3,2) (4,0) elevated twice.
  const std::vector<std::array<double, 2>> cubic{{0, 0}, {1, 2}, {3, 2}, {4, 0}};
  std::vector<std::array<double, 2>> points = cubic;
  for (int times = 0; times < 2; ++times) {  // P'_i = i/(m+1) P_{i-1} + (1 - i/(m+1)) P_i
    const int m = static_cast<int>(points.size()) - 1;
    std::vector<std::array<double, 2>> up(points.size() + 1);
    up.front() = points.front();
    up.back() = points.back();
    for (int i = 1; i <= m; ++i)
      for (int k = 0; k < 2; ++k)
        up[i][k] = (i * points[i - 1][k] + (m + 1 - i) * points[i][k]) / (m + 1);
    points = up;
  }
  const Curve curve = Curve::bezier("elevated", points);
  const InversionPlan plan = make_plan(curve);
  EXPECT_EQ(plan.curve().id, "elevated");
  EXPECT_EQ(plan.input_degree(), 5);
  EXPECT_EQ(plan.degree(), 3);
  EXPECT_TRUE(plan.usable());
  EXPECT_STREQ(plan.reason(), "");
  double x_max = 0, y_max = 0;
  for (const auto& p : points) x_max = std::max(x_max, p[0]), y_max = std::max(y_max, p[1]);
  EXPECT_DOUBLE_EQ(plan.diagonal(), std::hypot(x_max, y_max));  // the box is [0, x_max] x [0, y_max]

  const InversionPlan coincide = make_plan(Curve::bezier("dot", {{1, 2}, {1, 2}, {1, 2}}));
  EXPECT_FALSE(coincide.usable());
  EXPECT_NE(std::string(coincide.reason()), "");

  // An empty plan (vectors of plans are sized before they are filled) is not usable either.
  const InversionPlan empty;
  EXPECT_FALSE(empty.usable());
  EXPECT_NE(std::string(empty.reason()), "");

  // Copies share the plan: the same data, not a new computation.
  const InversionPlan copy = plan;
  EXPECT_EQ(&detail::plan_data(copy), &detail::plan_data(plan));
}

// Two bad curves among good ones: the error names the first, whichever thread met it.
TEST(MakePlans, NamesTheFirstCurveThatFailsValidation) {
  std::mt19937_64 rng(32);
  std::vector<Curve> curves = random_curves(300, rng);
  curves[217].x_num[1] = std::numeric_limits<double>::quiet_NaN();
  curves[143].y_den = {1.0, -1.0, 1.0};  // a pole inside the segment (and a length mismatch)
  for (int threads : {1, 2}) {
    try {
      make_plans(curves, threads);
      ADD_FAILURE() << "no PlansError";
    } catch (const PlansError& e) {
      EXPECT_EQ(e.index, 143u);
      std::string expected;
      try {
        make_plan(curves[143]);
      } catch (const CurveError& one) {
        expected = one.what();
      }
      EXPECT_FALSE(expected.empty());
      EXPECT_EQ(std::string(e.what()), expected);
    }
  }
}

}  // namespace
}  // namespace bezinv
