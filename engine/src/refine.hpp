#pragma once
// Geometry of the normalized curve for refinement and nearest-point search (engine internal).
#include <cstddef>
#include <cstdint>

#include "bezinv/kernels/batch.hpp"
#include "plan_data.hpp"
#include "bezinv/tolerances.hpp"

namespace bezinv::detail {

// refine_parameter's safeguards, for the kernels' lane-batched copy of it (rational_newton).
inline constexpr kernels::NewtonSettings kNewtonSettings{kNewtonMaxIterations, kNewtonMaxStep, kNewtonTrustedStep,
                                                         kNewtonMaxHalvings, kNewtonFinalStep};

// The same safeguards for the off-curve path's Newton kernel (nearest_newton).
inline constexpr kernels::NearestNewtonSettings kNearestNewtonSettings{kNewtonMaxIterations, kNewtonMaxStep,
                                                                       kNewtonTrustedStep, kNewtonMaxHalvings,
                                                                       kNearestNewtonFinalStep};

// The normalized curve as the kernels take it; with `horner`, with its Horner coefficients too
// (plan.horner: the kernels' jets then by Horner's rule).
// One denominator is passed as one array, which the kernels then evaluate once (the same bits).
inline kernels::RationalCurve kernel_curve(const PlanData& plan, bool horner = false) {
  const double* y_den = plan.common_denominator && plan.y_den == plan.x_den ? plan.x_den.data() : plan.y_den.data();
  kernels::RationalCurve curve{plan.degree, plan.x_num.data(), plan.x_den.data(), plan.y_num.data(), y_den};
  if (horner) curve.horner = plan.horner.data();
  return curve;
}

// P(t), P'(t), P''(t) of the normalized curve. For x = N/D:
//   x' = (N' - D' x) / D,   x'' = (N'' - 2 D' x' - D'' x) / D.
struct CurveJet { double x, y, dx, dy, ddx, ddy; };
CurveJet curve_jet(const PlanData& plan, double t);
// The same by Horner's rule (plan.horner, O(n) instead of O(n^2); other rounding, so not for
// refine_parameter, whose bits the kernels reproduce): for tests of a t, not for computing one.
CurveJet curve_jet_horner(const PlanData& plan, double t);
// P(t) and P'(t) alone by the same Horner's rule, the same doubles as curve_jet_horner's (ddx, ddy
// left 0): a stationarity test needs no second derivatives, whose Horner level and two divisions
// were a third of its cost.
CurveJet curve_slope_horner(const PlanData& plan, double t);
// Fills plan.horner from the normalized curve (make_plan).
void horner_coefficients(PlanData& plan);

// P(t) alone (the same numbers as PlanData::normalized_point, in one fused pass).
std::array<double, 2> curve_point(const PlanData& plan, double t);

// |P(t) - (u0, v0)| in normalized units (NaN where a denominator vanishes).
double distance(const PlanData& plan, double u0, double v0, double t);

// A parameter and |P(t) - P0| there (the refinement has it at hand; recomputing it would be the
// most expensive part of refining an on-curve point).
struct Refined { double t, distance; };

// Newton's method on f(t) = (P(t) - P0) . P'(t) (the nearest-point condition), started at t0.
// Safeguards: each step is at most kNewtonMaxStep and must not increase |P(t) - P0| (halved until
// it does), so the iterate stays in the basin it started in; with `stay_on_segment` it is also
// clamped to [0,1]. Returns the last accepted iterate and its distance (measured before the last
// step where that step moved t by a few ulps: the same to rounding).
Refined refine_parameter(const PlanData& plan, double u0, double v0, double t0, bool stay_on_segment);

// Whether t is a stationary point of the distance to (u0, v0), `distance` = |P(t) - P0|:
// cos(P(t) - P0, P'(t)) <= kStationaryCosine (a refinement may also stop on its iteration cap).
bool stationary_point(const PlanData& plan, double u0, double v0, double t, double distance);
// The same test for `count` points at once: stationary[l] = 1 where stationary_point(plan, u[l],
// v[l], t[l], distance[l]) holds, 0 elsewhere, on the same doubles from the kernels'
// rational_slope (Horner's rule is a chain of dependent steps per point: across SIMD lanes its
// latency is hidden).
void stationary_point_lanes(const PlanData& plan, std::size_t count, const double* u, const double* v,
                            const double* t, const double* distance, std::uint8_t* stationary);

// The number of intervals S of the nearest-point search's samples k / S at degree n.
int nearest_sample_count(int degree);

// Parameter of the nearest point of the segment [0,1] to (u0, v0): the certified search
// (stationary_points.hpp) where it proves its answer, nearest_parameter_by_sampling otherwise.
// `hint` (if in [0,1]) is a start the caller has.
double nearest_parameter_on_segment(const PlanData& plan, double u0, double v0, double hint);

// The same by dense sampling: it finds every basin wider than a sample, each local minimum is
// refined, the best one wins. The samples are plan.nearest_samples (make_plan computes them).
double nearest_parameter_by_sampling(const PlanData& plan, double u0, double v0, double hint);

}  // namespace bezinv::detail
