// engine/src/refine.cpp's safeguarded Newton and the kernels' lane-batched copy of it
// (Implementation::rational_newton) must give the same bits: the fast path refines with the kernel,
// the SVD path with refine_parameter, and tests/engine/invert_property_test.cpp relies on both
// agreeing. Starts range from the quadratic region to anywhere on the segment (line searches,
// clamping at the ends, Gauss-Newton where the distance is concave), points from on the curve to
// far off it, one and separate denominators. The accuracy of the refinement itself is checked
// against constructed points in tests/kernels/rational_newton_test.cpp.
#include <gtest/gtest.h>

#include <cstring>
#include <limits>
#include <random>
#include <vector>

#include "support/bits.hpp"
#include "bezinv/kernels/batch.hpp"
#include "plan_data.hpp"
#include "bezinv/plan.hpp"
#include "bezinv/tolerances.hpp"
#include "support/random_plan.hpp"
#include "refine.hpp"

namespace bezinv {
namespace {

using test_support::same_bits;

kernels::NewtonSettings settings_for_test() {
  return {kNewtonMaxIterations, kNewtonMaxStep, kNewtonTrustedStep, kNewtonMaxHalvings, kNewtonFinalStep};
}

// 37 points of the plan's curve, on it or moved off it by 1e-1..1e-9, and a start for Newton each:
// near the answer, anywhere, or (with `at_ends`) exactly at an end of the segment.
struct NewtonLanes {
  std::vector<double> u, v, t;
};
NewtonLanes random_lanes(const detail::PlanData& plan, std::mt19937_64& rng, bool at_ends) {
  std::uniform_real_distribution<double> unit(0.0, 1.0), coordinate(-1.0, 1.0);
  NewtonLanes lanes;
  for (int k = 0; k < 37; ++k) {
    const double t_true = unit(rng);
    const auto p = plan.normalized_point(t_true);
    const double noise = k % 3 == 0 ? 0.0 : std::pow(10.0, -1.0 - k % 9);
    lanes.u.push_back(p[0] + noise * coordinate(rng));
    lanes.v.push_back(p[1] + noise * coordinate(rng));
    double start;
    if (k % 5 == 0)
      start = unit(rng);
    else if (at_ends && k % 7 == 0)
      start = static_cast<double>(k % 2);
    else
      start = t_true + 1e-3 * coordinate(rng);
    lanes.t.push_back(std::clamp(start, 0.0, 1.0));
  }
  return lanes;
}

// Horner's rule (curve_jet_horner, for the stationarity test) against de Casteljau (curve_jet):
// the same jet to the rounding of either, at every degree, over the whole segment.
TEST(Refine, HornersJetIsDeCasteljausToRounding) {
  std::mt19937_64 rng(8);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  for (int n = 1; n <= kMaxDegree; ++n)
    for (bool common : {true, false}) {
      detail::PlanData plan = test_support::random_polynomials_plan(n, common, rng);
      detail::horner_coefficients(plan);
      for (double t : {0.0, 1.0, 0.5, unit(rng), unit(rng), unit(rng), 1e-9, 1 - 1e-9}) {
        const detail::CurveJet a = detail::curve_jet(plan, t), b = detail::curve_jet_horner(plan, t);
        // Relative to the sizes of the terms: |x| ~ 1, |x'| ~ n, |x''| ~ n^2 (coordinates in [-1, 1]).
        const double bound = 1e-13 * n;
        EXPECT_NEAR(a.x, b.x, bound) << n << " " << t;
        EXPECT_NEAR(a.y, b.y, bound) << n << " " << t;
        EXPECT_NEAR(a.dx, b.dx, bound * n) << n << " " << t;
        EXPECT_NEAR(a.dy, b.dy, bound * n) << n << " " << t;
        EXPECT_NEAR(a.ddx, b.ddx, bound * n * n) << n << " " << t;
        EXPECT_NEAR(a.ddy, b.ddy, bound * n * n) << n << " " << t;
      }
    }
}

TEST(Refine, KernelGivesTheScalarRefinementsBits) {
  const kernels::NewtonSettings settings = settings_for_test();
  for (const kernels::Implementation* implementation : kernels::available_implementations()) {
    std::mt19937_64 rng(42);
    int compared = 0, line_searches = 0;
    for (int n = 1; n <= 24; ++n)
      for (bool common : {true, false}) {
        // refine_parameter reads only the degree and the four polynomials
        const detail::PlanData plan = test_support::random_polynomials_plan(n, common, rng);
        auto [u, v, t] = random_lanes(plan, rng, /*at_ends=*/true);
        const std::vector<double> start = t;
        std::vector<double> distance(t.size(), 0.0);
        const kernels::RationalCurve curve{n, plan.x_num.data(), plan.x_den.data(), plan.y_num.data(), plan.y_den.data()};
        implementation->rational_newton(curve, settings, t.size(), u.data(), v.data(), t.data(), distance.data());
        for (std::size_t l = 0; l < t.size(); ++l) {
          SCOPED_TRACE(std::string(implementation->name) + " n=" + std::to_string(n) + " lane " + std::to_string(l));
          const detail::Refined r = detail::refine_parameter(plan, u[l], v[l], start[l], true);
          ASSERT_FALSE(std::isnan(distance[l]));  // every start is in [0, 1], every distance plain
          EXPECT_TRUE(same_bits(t[l], r.t)) << t[l] << " vs " << r.t;
          EXPECT_TRUE(same_bits(distance[l], r.distance)) << distance[l] << " vs " << r.distance;
          ++compared;
          if (std::abs(start[l] - r.t) > kNewtonTrustedStep) ++line_searches;
        }
      }
    EXPECT_EQ(compared, 24 * 2 * 37);
    EXPECT_GE(line_searches, 300);  // the line search and clamping really were exercised
  }
}

// With Horner's jets the kernel's answers are not refine_parameter's bits, but the same nearest
// points to rounding, and stationary points as stationary_point tests them (the off-curve path
// takes them as its hints).
TEST(Refine, KernelOnHornersJetsEndsWhereTheScalarRefinementDoes) {
  for (const kernels::Implementation* implementation : kernels::available_implementations()) {
    std::mt19937_64 rng(43);
    int compared = 0, stationary = 0;
    for (int n = 1; n <= 24; ++n)
      for (bool common : {true, false}) {
        detail::PlanData plan = test_support::random_polynomials_plan(n, common, rng);
        detail::horner_coefficients(plan);
        auto [u, v, t] = random_lanes(plan, rng, /*at_ends=*/false);
        const std::vector<double> start = t;
        std::vector<double> distance(t.size(), 0.0);
        kernels::RationalCurve curve{n, plan.x_num.data(), plan.x_den.data(), plan.y_num.data(), plan.y_den.data()};
        curve.horner = plan.horner.data();
        implementation->rational_newton(curve, settings_for_test(), t.size(), u.data(), v.data(), t.data(),
                                        distance.data());
        for (std::size_t l = 0; l < t.size(); ++l) {
          SCOPED_TRACE(std::string(implementation->name) + " n=" + std::to_string(n) + " lane " + std::to_string(l));
          const detail::Refined r = detail::refine_parameter(plan, u[l], v[l], start[l], true);
          ASSERT_FALSE(std::isnan(distance[l]));
          // Both are minima of the same distance from the same start: the same one, to the
          // rounding of the two evaluations (|P'| ~ n here, distances ~ 1).
          if (!detail::stationary_point(plan, u[l], v[l], r.t, r.distance)) continue;  // stopped elsewhere (an end)
          EXPECT_NEAR(t[l], r.t, 1e-9) << start[l];
          EXPECT_NEAR(distance[l], r.distance, 1e-14 * n) << start[l];
          ++compared;
          // Stationary as the test sees it (cos(P - P0, P') <= 1e-8) wherever that is above the
          // rounding: off the curve by more than a tolerance (the off-curve path's points).
          if (distance[l] > 1e-7) {
            EXPECT_TRUE(detail::stationary_point(plan, u[l], v[l], t[l], distance[l]));
            ++stationary;
          }
        }
      }
    EXPECT_GE(compared, 900);
    EXPECT_GE(stationary, 500);
  }
}

// Every implementation's rational_slope gives curve_slope_horner's bits: P and P' at any t of the
// segment, both sides of 1/2 and the ends, every degree and both kinds of denominator.
TEST(Refine, KernelSlopeIsCurveSlopeHornersBits) {
  for (const kernels::Implementation* implementation : kernels::available_implementations()) {
    std::mt19937_64 rng(45);
    std::uniform_real_distribution<double> unit(0.0, 1.0);
    int compared = 0;
    for (int n = 1; n <= kMaxDegree; ++n)
      for (bool common : {true, false}) {
        detail::PlanData plan = test_support::random_polynomials_plan(n, common, rng);
        detail::horner_coefficients(plan);
        std::vector<double> t = {0.0, 1.0, 0.5, std::nextafter(0.5, 1.0), 1e-300};
        while (t.size() < 21) t.push_back(unit(rng));  // 21: not a multiple of any vector width
        std::vector<double> x(t.size()), y(t.size()), dx(t.size()), dy(t.size());
        kernels::RationalCurve curve{n, plan.x_num.data(), plan.x_den.data(), plan.y_num.data(), plan.y_den.data()};
        curve.horner = plan.horner.data();
        implementation->rational_slope(curve, t.size(), t.data(), x.data(), y.data(), dx.data(), dy.data());
        for (std::size_t l = 0; l < t.size(); ++l) {
          SCOPED_TRACE(std::string(implementation->name) + " n=" + std::to_string(n) + " t=" + std::to_string(t[l]));
          const detail::CurveJet j = detail::curve_slope_horner(plan, t[l]);
          EXPECT_TRUE(same_bits(x[l], j.x));
          EXPECT_TRUE(same_bits(y[l], j.y));
          EXPECT_TRUE(same_bits(dx[l], j.dx));
          EXPECT_TRUE(same_bits(dy[l], j.dy));
          ++compared;
        }
      }
    EXPECT_EQ(compared, kMaxDegree * 2 * 21);
  }
}

// stationary_point_lanes (many lanes at once) answers as stationary_point does lane by lane, for
// stationary points (refined), other parameters, the ends, and NaN.
TEST(Refine, StationaryPointLanesAnswersAsStationaryPointDoes) {
  std::mt19937_64 rng(44);
  std::uniform_real_distribution<double> unit(0.0, 1.0), coordinate(-1.0, 1.0);
  int yes = 0, no = 0;
  for (int n = 1; n <= kMaxDegree; ++n)
    for (bool common : {true, false}) {
      detail::PlanData plan = test_support::random_polynomials_plan(n, common, rng);
      detail::horner_coefficients(plan);
      std::vector<double> u, v, t, distance;
      for (std::size_t k = 0; k < 64; ++k) {  // a batch of lanes
        const auto p = plan.normalized_point(unit(rng));
        u.push_back(p[0] + 1e-2 * coordinate(rng));
        v.push_back(p[1] + 1e-2 * coordinate(rng));
        double at = k % 4 == 0 ? unit(rng) : k % 9 == 0 ? static_cast<double>(k % 2) : unit(rng);
        double d = std::hypot(plan.normalized_point(at)[0] - u.back(), plan.normalized_point(at)[1] - v.back());
        if (k % 4 != 0) {
          const detail::Refined r = detail::refine_parameter(plan, u.back(), v.back(), at, true);
          at = r.t, d = r.distance;
        }
        if (k == 13) at = std::numeric_limits<double>::quiet_NaN();
        t.push_back(at);
        distance.push_back(d);
      }
      std::vector<std::uint8_t> many(t.size(), 7);
      detail::stationary_point_lanes(plan, t.size(), u.data(), v.data(), t.data(), distance.data(), many.data());
      for (std::size_t l = 0; l < t.size(); ++l) {
        const bool one = detail::stationary_point(plan, u[l], v[l], t[l], distance[l]);
        EXPECT_EQ(many[l], one ? 1 : 0) << "n " << n << " lane " << l << " t " << t[l];
        (one ? yes : no) += 1;
      }
    }
  EXPECT_GE(yes, 1000);
  EXPECT_GE(no, 1000);
}

}  // namespace
}  // namespace bezinv
