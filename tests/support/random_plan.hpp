#pragma once
// A bare plan's data for the tests of engine-internal pieces that read only the degree and the
// four polynomials (refine.cpp, degree_drop.cpp): no make_plan, so no normalization in the way.
#include <random>

#include "plan_data.hpp"

namespace bezinv::test_support {

// Degree n; weights uniform in [0.5, 2] (one W for x and y when `common`), numerators w * [-1, 1].
inline detail::PlanData random_polynomials_plan(int n, bool common, std::mt19937_64& rng) {
  std::uniform_real_distribution<double> coordinate(-1.0, 1.0), weight(0.5, 2.0);
  detail::PlanData plan;
  plan.degree = n;
  for (int i = 0; i <= n; ++i) {
    const double w = weight(rng), w2 = common ? w : weight(rng);
    plan.x_num.push_back(w * coordinate(rng));
    plan.x_den.push_back(w);
    plan.y_num.push_back(w2 * coordinate(rng));
    plan.y_den.push_back(w2);
  }
  return plan;
}

}  // namespace bezinv::test_support
