#include "piecewise/control_box.hpp"

#include <algorithm>
#include <cmath>

#include "bezinv/nurbs.hpp"
#include "ratio_range.hpp"

namespace bezinv::detail {
namespace {

void include(ControlBox& box, const std::array<double, 3>& p) {
  for (int k = 0; k < 3; ++k) {
    box.lo[k] = std::min(box.lo[k], p[k]);
    box.hi[k] = std::max(box.hi[k], p[k]);
  }
}

}  // namespace

double ControlBox::diagonal() const {
  return 2 * std::hypot(0.5 * hi[0] - 0.5 * lo[0], 0.5 * hi[1] - 0.5 * lo[1], 0.5 * hi[2] - 0.5 * lo[2]);
}

double ControlBox::magnitude() const {
  double m = 0;
  for (int k = 0; k < 3; ++k) m = std::max({m, std::abs(lo[k]), std::abs(hi[k])});
  return m;
}

ControlBox control_box(const Curve& curve) {
  constexpr double inf = HUGE_VAL;
  ControlBox box{{inf, inf, inf}, {-inf, -inf, -inf}};
  if (curve.kind == CurveKind::composite) {
    for (const Curve& part : curve.curves) {
      const ControlBox b = control_box(part);
      include(box, b.lo);
      include(box, b.hi);
    }
    return box;
  }
  const bool space = curve.dimension() == 3;
  if (curve.kind != CurveKind::nurbs &&
      (!ratios_bound(curve.x_num, curve.x_den) || !ratios_bound(curve.y_num, curve.y_den) ||
       (space && !ratios_bound(curve.z_num, curve.z_den)))) {
    // Ratios that do not bound the curve (a zero or negative denominator coefficient): the extent
    // of the segment itself, from pieces on which they do (ratio_range.hpp).
    const RatioRange x = ratio_range(curve.x_num, curve.x_den), y = ratio_range(curve.y_num, curve.y_den);
    const RatioRange z = space ? ratio_range(curve.z_num, curve.z_den) : RatioRange{0.0, 0.0};
    return {{x.lo, y.lo, z.lo}, {x.hi, y.hi, z.hi}};
  }
  for (std::size_t i = 0; i < curve.x_num.size(); ++i)
    if (curve.x_den[i] != 0.0 && curve.y_den[i] != 0.0 && (!space || curve.z_den[i] != 0.0))
      include(box, {curve.x_num[i] / curve.x_den[i], curve.y_num[i] / curve.y_den[i],
                    space ? curve.z_num[i] / curve.z_den[i] : 0.0});
  if (curve.kind != CurveKind::nurbs) {
    include(box, curve.point3(0.0));
    include(box, curve.point3(1.0));
  }
  return box;
}

}  // namespace bezinv::detail
