#pragma once
// What the plan of a NURBS or composite curve holds (engine internal): the plan of each of its
// rational Bezier spans (bezinv/nurbs.hpp), and what judges the whole curve's answers.
#include <array>
#include <vector>

#include "bezinv/invert.hpp"
#include "bezinv/plan.hpp"
#include "piecewise/control_box.hpp"

namespace bezinv::detail {

struct PiecewiseSpan {
  InversionPlan plan;       // of the span, s in [0, 1]
  double start = 0, end = 1;  // the whole curve's parameter at s = 0 and s = 1
  // The whole curve's diagonal over the span's: the span's relative tolerance is the curve's times
  // this, so every span is judged by the same distance (1 where the span's diagonal is 0 or inf).
  double tolerance_factor = 1;
  // The box of the span's control points, which holds its segment (positive weights; ratios that do
  // not bound a composite's part are replaced by its extent, control_box.hpp).
  ControlBox box{};
};

struct PiecewiseData {
  std::vector<PiecewiseSpan> spans;
  int dimension = 2;
  double diagonal = 0;    // of the whole curve's control points (piecewise/control_box.hpp), input units
  double resolution = 0;  // kResolutionUlps ulps of the box's largest coordinate, input units
  std::array<double, 2> domain{0, 1};
  std::array<double, 3> first_point{}, last_point{};  // P at the two ends of the domain

  // The on-curve tolerance in input units: relative to the whole curve, never below the resolution.
  double tolerance(const InvertOptions& options) const;
  // The global parameter of span k's s (exact at s = 0 and 1).
  double parameter(std::size_t k, double s) const;
  // |P(s) - point| on span k, input units.
  double distance(std::size_t k, double s, const std::array<double, 3>& point) const;
  // The distance from `point` to span k's box: no point of the span's segment is nearer (NaN where
  // the box is not finite).
  double box_distance(std::size_t k, const std::array<double, 3>& point) const;
};

// Throws CurveError for a curve that fails validate().
PiecewiseData make_piecewise_data(const Curve& curve);

}  // namespace bezinv::detail
