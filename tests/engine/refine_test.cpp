// engine/src/refine.cpp's safeguarded Newton and the kernels' lane-batched copy of it
// (Implementation::rational_newton) must give the same bits: the fast path refines with the kernel,
// the SVD path with refine_parameter, and tests/engine/invert_property_test.cpp relies on both
// agreeing. Starts range from the quadratic region to anywhere on the segment (line searches,
// clamping at the ends, Gauss-Newton where the distance is concave), points from on the curve to
// far off it, one and separate denominators. The accuracy of the refinement itself is checked
// against constructed points in tests/kernels/rational_newton_test.cpp.
#include <gtest/gtest.h>

#include <cstring>
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
  const kernels::NewtonSettings settings{kNewtonMaxIterations, kNewtonMaxStep, kNewtonTrustedStep, kNewtonMaxHalvings,
                                         kNewtonFinalStep};
  for (const kernels::Implementation* implementation : kernels::available_implementations()) {
    std::mt19937_64 rng(42);
    std::uniform_real_distribution<double> unit(0.0, 1.0), coordinate(-1.0, 1.0);
    int compared = 0, line_searches = 0;
    for (int n = 1; n <= 24; ++n)
      for (bool common : {true, false}) {
        // refine_parameter reads only the degree and the four polynomials
        const detail::PlanData plan = test_support::random_polynomials_plan(n, common, rng);
        std::vector<double> u, v, t, distance;
        for (int k = 0; k < 37; ++k) {
          const double t_true = unit(rng);
          const auto p = plan.normalized_point(t_true);
          const double noise = k % 3 == 0 ? 0.0 : std::pow(10.0, -1.0 - k % 9);
          u.push_back(p[0] + noise * coordinate(rng));
          v.push_back(p[1] + noise * coordinate(rng));
          // Near the answer, anywhere, or exactly at an end.
          t.push_back(k % 5 == 0 ? unit(rng) : k % 7 == 0 ? static_cast<double>(k % 2) : t_true + 1e-3 * coordinate(rng));
          t.back() = std::clamp(t.back(), 0.0, 1.0);
        }
        std::vector<double> start = t;
        distance.assign(t.size(), 0.0);
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

}  // namespace
}  // namespace bezinv
