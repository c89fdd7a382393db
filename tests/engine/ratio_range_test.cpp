// engine/src/ratio_range.cpp: the extent of x(t) = num(t) / den(t) over [0, 1], which sizes a plan,
// against the extent of points made on the curve; and the plans of curves whose ratios num_i / den_i
// do not bound them (a zero or negative denominator coefficient), inverting points made on them.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <vector>

#include "bezinv/bernstein.hpp"
#include "bezinv/curve.hpp"
#include "bezinv/invert.hpp"
#include "bezinv/plan.hpp"
#include "ratio_range.hpp"

namespace bezinv {
namespace {

// The extent of num / den sampled at 20,001 parameters: points on the curve, so the range must
// hold every one.
detail::RatioRange sampled_range(const std::vector<double>& num, const std::vector<double>& den) {
  detail::RatioRange r{std::numeric_limits<double>::infinity(), -std::numeric_limits<double>::infinity()};
  for (int k = 0; k <= 20000; ++k) {
    const double t = k / 20000.0;
    const double x = bernstein_value(num, t) / bernstein_value(den, t);
    r.lo = std::min(r.lo, x);
    r.hi = std::max(r.hi, x);
  }
  return r;
}

void expect_holds_and_near(const std::vector<double>& num, const std::vector<double>& den, double slack) {
  const detail::RatioRange range = detail::ratio_range(num, den);
  const detail::RatioRange sampled = sampled_range(num, den);
  const double width = sampled.hi - sampled.lo;
  EXPECT_LE(range.lo, sampled.lo + 1e-15 * (1 + std::abs(sampled.lo)));
  EXPECT_GE(range.hi, sampled.hi - 1e-15 * (1 + std::abs(sampled.hi)));
  // Not much wider than the segment: halving converges on it.
  EXPECT_GE(range.lo, sampled.lo - slack * width);
  EXPECT_LE(range.hi, sampled.hi + slack * width);
}

TEST(RatiosBound, OnlyWithEveryDenominatorCoefficientOfOneSignAndFiniteRatios) {
  EXPECT_TRUE(detail::ratios_bound(std::vector{1.0, 2.0, 3.0}, std::vector{1.0, 0.5, 2.0}));
  EXPECT_TRUE(detail::ratios_bound(std::vector{1.0, 2.0, 3.0}, std::vector{-1.0, -0.5, -2.0}));
  EXPECT_FALSE(detail::ratios_bound(std::vector{1.0, 0.0, -1.0}, std::vector{1.0, 0.0, 1.0}));
  EXPECT_FALSE(detail::ratios_bound(std::vector{1.0, 0.0, -1.0}, std::vector{1.0, -0.4, 1.0}));
  EXPECT_FALSE(detail::ratios_bound(std::vector{1.0, 1e300, -1.0}, std::vector{1.0, 1e-300, 1.0}));
}

TEST(RatioRange, TheRatiosThemselvesWhereTheyBound) {
  const detail::RatioRange r = detail::ratio_range(std::vector{1.0, -3.0, 4.0, 2.0}, std::vector{1.0, 2.0, 0.5, 1.0});
  EXPECT_EQ(r.lo, -1.5);
  EXPECT_EQ(r.hi, 8.0);
}

// The upper unit semicircle with its middle control point at infinity (weight 0, the direction
// (0, 1) as its numerator): x from -1 to 1, y from 0 to 1, where the ratios give no bound on y.
TEST(RatioRange, AControlPointAtInfinity) {
  expect_holds_and_near({1.0, 0.0, -1.0}, {1.0, 0.0, 1.0}, 0.05);
  expect_holds_and_near({0.0, 1.0, 0.0}, {1.0, 0.0, 1.0}, 0.05);
}

// A negative middle weight with no root of den on [0, 1]: the ratios' box [-2.5, 0] of y does not
// hold the curve, which reaches 1/0.6 at t = 1/2.
TEST(RatioRange, ANegativeDenominatorCoefficient) {
  expect_holds_and_near({1.0, 0.0, -1.0}, {1.0, -0.4, 1.0}, 0.05);
  expect_holds_and_near({0.0, 1.0, 0.0}, {1.0, -0.4, 1.0}, 0.05);
  expect_holds_and_near({0.3, -2.0, 5.0, 1.0, -0.7}, {2.0, -1.0, 3.0, -0.5, 1.5}, 0.05);
}

// Ratios that overflow on every piece (a huge numerator over a subnormal denominator) cost a
// bounded number of halvings, and give a range that still holds the ends.
TEST(RatioRange, OverflowingRatiosEndInBoundedTime) {
  const detail::RatioRange r = detail::ratio_range(std::vector{1.0, 1e308, 1e308, -1.0}, std::vector{1.0, 1e-310, 1e-310, 1.0});
  EXPECT_LE(r.lo, -1.0);
  EXPECT_GE(r.hi, 1.0);
}

// A curve whose ratios do not bound it is sized by its segment: a point made on it at a known t is
// answered ok with that t, and a point half the curve's height off it is off_curve (with the box
// of the ratios, [-1, 1] x [-2.5, 0], the curve's top at y = 1/0.6 was outside its box).
TEST(RatioRangePlan, ACurveWithANegativeWeightIsSizedByItsSegment) {
  const Curve curve = Curve::rational("negative-weight", {1.0, 0.0, -1.0}, {1.0, -0.4, 1.0}, {0.0, 1.0, 0.0},
                                      {1.0, -0.4, 1.0});
  const InversionPlan plan = make_plan(curve);
  const detail::RatioRange x = sampled_range(curve.x_num, curve.x_den), y = sampled_range(curve.y_num, curve.y_den);
  const double extent = std::hypot(x.hi - x.lo, y.hi - y.lo);
  EXPECT_GT(plan.diagonal(), extent * (1 - 1e-12));
  EXPECT_LT(plan.diagonal(), 1.05 * extent);
  for (const double t : {0.0, 0.2, 0.5, 0.65, 1.0}) {
    const auto p = curve.point(t);
    const PointResult r = invert_point(plan, Point{p[0], p[1]});
    EXPECT_EQ(r.status, Status::ok) << t;
    EXPECT_NEAR(r.t, t, 1e-12) << t;
  }
  const PointResult off = invert_point(plan, Point{0.0, 0.5 / 0.6});
  EXPECT_EQ(off.status, Status::off_curve);
}

// The semicircle with a control point at infinity, in space (the space plan sizes it the same way):
// before, its box was infinite and every point answered off_curve.
TEST(RatioRangePlan, ASpaceCurveWithAControlPointAtInfinity) {
  const Curve curve = Curve::space_rational("semicircle", {1.0, 0.0, -1.0}, {1.0, 0.0, 1.0}, {0.0, 1.0, 0.0},
                                            {1.0, 0.0, 1.0}, {0.5, 0.5, 0.5}, {1.0, 1.0, 1.0});
  const InversionPlan plan = make_plan(curve);
  ASSERT_TRUE(std::isfinite(plan.diagonal()));
  for (const double t : {0.0, 0.3, 0.5, 0.9, 1.0}) {
    const auto p = curve.point3(t);
    const PointResult r = invert_point(plan, Point3{p[0], p[1], p[2]});
    EXPECT_EQ(r.status, Status::ok) << t;
    EXPECT_NEAR(r.t, t, 1e-12) << t;
  }
  EXPECT_EQ(invert_point(plan, Point3{0.0, 0.5, 0.5}).status, Status::off_curve);
}

}  // namespace
}  // namespace bezinv
