#include "bezinv/datasets/translation.hpp"

#include <string>

namespace bezinv::datasets {

Curve translated(const Curve& curve, double dx, double dy) {
  Curve c = curve;
  c.id = curve.id + "-translated";
  for (std::size_t i = 0; i < c.x_num.size(); ++i) {
    c.x_num[i] += dx * c.x_den[i];
    c.y_num[i] += dy * c.y_den[i];
  }
  return c;
}

Curve scaled(const Curve& curve, double factor) {
  Curve c = curve;
  c.id = curve.id + "-scaled";
  for (double& v : c.x_num) v *= factor;
  for (double& v : c.y_num) v *= factor;
  return c;
}

}  // namespace bezinv::datasets
