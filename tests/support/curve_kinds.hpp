#pragma once
// The kinds of plane curve the plan takes, for tests that run over all of them.
#include "bezinv/curve.hpp"

namespace bezinv::test_support {

inline constexpr CurveKind kAllKinds[] = {CurveKind::bezier, CurveKind::rational_bezier, CurveKind::rational};

}  // namespace bezinv::test_support
