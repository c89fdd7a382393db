#pragma once
// The Sylvester path (paper Sect. 4): where p and q both lose degree at a point, B of formal
// degree n gains a null direction at infinity, and the parameter is read from the Sylvester matrix
// of p and q at their true degrees instead.
#include "pipeline/point_polynomials.hpp"

namespace bezinv::detail {

// The parameter from the left null vector of S(p, q) at the true degrees m and k: the Bernstein
// basis of degree m + k - 1 at the common root. NaN when p or q is constant.
double sylvester_parameter(const PointPolynomials& pq);

}  // namespace bezinv::detail
