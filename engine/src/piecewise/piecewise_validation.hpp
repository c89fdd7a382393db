#pragma once
// validate() for the piecewise kinds (bezinv/curve.hpp): each throws CurveError naming the field,
// its text starting with `who` ("curve \"id\": ").
#include <string>

#include "bezinv/curve.hpp"

namespace bezinv::detail {

void validate_nurbs(const Curve& curve, const std::string& who);
void validate_composite(const Curve& curve, const std::string& who);

}  // namespace bezinv::detail
