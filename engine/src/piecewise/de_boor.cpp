#include "piecewise/de_boor.hpp"

#include <algorithm>

namespace bezinv::detail {

std::size_t knot_span(const HomogeneousSpline& spline, double u) {
  const auto& U = spline.knots;
  const std::size_t p = static_cast<std::size_t>(spline.degree), last = U.size() - 1 - p;  // domain [U[p], U[last]]
  std::size_t first_span = p, last_span = last - 1;
  while (first_span < last_span && !(U[first_span] < U[first_span + 1])) ++first_span;
  while (last_span > first_span && !(U[last_span] < U[last_span + 1])) --last_span;
  if (!(u >= U[first_span + 1])) return first_span;
  if (u >= U[last_span]) return last_span;
  // The last k with U[k] <= u: then U[k] <= u < U[k + 1], a non-empty interval.
  return static_cast<std::size_t>(std::upper_bound(U.begin(), U.end(), u) - U.begin()) - 1;
}

std::array<double, 4> de_boor(const HomogeneousSpline& spline, double u) {
  const int p = spline.degree;
  const std::size_t k = knot_span(spline, u);
  const auto& U = spline.knots;
  // d_j = P_{k-p+j}; level r: d_j = (1 - a) d_{j-1} + a d_j, a = (u - U[k-p+j]) / (U[k+1+j-r] - U[k-p+j]).
  std::vector<std::array<double, 4>> d(spline.points.begin() + static_cast<std::ptrdiff_t>(k - p),
                                       spline.points.begin() + static_cast<std::ptrdiff_t>(k + 1));
  for (int r = 1; r <= p; ++r)
    for (int j = p; j >= r; --j) {
      const std::size_t i = k - p + j;
      const double a = (u - U[i]) / (U[k + 1 + j - r] - U[i]);
      for (int c = 0; c < 4; ++c) d[j][c] = (1 - a) * d[j - 1][c] + a * d[j][c];
    }
  return d[p];
}

}  // namespace bezinv::detail
