#pragma once
// The pieces of the null-vector read-out (bezinv/null_vector.hpp) that the tests check on their own.
#include <span>

namespace bezinv::detail {

// Index i (1 <= i <= size-1) of the pair (z_{i-1}, z_i) that parameter_from_null_vector uses.
int null_vector_pair(std::span<const double> z);

// How far z is from the Bernstein form: the sine of the angle between z and the basis vector
// beta^{(N)}(t). Near 0 when z really is a (scaled) basis vector; a random mix of two basis
// vectors (nullity 2) gives an O(1) value. Scale-invariant.
double bernstein_form_defect(std::span<const double> z, double t);

}  // namespace bezinv::detail
