#pragma once
// A curve of kind nurbs as the homogeneous B-spline the algorithms take (de_boor.hpp).
#include "bezinv/curve.hpp"
#include "piecewise/de_boor.hpp"

namespace bezinv::detail {

// Control points (w x, w y, w z, w) from the curve's homogeneous lists (z = 0 for a plane curve).
inline HomogeneousSpline homogeneous_spline(const Curve& nurbs) {
  HomogeneousSpline spline;
  spline.degree = nurbs.degree();
  spline.knots = nurbs.knots;
  for (std::size_t i = 0; i < nurbs.x_num.size(); ++i)
    spline.points.push_back(
        {nurbs.x_num[i], nurbs.y_num[i], nurbs.dimension() == 3 ? nurbs.z_num[i] : 0.0, nurbs.x_den[i]});
  return spline;
}

}  // namespace bezinv::detail
