#pragma once
// How the accuracy tests state what they measured: errors in units of the double's epsilon, and
// the worst figures recorded in the XML report (--gtest_output=xml).
#include <cstdio>
#include <string>

namespace bezinv::test_support {

// 2^-52, the spacing of doubles at 1 (DBL_EPSILON); the error bounds are written as multiples.
inline constexpr double kEps = 0x1p-52;
inline constexpr double kUnit = 0x1p-53;  // the unit round-off u = eps / 2

// Measured figures go to the XML report in scientific notation, three significant digits.
inline std::string sci(double x) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.2e", x);
  return buf;
}

}  // namespace bezinv::test_support
