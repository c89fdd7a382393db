#pragma once
// What the constructed curves (self_intersection.cpp, cusp.cpp) share: a condition on a curve that
// is linear in one numerator's Bernstein coefficients, g . num = 0, met by the minimal-norm change
// of num.
#include <vector>

#include "bezinv/datasets/reference_evaluation.hpp"

namespace bezinv::datasets::detail {

// beta_i^n(t) = C(n, i) (1 - t)^(n-i) t^i, 0 <= i <= n.
inline Real beta(int n, int i, Real t) {
  Real b = 1;
  for (int j = 1; j <= i; ++j) b = b * (n - i + j) / j;
  for (int j = 0; j < n - i; ++j) b *= 1 - t;
  for (int j = 0; j < i; ++j) b *= t;
  return b;
}

// num -= g (g . num) / (g . g), twice: the second pass removes what rounding the first to doubles
// left.
inline void enforce_linear_condition(std::vector<double>& num, const std::vector<Real>& g) {
  Real gg = 0;
  for (Real gi : g) gg += gi * gi;
  for (int pass = 0; pass < 2; ++pass) {
    Real r = 0;
    for (std::size_t i = 0; i < num.size(); ++i) r += g[i] * num[i];
    for (std::size_t i = 0; i < num.size(); ++i) num[i] = static_cast<double>(num[i] - g[i] * r / gg);
  }
}

}  // namespace bezinv::datasets::detail
