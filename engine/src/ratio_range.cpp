#include "ratio_range.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <vector>

#include "bernstein_arithmetic.hpp"
#include "bezinv/tolerances.hpp"

namespace bezinv::detail {
namespace {

void include(double x, RatioRange& range) {
  range.lo = std::min(range.lo, x);
  range.hi = std::max(range.hi, x);
}

void include_ratios(std::span<const double> num, std::span<const double> den, RatioRange& range) {
  for (std::size_t i = 0; i < num.size(); ++i) include(num[i] / den[i], range);
}

void include_piece(const BernsteinPoly& num, const BernsteinPoly& den, int level, int& pieces, RatioRange& range) {
  ++pieces;
  // The whole segment's ratios where they bound it; once it has to be halved, pieces at least
  // kRatioRangeMinHalvings deep, so that the bound is near the extent (the gap between a piece's
  // ratios and its curve shrinks as the square of its width).
  if (ratios_bound(num, den) && (level == 0 || level >= kRatioRangeMinHalvings)) return include_ratios(num, den, range);
  if (level == kRatioRangeHalvings || pieces >= kRatioRangePieces) {
    // The piece's end points lie on the curve wherever den does not vanish there.
    for (const std::size_t i : {std::size_t{0}, num.size() - 1})
      if (den[i] != 0.0 && std::isfinite(num[i] / den[i])) include(num[i] / den[i], range);
    return;
  }
  BernsteinPoly num_left, num_right, den_left, den_right;
  halve(num, num_left, num_right);
  halve(den, den_left, den_right);
  include_piece(num_left, den_left, level + 1, pieces, range);
  include_piece(num_right, den_right, level + 1, pieces, range);
}

}  // namespace

bool ratios_bound(std::span<const double> num, std::span<const double> den) {
  const bool positive = std::all_of(den.begin(), den.end(), [](double d) { return d > 0; });
  const bool negative = std::all_of(den.begin(), den.end(), [](double d) { return d < 0; });
  if (!positive && !negative) return false;
  for (std::size_t i = 0; i < num.size(); ++i)
    if (!std::isfinite(num[i] / den[i])) return false;
  return true;
}

RatioRange ratio_range(std::span<const double> num, std::span<const double> den) {
  RatioRange range{std::numeric_limits<double>::infinity(), -std::numeric_limits<double>::infinity()};
  int pieces = 0;
  include_piece(BernsteinPoly(num.begin(), num.end()), BernsteinPoly(den.begin(), den.end()), 0, pieces, range);
  return range;
}

}  // namespace bezinv::detail
