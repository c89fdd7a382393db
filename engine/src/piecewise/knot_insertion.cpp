#include "piecewise/knot_insertion.hpp"

#include <algorithm>
#include <cstddef>

namespace bezinv::detail {

void insert_knot(HomogeneousSpline& spline, double u) {
  const auto& U = spline.knots;
  const std::ptrdiff_t p = spline.degree;
  const std::ptrdiff_t k = std::upper_bound(U.begin(), U.end(), u) - U.begin() - 1;
  const std::ptrdiff_t s = std::count(U.begin(), U.end(), u);
  const auto& P = spline.points;
  std::vector<std::array<double, 4>> Q;
  Q.reserve(P.size() + 1);
  for (std::ptrdiff_t i = 0; i <= k - p; ++i) Q.push_back(P[i]);
  for (std::ptrdiff_t i = k - p + 1; i <= k - s; ++i) {
    const double a = (u - U[i]) / (U[i + p] - U[i]);
    std::array<double, 4> q;
    for (int c = 0; c < 4; ++c) q[c] = a * P[i][c] + (1 - a) * P[i - 1][c];
    Q.push_back(q);
  }
  for (std::ptrdiff_t i = k - s; i < static_cast<std::ptrdiff_t>(P.size()); ++i) Q.push_back(P[i]);
  spline.points = std::move(Q);
  spline.knots.insert(spline.knots.begin() + k + 1, u);
}

std::vector<HomogeneousSpan> bezier_decomposition(HomogeneousSpline spline) {
  const std::size_t p = static_cast<std::size_t>(spline.degree);
  const double a = spline.knots[p], b = spline.knots[spline.knots.size() - 1 - p];
  std::vector<double> distinct;
  for (const double u : spline.knots)
    if (u >= a && u <= b && (distinct.empty() || u != distinct.back())) distinct.push_back(u);
  for (const double u : distinct)
    for (auto s = static_cast<std::size_t>(std::count(spline.knots.begin(), spline.knots.end(), u)); s < p; ++s)
      insert_knot(spline, u);
  const auto& U = spline.knots;
  std::vector<HomogeneousSpan> spans;
  for (std::size_t j = p; j + p + 1 < U.size(); ++j) {
    if (!(U[j] < U[j + 1])) continue;
    spans.push_back({std::vector<std::array<double, 4>>(spline.points.begin() + static_cast<std::ptrdiff_t>(j - p),
                                                        spline.points.begin() + static_cast<std::ptrdiff_t>(j + 1)),
                     U[j], U[j + 1]});
  }
  return spans;
}

}  // namespace bezinv::detail
