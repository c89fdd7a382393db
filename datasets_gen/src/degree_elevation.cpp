#include "bezinv/datasets/degree_elevation.hpp"

#include <string>
#include <vector>

namespace bezinv::datasets {
namespace {

std::vector<double> elevated(const std::vector<double>& p) {
  const int n = static_cast<int>(p.size()) - 1;
  std::vector<double> q(n + 2);
  q[0] = p[0];
  q[n + 1] = p[n];
  for (int i = 1; i <= n; ++i) {
    const double a = static_cast<double>(i) / (n + 1);
    q[i] = a * p[i - 1] + (1 - a) * p[i];
  }
  return q;
}

}  // namespace

Curve degree_elevated(const Curve& curve, int times) {
  Curve c = curve;
  c.id = curve.id + "-elevated-" + std::to_string(times);
  for (int k = 0; k < times; ++k) {
    c.x_num = elevated(c.x_num);
    c.x_den = elevated(c.x_den);
    c.y_num = elevated(c.y_num);
    c.y_den = elevated(c.y_den);
  }
  return c;
}

}  // namespace bezinv::datasets
