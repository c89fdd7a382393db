#include "pipeline/projection.hpp"

#include <algorithm>
#include <cmath>

#include "bezinv/tolerances.hpp"
#include "extension.hpp"
#include "isolation.hpp"
#include "pipeline/formula_path.hpp"
#include "pipeline/off_curve_path.hpp"
#include "refine.hpp"

namespace bezinv::detail {

bool projects_off_curve(const PlanData& plan, const InvertOptions& options) {
  return options.off_curve == OffCurve::projection && formula_path_data(plan).usable;
}

void project_off_curve(const PlanData& plan, double u0, double v0, double beyond, PointResult& r) {
  const double t = formula_parameter(formula_path_data(plan), u0, v0);
  if (!std::isfinite(t)) return;
  const double d = distance(plan, u0, v0, t);
  if (!(d > beyond) || !std::isfinite(d)) return;
  r.t = t;
  r.t2 = PointResult::nan;
  r.residual = d * plan.scale;
  r.path = Path::projection;
  r.sigma_min = r.sigma_next = PointResult::nan;
}

void projection_path(const PlanData& plan, const InvertOptions& options, std::size_t count, BatchWorkspace& w,
                     LaneRows rows) {
  const double tolerance = normalized_tolerance(plan, options), radius = off_curve_radius(tolerance);
  const FormulaPathData& f = formula_path_data(plan);
  for (std::size_t l = 0; l < count; ++l) {
    if (!w.active[l] || w.off_curve_tried[l] ||
        !(std::max(std::abs(w.u[l]), std::abs(w.v[l])) <= kOffCurvePathMaxCoordinate))
      continue;
    const double t = w.t_refined[l], d = w.distance[l];
    if (!(t >= 0.0 && t <= 1.0 && d > radius)) continue;
    const double projected = formula_parameter(f, w.u[l], w.v[l]);
    if (!std::isfinite(projected)) continue;  // near a base point: the nearest point, as without projection
    // No point of the segment within the tolerance: around t the distance has a single stationary
    // point, t, where it is d; every other piece's box is beyond the tolerance. Then the extension.
    if (!isolated(plan, w.u[l], w.v[l], t, d, tolerance) || !extension_clear(plan, w.u[l], w.v[l], radius)) continue;
    // |P(t*) - P0| by Horner's rule on the segment (O(n), where de Casteljau is O(n^2)): a
    // residual reported, not a parameter computed from it.
    double projected_distance;
    if (projected >= 0.0 && projected <= 1.0) {
      const CurveJet j = curve_slope_horner(plan, projected);
      projected_distance = std::hypot(j.x - w.u[l], j.y - w.v[l]);
    } else {
      projected_distance = distance(plan, w.u[l], w.v[l], projected);
    }
    // Within the radius (rounding, as the whole segment was proved farther): not by projection.
    if (!(projected_distance > radius) || !std::isfinite(projected_distance)) continue;
    w.active[l] = 0;
    PointResult& r = rows[l];
    r.status = Status::off_curve;
    r.t = projected;
    r.residual = projected_distance * plan.scale;
    r.path = Path::projection;
    r.sigma_min = r.sigma_next = PointResult::nan;
  }
}

}  // namespace bezinv::detail
