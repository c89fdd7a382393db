#include "pipeline/formula_path.hpp"

#include <array>
#include <cmath>

#include "bezinv/inversion_formula.hpp"
#include "bezinv/kernels/batch.hpp"
#include "pipeline/fast_path.hpp"
#include "degree_drop.hpp"
#include "isolation.hpp"
#include "pipeline/decide.hpp"
#include "pipeline/form_b.hpp"
#include "refine.hpp"

namespace bezinv::detail {

const FormulaPathData& formula_path_data(const PlanData& plan) {
  return plan.formula_path.get([&](FormulaPathData& data) {
    // The curve's degree as the formula sees it: twice the plan's with separate denominators.
    const int degree = plan.common_denominator ? plan.degree : 2 * plan.degree;
    if (!plan.usable || plan.straight_line || degree > kFormulaPathMaxDegree) return;
    try {
      const InversionFormula formula(plan, FormulaChoice{});
      if (!(formula.segment_error() <= kFormulaPathMaxSegmentError)) return;
      // The formula's frame is the plan's normalization followed by a shift and a scale per axis:
      // its centre and scales, in the plan's normalized units.
      const PlaneFrame& frame = formula.numerator().frame();
      const auto centre = plan.normalize(frame.centre[0], frame.centre[1]);
      data.centre_u = centre[0];
      data.centre_v = centre[1];
      data.inverse_half_u = 1.0 / (frame.scale_u * plan.inverse_scale);
      data.inverse_half_v = 1.0 / (frame.scale_v * plan.inverse_scale);
      data.degree = formula.degree();
      data.n.assign(formula.numerator().coefficients().begin(), formula.numerator().coefficients().end());
      data.m.assign(formula.denominator().coefficients().begin(), formula.denominator().coefficients().end());
      data.usable = true;
    } catch (const FormulaError&) {
      // No formula (a curve traced more than once, ...): the plan keeps the Bezout path.
    }
  });
}

const FormulaPathData& fast_path_formula(const PlanData& plan) {
  if (plan.linear_formula.usable) return plan.linear_formula;
  return plan.low_degree_formula.usable ? plan.low_degree_formula : formula_path_data(plan);
}

bool takes_formula_path(const PlanData& plan, const InvertOptions& options) {
  // automatic: the formulae made with the plan only, where they are the faster (a conic's or
  // cubic's N / M, a few operations, against its B and seed; docs/inversion-formula.md, "Where
  // the default takes it: conics and cubics"); the curve's own is made per plan on first use (up
  // to ~80 ms at degree 20), which a file of many curves would pay for each.
  const bool automatic = (plan.near_lower_degree && plan.linear_formula.usable) ||
                         (plan.low_degree_formula.usable && plan.formula_weights_moderate);
  const bool asked = options.algebraic == Algebraic::formula ||
                     (options.algebraic == Algebraic::automatic && automatic);
  return asked && takes_fast_path(plan, options) && plan.degree >= 2 && fast_path_formula(plan).usable;
}

bool repays_curve_formula(const PlanData& plan, const InvertOptions& options, std::size_t points) {
  if (options.algebraic != Algebraic::automatic || !options.refine || !options.fast_path) return false;
  // (Not a space curve's projection, inverted chunk by chunk: not measured. A piecewise plan's
  // spans come here as plans of their own.)
  if (!plan.usable || plan.space || !plan.common_denominator || !plan.formula_weights_moderate) return false;
  // (A plan close to a lower degree with a linear formula has automatic's formula path already.)
  if (plan.degree < 4 || plan.degree > kFormulaPathMaxDegree || (plan.near_lower_degree && plan.linear_formula.usable))
    return false;
  return points >= kCurveFormulaMinPoints[static_cast<std::size_t>(plan.degree)];
}

bool reports_formula_unrefined(const PlanData& plan, const InvertOptions& options) {
  // (Degree 1 has no B to form late: a line's parameter is read directly.)
  return !options.refine && options.algebraic == Algebraic::formula && plan.degree >= 2 &&
         fast_path_formula(plan).usable;
}

bool forms_b_late(const PlanData& plan, const InvertOptions& options) {
  return forms_b_in_seed(plan, options) || takes_formula_path(plan, options) ||
         reports_formula_unrefined(plan, options);
}

kernels::PlaneFormula plane_formula(const FormulaPathData& f) {
  return {.degree = f.degree,
          .centre_u = f.centre_u,
          .centre_v = f.centre_v,
          .inverse_half_u = f.inverse_half_u,
          .inverse_half_v = f.inverse_half_v,
          .max_coordinate = kFormulaPathMaxCoordinate,
          .min_denominator = kFormulaPathMinDenominator,
          .n = f.n.data(),
          .m = f.m.data()};
}

double formula_parameter(const FormulaPathData& f, double u, double v) {
  if (!(std::abs(u) <= kFormulaPathMaxCoordinate && std::abs(v) <= kFormulaPathMaxCoordinate))
    return PointResult::nan;
  const double a = (u - f.centre_u) * f.inverse_half_u, b = (v - f.centre_v) * f.inverse_half_v;
  // sum_{i + j <= d} c_ij T_i(a) T_j(b), in PlanePolynomial::index order.
  std::array<double, kMaxDegree + 1> ta, tb;
  ta[0] = tb[0] = 1.0;
  ta[1] = a;
  tb[1] = b;
  for (int k = 1; k < f.degree; ++k) {
    ta[k + 1] = 2.0 * a * ta[k] - ta[k - 1];
    tb[k + 1] = 2.0 * b * tb[k] - tb[k - 1];
  }
  double numerator = 0.0, denominator = 0.0, size = 0.0;
  std::size_t e = 0;
  for (int k = 0; k <= f.degree; ++k)
    for (int j = 0; j <= k; ++j, ++e) {
      const double term = ta[k - j] * tb[j];
      numerator += f.n[e] * term;
      denominator += f.m[e] * term;
      size += std::abs(f.m[e] * term);
    }
  if (!(std::abs(denominator) >= kFormulaPathMinDenominator * size)) return PointResult::nan;
  return numerator / denominator;
}

void formula_or_seed(const PlanData& plan, const Point* points, LaneRows rows, std::size_t count,
                     BatchWorkspace& w, bool formula_given) {
  const FormulaPathData& f = fast_path_formula(plan);
  const int n = plan.degree;
  const std::size_t stride = kBatchLanes;
  std::array<double, kBatchLanes> computed;
  // Every lane, inactive ones too: a batch is nearly all active. (Given, it is read in lane l
  // before lane l's t_algebraic is written.)
  const double* formula_t = formula_given ? w.t_algebraic.data() : computed.data();
  if (!formula_given)
    kernels::active_implementation().formula_parameter(plane_formula(f), count, w.u.data(), w.v.data(),
                                                       computed.data());
  std::size_t seeded = 0;
  for (std::size_t l = 0; l < count; ++l) {
    w.from_formula[l] = 0;
    if (!w.active[l]) continue;  // the fast path leaves an inactive lane alone
    const double t = formula_t[l];
    if (std::isfinite(t)) {
      w.t_algebraic[l] = t;
      w.defect[l] = 0.0;
      w.estimate[l] = PointResult::nan;  // no B: no sigma_min estimate
      w.from_formula[l] = 1;
    } else {
      w.gap_lane_of[seeded++] = static_cast<std::uint8_t>(l);
    }
  }
  if (seeded == 0) return;
  // The other lanes: the fast path's seed on their B, formed here (compacted), its overflow
  // checked as stage 1 checks it.
  std::array<double, kBatchLanes> u, v, poison, t;
  for (std::size_t k = 0; k < seeded; ++k) u[k] = w.u[w.gap_lane_of[k]], v[k] = w.v[w.gap_lane_of[k]];
  const kernels::Implementation& kernel = kernels::active_implementation();
  if (n >= kFormedBMinDegree) {
    kernel.bezout_null_vector_seed(n, seeded, stride, plan.B0.data(), plan.Bx.data(), plan.By.data(),
                                   bilinear_coefficients(plan), u.data(), v.data(), w.gap_z.data(),
                                   w.gap_defect.data(), w.gap_estimate.data(), poison.data(), kFastPathMaxDefect);
  } else {
    kernel.bezout_matrix(n, seeded, stride, plan.B0.data(), plan.Bx.data(), plan.By.data(),
                         bilinear_coefficients(plan), u.data(), v.data(), w.gap_B.data(), poison.data());
    if (n >= kernels::kNullVectorSeedMinSize)
      kernel.null_vector_seed(n, seeded, stride, w.gap_B.data(), w.gap_z.data(), w.gap_defect.data(),
                              w.gap_estimate.data(), kFastPathMaxDefect);
    else  // a conic: the pivoted kernel (its gap unused here: the gap pass decides with its own)
      kernel.null_vector(n, seeded, stride, w.gap_B.data(), w.gap_z.data(), w.gap_defect.data(),
                         w.gap_estimate.data(), /*second=*/nullptr);
  }
  kernel.bernstein_parameter(n, seeded, stride, w.gap_z.data(), t.data());
  std::array<double, kBatchLanes> lane_poison{};
  for (std::size_t k = 0; k < seeded; ++k) {
    const std::size_t l = w.gap_lane_of[k];
    w.t_algebraic[l] = t[k];
    w.defect[l] = w.gap_defect[k];
    w.estimate[l] = w.gap_estimate[k];
    lane_poison[l] = poison[k];
  }
  mark_overflowing_b(plan, points, lane_poison.data(), count, w, rows);
}

void formula_unrefined(const PlanData& plan, const InvertOptions& options, std::size_t count, BatchWorkspace& w,
                       LaneRows rows) {
  const FormulaPathData& f = fast_path_formula(plan);
  const double tolerance = normalized_tolerance(plan, options);
  for (std::size_t l = 0; l < count; ++l) {
    if (!w.active[l]) continue;
    const double u = w.u[l], v = w.v[l];
    const double t = formula_parameter(f, u, v);
    if (!(t >= 0.0 && t <= 1.0)) continue;  // NaN too
    const double d = distance(plan, u, v, t);
    if (!(d <= tolerance) || degree_drops(plan, u, v) || !isolated(plan, u, v, t, d, tolerance)) continue;
    w.active[l] = 0;
    answer_fast(plan, t, d, PointResult::nan, PointResult::nan, rows[l], Path::formula);
  }
}

}  // namespace bezinv::detail
