#pragma once
// A factor common to all of a curve's polynomials (engine internal).
//
// If X, Y and W share a factor g of degree d >= 1, so do p = X - x0 W and q = Y - y0 W at every
// point: the Bezout matrix has nullity d + 1 on the whole curve and d everywhere else, and its
// null vector no longer names the point's parameter. The curve X/g, Y/g, W/g of degree n - d is
// the same curve (P = X/W is unchanged wherever g != 0). With separate denominators, a factor of
// x_num and x_den cancels in x = x_num / x_den alone, and one of y_num and y_den in y.
//
// The test is exact: a double is a dyadic rational, so the curve as given has an exact gcd. Most
// curves have none, and a gcd taken modulo the prime 2^61 - 1 shows that without big numbers (a
// common factor over Q stays common modulo a prime, unless the prime divides every coefficient of
// it but the constant one). Only where that gcd is not constant is the gcd found over Q (GMP), and
// the quotients rounded once to double. A factor that is common only up to rounding is not
// removed; the per-point search of the near-null space handles it (engine/src/invert.cpp).
#include "bezinv/curve.hpp"

namespace bezinv::detail {

// The curve without the factor its polynomials share exactly, at degree n - deg gcd (kind and id
// kept; separate denominators come back at one common degree). Unchanged when there is none.
Curve without_common_factor(const Curve& curve);

}  // namespace bezinv::detail
