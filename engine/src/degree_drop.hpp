#pragma once
// Whether the Bezout matrix at a point has a null direction at infinity (engine internal).
//
// Paper Sect. 4: when the power-basis leading coefficients of p = X - u0 W AND q = Y - v0 W both
// vanish, p and q share a root at infinity and the Bezout matrix of formal degree n gains a null
// direction that is not a point of the curve; such a point is inverted with the Sylvester matrix at
// the true degrees. "Vanish" is relative: |lead| <= kDegreeDropRatio * sum_i C(n,i) |c_i|.
#include <cstddef>
#include <cstdint>

#include "plan_data.hpp"

namespace bezinv::detail {

// For one point (u0, v0) in normalized coordinates: the reference.
bool degree_drops(const PlanData& plan, double u0, double v0);

// The same for count points at once: drops[l] = degree_drops(plan, u[l], v[l]), bit for bit the
// same decision (the same operations per lane), with a cheap test first that rules out almost
// every point in O(1) instead of O(n).
void degree_drops_batch(const PlanData& plan, const double* u, const double* v, std::size_t count,
                        std::uint8_t* drops);

}  // namespace bezinv::detail
