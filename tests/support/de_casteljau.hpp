#pragma once
// Points from known parameters for the end-to-end tests, computed here and not by the engine:
// de Casteljau on the control points (valid for t outside [0,1] too: it is the polynomial itself).
#include <array>
#include <vector>

namespace bezinv::test_support {

using Vec2 = std::array<double, 2>;

inline Vec2 de_casteljau(std::vector<Vec2> p, double t) {
  for (std::size_t level = 1; level < p.size(); ++level)
    for (std::size_t i = 0; i + level < p.size(); ++i)
      for (int c = 0; c < 2; ++c) p[i][c] = (1 - t) * p[i][c] + t * p[i + 1][c];
  return p[0];
}

// Rational de Casteljau on homogeneous points (w x, w y, w).
inline Vec2 rational_de_casteljau(const std::vector<Vec2>& p, const std::vector<double>& w, double t) {
  std::vector<std::array<double, 3>> h;
  for (std::size_t i = 0; i < p.size(); ++i) h.push_back({w[i] * p[i][0], w[i] * p[i][1], w[i]});
  for (std::size_t level = 1; level < h.size(); ++level)
    for (std::size_t i = 0; i + level < h.size(); ++i)
      for (int c = 0; c < 3; ++c) h[i][c] = (1 - t) * h[i][c] + t * h[i + 1][c];
  return {h[0][0] / h[0][2], h[0][1] / h[0][2]};
}

}  // namespace bezinv::test_support
