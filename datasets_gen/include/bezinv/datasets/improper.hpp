#pragma once
// An improperly parametrized curve: P(t) = Q(t^2). Every point has the two parameters t and -t
// (one on the segment, one on the extension), so the Bezout matrix has nullity 2 at every point of
// the curve: the engine must take both from its two-dimensional null space and answer the one on
// the segment.
#include "bezinv/curve.hpp"

namespace bezinv::datasets {

// Q of degree m (any kind) -> P(t) = Q(t^2) of degree 2m, same kind. In the Bernstein basis
//     beta_i^{(m)}(t^2) = C(m,i) (1-t^2)^{m-i} t^{2i},   1 - t^2 = (1-t) ((1-t) + 2t),
// and expanding ((1-t) + 2t)^{m-i} by the binomial theorem,
//     beta_i^{(m)}(t^2) = sum_{k=0}^{m-i} C(m,i) C(m-i,k) 2^k / C(2m, 2i+k) beta_{2i+k}^{(2m)}(t).
// All these weights are >= 0, so positive denominators stay positive. Each new coefficient is a
// sum of exact integer-ratio terms accumulated in long double and rounded once.
Curve improper(const Curve& curve);

}  // namespace bezinv::datasets
