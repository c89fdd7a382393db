// engine/src/degree_drop.cpp: the batch test (with its cheap O(1) rejection first) must decide
// every point exactly as the per-point reference, and the reference must find the drop where the
// construction puts it: at (lead X / lead W, lead Y / lead W) both leading power coefficients of
// p = X - u0 W and q = Y - v0 W vanish (paper Sect. 4).
#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <limits>
#include <random>
#include <vector>

#include "bezinv/bernstein.hpp"
#include "plan_data.hpp"
#include "bezinv/plan.hpp"
#include "degree_drop.hpp"
#include "support/random_plan.hpp"

namespace bezinv {
namespace {

// A plan with only what the degree-drop test reads: the degree, the four polynomials and their
// leading power coefficients.
detail::PlanData random_plan(int n, bool common, std::mt19937_64& rng) {
  detail::PlanData plan = test_support::random_polynomials_plan(n, common, rng);
  plan.lead_x_num = power_leading_coefficient(plan.x_num);
  plan.lead_x_den = power_leading_coefficient(plan.x_den);
  plan.lead_y_num = power_leading_coefficient(plan.y_num);
  plan.lead_y_den = power_leading_coefficient(plan.y_den);
  return plan;
}

TEST(DegreeDrop, BatchDecidesAsTheReferenceAndFindsTheConstructedDrop) {
  std::mt19937_64 rng(3);
  std::uniform_real_distribution<double> coordinate(-1.0, 1.0);
  const double inf = std::numeric_limits<double>::infinity(), nan = std::numeric_limits<double>::quiet_NaN();
  int drops_found = 0, points = 0;
  for (int n = 1; n <= 24; ++n)
    for (bool common : {true, false}) {
      const detail::PlanData plan = random_plan(n, common, rng);
      const double u_star = plan.lead_x_num / plan.lead_x_den, v_star = plan.lead_y_num / plan.lead_y_den;
      std::vector<double> u, v;
      std::vector<int> expected;  // 1: must drop, 0: must not, -1: either (near the threshold)
      auto add = [&](double a, double b, int e) { u.push_back(a); v.push_back(b); expected.push_back(e); };
      // Around the drop point at relative distances from 0 to 1e-2 (the threshold is 1e-9 of the
      // coefficient size, so 1e-12 still drops and 1e-5 no longer does), on one coordinate or both.
      for (double d : {0.0, 1e-14, 1e-12, 1e-10, 1e-9, 1e-8, 1e-7, 1e-5, 1e-2}) {
        const int e = d <= 1e-12 ? 1 : d >= 1e-5 ? 0 : -1;
        add(u_star * (1 + d), v_star, e);
        add(u_star, v_star * (1 - d), e);
        add(u_star * (1 + d), v_star * (1 + d), e);
      }
      for (int k = 0; k < 150; ++k) add(coordinate(rng), coordinate(rng), -1);  // more than one chunk of 64
      // Not finite: the engine rejects such points before asking, but the batch must still agree.
      add(nan, v_star, -1);
      add(u_star, inf, -1);
      add(-inf, nan, -1);
      std::vector<std::uint8_t> drops(u.size(), 7);
      detail::degree_drops_batch(plan, u.data(), v.data(), u.size(), drops.data());
      for (std::size_t l = 0; l < u.size(); ++l) {
        SCOPED_TRACE("n=" + std::to_string(n) + (common ? " common" : " separate") + " point " + std::to_string(l));
        const bool reference = detail::degree_drops(plan, u[l], v[l]);
        ASSERT_EQ(drops[l], reference ? 1 : 0) << u[l] << ", " << v[l];
        if (expected[l] >= 0) {
          EXPECT_EQ(reference, expected[l] == 1) << u[l] << ", " << v[l];
        }
        drops_found += reference;
        ++points;
      }
    }
  RecordProperty("points", points);
  RecordProperty("drops", drops_found);
}

// Only one point of the plane drops; a batch without it must say so for every lane.
TEST(DegreeDrop, NoPointOfABatchFarFromTheDropPointDrops) {
  std::mt19937_64 rng(11);
  std::uniform_real_distribution<double> coordinate(-1.0, 1.0);
  const detail::PlanData plan = random_plan(5, true, rng);
  std::vector<double> u(64), v(64);
  for (std::size_t l = 0; l < u.size(); ++l) {
    u[l] = plan.lead_x_num / plan.lead_x_den + 0.1 + coordinate(rng) * 0.05;
    v[l] = coordinate(rng);
  }
  std::vector<std::uint8_t> drops(u.size(), 7);
  detail::degree_drops_batch(plan, u.data(), v.data(), u.size(), drops.data());
  for (std::size_t l = 0; l < u.size(); ++l) EXPECT_EQ(drops[l], 0) << "lane " << l;
}

}  // namespace
}  // namespace bezinv
