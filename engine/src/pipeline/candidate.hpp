#pragma once
// A candidate parameter of one point, and how it becomes a verified one (settle): every path
// (SVD, pair, Sylvester, nearest) ends here, and only the distance decides (docs/accuracy-model.md).
#include <algorithm>

#include "bezinv/invert.hpp"
#include "plan_data.hpp"

namespace bezinv::detail {

// The tolerance on |P(t) - P0| in normalized units: relative to the curve's size, never below the
// resolution of its coordinates.
inline double normalized_tolerance(const PlanData& plan, const InvertOptions& options) {
  return std::max(options.relative_tolerance * plan.normalized_diagonal, plan.normalized_resolution);
}

struct Candidate {
  double t = PointResult::nan;
  double distance = PointResult::nan;  // normalized units
  Path path = Path::none;
  bool on_segment = false;  // t in [0,1] and within tolerance
  bool on_curve = false;    // within tolerance (segment or extension)
};

inline void classify(Candidate& c, double tolerance) {
  c.on_curve = c.distance <= tolerance;
  c.on_segment = c.on_curve && c.t >= 0.0 && c.t <= 1.0;
}

// From an algebraic parameter to a verified one: refine (or not), then measure.
Candidate settle(const PlanData& plan, double u0, double v0, double t_algebraic, Path path,
                 double tolerance, bool refine);

}  // namespace bezinv::detail
