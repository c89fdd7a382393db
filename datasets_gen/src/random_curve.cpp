#include "bezinv/datasets/random_curve.hpp"

#include <array>
#include <cmath>
#include <numbers>
#include <stdexcept>
#include <string>
#include <vector>

#include "bezinv/datasets/random_numbers.hpp"

namespace bezinv::datasets {
namespace {

constexpr double kMinWeight = 0.5, kMaxWeight = 2.0;

std::vector<std::array<double, 2>> control_points(int degree, std::mt19937_64& rng, ControlPolygon polygon) {
  std::vector<std::array<double, 2>> points(degree + 1);
  if (polygon == ControlPolygon::unit_square) {
    for (auto& p : points) p = {uniform(rng, 0.0, 1.0), uniform(rng, 0.0, 1.0)};
    return points;
  }
  const double opening = uniform(rng, 90.0, 300.0) * std::numbers::pi / 180;
  const double start = uniform(rng, 0.0, 2 * std::numbers::pi);
  for (int i = 0; i <= degree; ++i) {
    const double angle = start + opening * i / degree;
    points[i] = {0.5 + 0.5 * std::cos(angle) + uniform(rng, -0.08, 0.08),
                 0.5 + 0.5 * std::sin(angle) + uniform(rng, -0.08, 0.08)};
  }
  return points;
}

std::vector<double> positive_coefficients(int degree, std::mt19937_64& rng) {
  std::vector<double> w(degree + 1);
  for (double& v : w) v = uniform(rng, kMinWeight, kMaxWeight);
  return w;
}

}  // namespace

const char* to_string(ControlPolygon polygon) {
  return polygon == ControlPolygon::unit_square ? "unit_square" : "perturbed_arc";
}

Curve random_curve(CurveKind kind, int degree, std::mt19937_64& rng, ControlPolygon polygon) {
  const auto points = control_points(degree, rng, polygon);
  Curve c;
  c.id = std::string("random-") + bezinv::to_string(kind) + "-" + std::to_string(degree) + "-" + to_string(polygon);
  c.kind = kind;
  c.x_num.resize(degree + 1);
  c.y_num.resize(degree + 1);
  switch (kind) {
    case CurveKind::bezier:
      c.x_den.assign(degree + 1, 1.0);
      c.y_den = c.x_den;
      break;
    case CurveKind::rational_bezier:
      c.x_den = positive_coefficients(degree, rng);
      c.y_den = c.x_den;
      break;
    case CurveKind::rational:
      c.x_den = positive_coefficients(degree, rng);
      c.y_den = positive_coefficients(degree, rng);
      break;
    case CurveKind::nurbs:
    case CurveKind::composite:  // made of Bezier curves: the generators make those
      throw std::invalid_argument(std::string("random_curve: no random curve of kind ") + bezinv::to_string(kind));
  }
  for (int i = 0; i <= degree; ++i) {
    c.x_num[i] = points[i][0] * c.x_den[i];
    c.y_num[i] = points[i][1] * c.y_den[i];
  }
  return c;
}

}  // namespace bezinv::datasets
