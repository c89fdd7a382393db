#pragma once
// Bit-for-bit comparison of doubles (and the NaN tests feed in): the engine promises the same
// bits across paths, kernels and thread counts, which == cannot say (it equates +0 and -0, and
// never NaN with NaN).
#include <bit>
#include <cstddef>
#include <cstdint>
#include <limits>
#include <vector>

namespace bezinv::test_support {

inline bool same_bits(double a, double b) { return std::bit_cast<std::uint64_t>(a) == std::bit_cast<std::uint64_t>(b); }

inline bool same_bits(const std::vector<double>& a, const std::vector<double>& b) {
  if (a.size() != b.size()) return false;
  for (std::size_t i = 0; i < a.size(); ++i)
    if (!same_bits(a[i], b[i])) return false;
  return true;
}

inline constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

}  // namespace bezinv::test_support
