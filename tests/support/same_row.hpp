#pragma once
// Two rows the same, bit for bit (support/bits.hpp), status, path and reason included: what the
// engine promises a point whatever its batch, queue or thread count. On failure, both rows.
#include <gtest/gtest.h>

#include <cstring>
#include <sstream>

#include "bezinv/invert.hpp"
#include "support/bits.hpp"

namespace bezinv::test_support {

inline ::testing::AssertionResult same_row(const PointResult& a, const PointResult& b) {
  if (same_bits(a.t, b.t) && same_bits(a.t2, b.t2) && same_bits(a.residual, b.residual) &&
      same_bits(a.sigma_min, b.sigma_min) && same_bits(a.sigma_next, b.sigma_next) && a.status == b.status &&
      a.path == b.path && std::strcmp(a.reason, b.reason) == 0)
    return ::testing::AssertionSuccess();
  std::ostringstream s;
  s.precision(17);
  s << to_string(a.status) << " t " << a.t << " t2 " << a.t2 << " residual " << a.residual << " path "
    << to_string(a.path) << "; against " << to_string(b.status) << " t " << b.t << " t2 " << b.t2 << " residual "
    << b.residual << " path " << to_string(b.path);
  return ::testing::AssertionFailure() << s.str();
}

}  // namespace bezinv::test_support
