#pragma once
// The bounding box of a curve's control points, which sets its size (the on-curve tolerance is
// relative to its diagonal): as the plan takes it for a Bezier-form curve (num_i / den_i and the
// two ends; the segment's extent where those ratios do not bound it), the control points of a nurbs curve, the union of
// a composite's curves' boxes. z is 0 for a plane curve.
#include <array>

#include "bezinv/curve.hpp"

namespace bezinv::detail {

struct ControlBox {
  std::array<double, 3> lo, hi;
  // In halves, so that a box as wide as the doubles go does not overflow (inf then).
  double diagonal() const;
  // The largest |coordinate|: the input's own resolution is an ulp of it.
  double magnitude() const;
};

ControlBox control_box(const Curve& curve);

}  // namespace bezinv::detail
