#include "plan_data.hpp"

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>
#include <tbb/task_arena.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <memory>
#include <mutex>
#include <numbers>
#include <numeric>
#include <optional>
#include <vector>

#include "bernstein_arithmetic.hpp"
#include "bezinv/bernstein.hpp"
#include "bezinv/bezout.hpp"
#include "bezinv/tolerances.hpp"
#include "common_factor.hpp"
#include "extension.hpp"
#include "formula/linear_inversion_formula.hpp"
#include "isolation.hpp"
#include "ratio_range.hpp"
#include "stationary_points.hpp"

#include "bezinv/nurbs.hpp"
#include "piecewise/piecewise_plan.hpp"
#include "refine.hpp"
#include "space/space_curve.hpp"

namespace bezinv {
namespace {

using Poly = std::vector<double>;

// |leading power coefficient| against what rounding of the coefficients can leave in it.
// `magnitude` bounds the coefficients as they were before translation to the centre: a curve
// elevated at (1e6, -1e6) carries rounding of 1e6 * eps in every coefficient, which the
// translation does not remove. The bound on the leading coefficient is then
// sum_i C(n,i) * magnitude = 2^n * magnitude.
bool leading_coefficient_vanishes(const Poly& p, double magnitude, double ratio) {
  const double bound = std::max(power_leading_bound(p), std::ldexp(magnitude, static_cast<int>(p.size()) - 1));
  return std::abs(power_leading_coefficient(p)) <= ratio * bound;
}

Poly reduced(const Poly& p) {
  Poly r(p.size() - 1);
  reduce_degree(p, r);
  return r;
}

// How far r, p reduced by one degree or more, is from p: r elevated back to p's degree, the
// largest difference of their Bernstein coefficients (which bounds the difference of the two
// polynomials on [0, 1]: the Bernstein basis sums to 1).
double reduction_change(const Poly& p, Poly r) {
  while (r.size() < p.size()) {
    Poly q(r.size() + 1);
    elevate_degree(r, q);
    r = std::move(q);
  }
  double change = 0;
  for (std::size_t i = 0; i < p.size(); ++i) change = std::max(change, std::abs(r[i] - p[i]));
  return change;
}

// The control points whose bounding box sets the curve's size: (num_i / den_i) where the
// denominator coefficient is non-zero, plus the curve's two end points (for kind `rational` the
// ratios need not bound the curve, the ends always lie on it).
std::vector<std::array<double, 2>> control_points(const Curve& c) {
  std::vector<std::array<double, 2>> pts;
  for (std::size_t i = 0; i < c.x_num.size(); ++i)
    if (c.x_den[i] != 0.0 && c.y_den[i] != 0.0)
      pts.push_back({c.x_num[i] / c.x_den[i], c.y_num[i] / c.y_den[i]});
  pts.push_back(c.point(0.0));
  pts.push_back(c.point(1.0));
  return pts;
}

// Whether the normalized curve lies on a straight line: its distance from the line through two of
// its points, a rational function whose numerator has degree at most 2n, vanishes at 2n + 1
// parameters (to kVanishingBezoutRatio of the curve's size), so it vanishes everywhere.
bool on_a_line(const detail::PlanData& plan) {
  const int count = 2 * plan.degree + 1;
  std::vector<std::array<double, 2>> p(count);
  for (int k = 0; k < count; ++k) p[k] = plan.normalized_point(static_cast<double>(k) / (count - 1));
  // Through the two samples farthest apart (a turning line may come back to its start).
  int a = 0, b = 0;
  double widest = 0.0;
  for (int i = 0; i < count; ++i)
    for (int j = i + 1; j < count; ++j) {
      const double d = std::hypot(p[j][0] - p[i][0], p[j][1] - p[i][1]);
      if (d > widest) { widest = d; a = i; b = j; }
    }
  if (!(widest > 0.0)) return false;
  const double dx = (p[b][0] - p[a][0]) / widest, dy = (p[b][1] - p[a][1]) / widest;
  for (int k = 0; k < count; ++k)
    if (!(std::abs((p[k][0] - p[a][0]) * dy - (p[k][1] - p[a][1]) * dx) <= kVanishingBezoutRatio)) return false;
  return true;
}

// Whether every polynomial of the normalized curve has a top power coefficient below
// kNearLowerDegreeRatio of its bound (PlanData::near_lower_degree).
bool near_lower_degree(const detail::PlanData& plan) {
  const int n = plan.degree;
  for (const std::vector<double>* c : {&plan.x_num, &plan.x_den, &plan.y_num, &plan.y_den}) {
    const std::span<const double> p(c->data(), static_cast<std::size_t>(n) + 1);
    if (!(std::abs(power_leading_coefficient(p)) <= kNearLowerDegreeRatio * power_leading_bound(p))) return false;
  }
  return true;
}

// The degree-1 formula of a polynomial curve with a direction e along which e . P(t) is linear
// (PlanData::linear_formula). e . P is linear when every second difference of its Bernstein
// coefficients vanishes, i.e. e is normal to every second difference d_i of the control points:
// normal to the largest, and the others along it (to kLinearDirectionRatio of their bound).
detail::FormulaPathData linear_direction_formula(const detail::PlanData& plan) {
  detail::FormulaPathData f;
  const int n = plan.degree;
  const auto constant = [&](const std::vector<double>& w) {
    return std::all_of(w.begin(), w.begin() + n + 1, [&](double c) { return c == w[0]; });
  };
  if (!plan.common_denominator || !constant(plan.x_den) || plan.x_den[0] == 0.0) return f;
  const double w = plan.x_den[0];
  std::vector<std::array<double, 2>> d(static_cast<std::size_t>(n - 1));
  double bound = 0.0, largest = 0.0;
  std::size_t k = 0;
  for (int i = 0; i + 2 <= n; ++i) {
    d[i] = {(plan.x_num[i + 2] - 2 * plan.x_num[i + 1] + plan.x_num[i]) / w,
            (plan.y_num[i + 2] - 2 * plan.y_num[i + 1] + plan.y_num[i]) / w};
    bound += std::abs(plan.x_num[i + 2] / w) + 2 * std::abs(plan.x_num[i + 1] / w) + std::abs(plan.x_num[i] / w) +
             std::abs(plan.y_num[i + 2] / w) + 2 * std::abs(plan.y_num[i + 1] / w) + std::abs(plan.y_num[i] / w);
    const double size = std::hypot(d[i][0], d[i][1]);
    if (size > largest) largest = size, k = static_cast<std::size_t>(i);
  }
  if (!(largest > 0.0)) return f;  // a straight line (no second differences): its own path
  const double eu = -d[k][1] / largest, ev = d[k][0] / largest;
  for (const auto& di : d)
    if (!(std::abs(eu * di[0] + ev * di[1]) <= kLinearDirectionRatio * bound)) return f;
  // e . P(t) = e . c_0 + n e . (c_1 - c_0) t in normalized units.
  const double start = (eu * plan.x_num[0] + ev * plan.y_num[0]) / w;
  const double slope = n * (eu * (plan.x_num[1] - plan.x_num[0]) + ev * (plan.y_num[1] - plan.y_num[0])) / w;
  if (!(std::abs(slope) >= kLinearDirectionMinSlope * plan.normalized_diagonal)) return f;
  f.degree = 1;
  f.n = {-start, eu, ev};  // N = e . (u, v) - e . P(0)
  f.m = {slope, 0.0, 0.0};  // M = n e . (c_1 - c_0)
  f.usable = true;
  return f;
}

}  // namespace

namespace detail {

std::array<double, 2> PlanData::normalized_point(double t) const {
  return {bernstein_value(x_num, t) / bernstein_value(x_den, t),
          bernstein_value(y_num, t) / bernstein_value(y_den, t)};
}

void bezout_at(const PlanData& plan, double u0, double v0, std::span<double> out) {
  const int nn = plan.degree * plan.degree;
  if (plan.common_denominator) {
    for (int i = 0; i < nn; ++i) out[i] = plan.B0[i] - u0 * plan.Bx[i] - v0 * plan.By[i];
  } else {
    const double uv = u0 * v0;
    for (int i = 0; i < nn; ++i) out[i] = plan.B0[i] - u0 * plan.Bx[i] - v0 * plan.By[i] + uv * plan.Bxy[i];
  }
}

PlanData make_plan_data(const Curve& given) {
  validate(given);
  PlanData plan;
  plan.curve = given;
  plan.input_degree = given.degree();
  // A factor shared by all the polynomials would give B a null direction at every point
  // (engine/src/common_factor.hpp); the rest of the plan is the curve without it.
  const Curve curve = detail::without_common_factor(given);
  plan.common_denominator = curve.common_denominator();

  // Size: bounding box of the control points.
  const auto pts = control_points(curve);
  double lo[2] = {pts[0][0], pts[0][1]}, hi[2] = {lo[0], lo[1]};
  for (const auto& p : pts)
    for (int k = 0; k < 2; ++k) { lo[k] = std::min(lo[k], p[k]); hi[k] = std::max(hi[k], p[k]); }
  // Where the ratios do not bound the curve (a zero or negative denominator coefficient: a
  // "control point" at infinity or on the far side), the extent of the segment itself, from pieces
  // on which they do (ratio_range.hpp).
  if (!detail::ratios_bound(curve.x_num, curve.x_den) || !detail::ratios_bound(curve.y_num, curve.y_den)) {
    const detail::RatioRange x = detail::ratio_range(curve.x_num, curve.x_den);
    const detail::RatioRange y = detail::ratio_range(curve.y_num, curve.y_den);
    lo[0] = x.lo; hi[0] = x.hi; lo[1] = y.lo; hi[1] = y.hi;
  }
  // In halves, so that a box as wide as the doubles go does not overflow: the diagonal may then be
  // inf, but its half, the centre and the scale are finite.
  const double half_diagonal = std::hypot(0.5 * hi[0] - 0.5 * lo[0], 0.5 * hi[1] - 0.5 * lo[1]);
  plan.diagonal = 2 * half_diagonal;
  plan.centre = {0.5 * lo[0] + 0.5 * hi[0], 0.5 * lo[1] + 0.5 * hi[1]};
  const double magnitude = std::max({std::abs(lo[0]), std::abs(hi[0]), std::abs(lo[1]), std::abs(hi[1])});
  if (half_diagonal > 0) {
    const int e = detail::normalizing_exponent(half_diagonal, magnitude);
    plan.scale = std::ldexp(1.0, e);
    plan.inverse_scale = std::ldexp(1.0, -e);
  }
  plan.normalized_diagonal = 2 * (half_diagonal * plan.inverse_scale);
  // The coordinates' own resolution: a point made on the curve and rounded to doubles is within
  // an ulp of it, wherever the curve sits (a 1-unit curve at 1e12 has ulps of 1.2e-4).
  plan.normalized_resolution = kResolutionUlps * ulp(magnitude) * plan.inverse_scale;

  // Rotation (one denominator only): turn the principal axis of the control points to 45 degrees,
  // so neither coordinate of a straight segment is constant (a constant x makes p = X - x0 W
  // vanish identically for every point on it, and B = 0). Separate denominators would be mixed by
  // a rotation (x' = c x - s y needs the product of both), so they keep the axes.
  if (plan.common_denominator) {
    // In units of the scale, rescaled where their squares would overflow (offset_rescaling: a
    // curve with a negative weight is sized by its segment, and a control point 1 unit away from a
    // segment 1e-300 long is 1e300 away scaled), which made the axis, and every normalized
    // coefficient with it, NaN.
    std::vector<std::array<double, 2>> offsets;
    double farthest = 0;
    for (const auto& p : pts) {
      const double dx = p[0] * plan.inverse_scale - plan.centre[0] * plan.inverse_scale;
      const double dy = p[1] * plan.inverse_scale - plan.centre[1] * plan.inverse_scale;
      offsets.push_back({dx, dy});
      farthest = std::max({farthest, std::abs(dx), std::abs(dy)});
    }
    if (const int shift = detail::offset_rescaling(farthest); shift != 0)
      for (auto& d : offsets) d = {std::ldexp(d[0], shift), std::ldexp(d[1], shift)};
    double sxx = 0, syy = 0, sxy = 0;
    for (const auto& [dx, dy] : offsets) {
      sxx += dx * dx; syy += dy * dy; sxy += dx * dy;
    }
    const double principal = 0.5 * std::atan2(2 * sxy, sxx - syy);
    const double alpha = std::numbers::pi / 4 - principal;
    plan.cos_rotation = std::cos(alpha);
    plan.sin_rotation = std::sin(alpha);
  }

  // Normalized coefficients. Numerator and denominator are divided by the largest denominator
  // coefficient too (P = X/W is unchanged), so huge or tiny weights do not reach B.
  const int n0 = curve.degree();
  const double xs = max_abs(curve.x_den), ys = max_abs(curve.y_den);
  Poly xn(n0 + 1), xd(n0 + 1), yn(n0 + 1), yd(n0 + 1);
  double magnitude_x = 0, magnitude_y = 0;  // coefficient size before translation, normalized units
  // Scaled first (by the power of two 1/scale: the same bits as scaling last), so that coefficients
  // near the largest double do not overflow in the translation or the rotation.
  const double s = plan.inverse_scale;
  const double cx = plan.centre[0] * s, cy = plan.centre[1] * s;
  for (int i = 0; i <= n0; ++i) {
    const double Wx = curve.x_den[i] / xs, Wy = curve.y_den[i] / ys;
    const double ax = curve.x_num[i] / xs * s, ay = curve.y_num[i] / ys * s;
    magnitude_x = std::max(magnitude_x, std::abs(ax) + std::abs(cx * Wx));
    magnitude_y = std::max(magnitude_y, std::abs(ay) + std::abs(cy * Wy));
    const double X = ax - cx * Wx, Y = ay - cy * Wy;
    if (plan.common_denominator) {
      xn[i] = plan.cos_rotation * X - plan.sin_rotation * Y;
      yn[i] = plan.sin_rotation * X + plan.cos_rotation * Y;
    } else {
      xn[i] = X;
      yn[i] = Y;
    }
    xd[i] = Wx;
    yd[i] = Wy;
  }

  // Effective degree: a degree-elevated curve has all four power-basis leading coefficients at
  // round-off level; its Bezout matrix would then have a spurious null direction (the common
  // "root at infinity") at every point. Reduce until one of them is genuinely non-zero.
  // A rotation mixes x and y, so either numerator may carry either coordinate's rounding.
  const double magnitude_num = plan.common_denominator ? magnitude_x + magnitude_y : std::max(magnitude_x, magnitude_y);
  // The test on the leading coefficients alone is necessary but not enough: a degree-13 curve 1.3
  // wide at x = -6.5e11 has leading power coefficients of 5 and 9 against a bound of ~19, and its
  // reduction moved it by 46-84 ulps of its coordinates, where a curve elevated and rounded to
  // doubles moves by about 3 (docs/accuracy-model.md, "Effective degree"). So a reduction is kept
  // only where it moves no coefficient by more than rounding of it can: the same ratio times the
  // larger of the largest coefficient and `magnitude` (the leading test's measure of that rounding,
  // per coefficient instead of summed into the leading one). Each is checked against the curve as
  // given (not the step before), so that the steps' changes cannot add up unseen.
  const Poly xn0 = xn, xd0 = xd, yn0 = yn, yd0 = yd;
  const double rounding_xn = kElevatedLeadingRatio * std::max(max_abs(xn0), magnitude_num);
  const double rounding_yn = kElevatedLeadingRatio * std::max(max_abs(yn0), magnitude_num);
  const double rounding_xd = kElevatedLeadingRatio * max_abs(xd0), rounding_yd = kElevatedLeadingRatio * max_abs(yd0);
  double numerator_change = 0, denominator_change = 0;
  while (xn.size() > 2 && leading_coefficient_vanishes(xn, magnitude_num, kElevatedLeadingRatio) &&
         leading_coefficient_vanishes(xd, 0.0, kElevatedLeadingRatio) &&
         leading_coefficient_vanishes(yn, magnitude_num, kElevatedLeadingRatio) &&
         leading_coefficient_vanishes(yd, 0.0, kElevatedLeadingRatio)) {
    Poly rxn = reduced(xn), rxd = reduced(xd), ryn = reduced(yn), ryd = reduced(yd);
    const double cxn = reduction_change(xn0, rxn), cyn = reduction_change(yn0, ryn);
    const double cxd = reduction_change(xd0, rxd), cyd = reduction_change(yd0, ryd);
    if (!(cxn <= rounding_xn && cyn <= rounding_yn && cxd <= rounding_xd && cyd <= rounding_yd)) break;
    xn = std::move(rxn); xd = std::move(rxd); yn = std::move(ryn); yd = std::move(ryd);
    numerator_change = std::max(cxn, cyn);
    denominator_change = std::max(cxd, cyd);
  }
  // The plan's curve is then within (its numerators' change + its denominators' change times
  // |P|) / W of the given one, W the smallest denominator coefficient and |P| at most the
  // normalized diagonal (the control points' box, centred at the origin; a rotation keeps
  // lengths): the on-curve tolerance's floor takes it in, so that a point on the given curve is
  // within the tolerance of the plan's. (With a coefficient W <= 0 no such bound holds; such a
  // curve's reduction moved it by no more than rounding of its coefficients, as above.)
  if (numerator_change > 0 || denominator_change > 0) {
    double smallest = std::numeric_limits<double>::infinity();
    for (const Poly* w : {&xd, &yd})
      for (double c : *w) smallest = std::min(smallest, c);
    if (smallest > 0)
      plan.normalized_resolution +=
          (numerator_change + denominator_change * plan.normalized_diagonal) / smallest;
  }
  const int n = static_cast<int>(xn.size()) - 1;
  plan.degree = n;
  plan.x_num = xn; plan.x_den = xd; plan.y_num = yn; plan.y_den = yd;
  plan.lead_x_num = power_leading_coefficient(xn);
  plan.lead_x_den = power_leading_coefficient(xd);
  plan.lead_y_num = power_leading_coefficient(yn);
  plan.lead_y_den = power_leading_coefficient(yd);

  // B(u0,v0) = Bez(Xn,Yn) - u0 Bez(Xd,Yn) - v0 Bez(Xn,Yd) + u0 v0 Bez(Xd,Yd).
  const int nn = n * n;
  plan.B0.assign(nn, 0.0); plan.Bx.assign(nn, 0.0); plan.By.assign(nn, 0.0); plan.Bxy.assign(nn, 0.0);
  bezout_matrix(xn, yn, plan.B0);
  bezout_matrix(xd, yn, plan.Bx);
  bezout_matrix(xn, yd, plan.By);
  if (!plan.common_denominator) bezout_matrix(xd, yd, plan.Bxy);
  for (int i = 0; i < nn; ++i) {
    plan.bezout_max_entries[0] = std::max(plan.bezout_max_entries[0], std::abs(plan.B0[i]));
    plan.bezout_max_entries[1] = std::max(plan.bezout_max_entries[1], std::abs(plan.Bx[i]));
    plan.bezout_max_entries[2] = std::max(plan.bezout_max_entries[2], std::abs(plan.By[i]));
    plan.bezout_max_entries[3] = std::max(plan.bezout_max_entries[3], std::abs(plan.Bxy[i]));
  }

  // The nearest-point search's samples P(k / S): the same for every point of the curve.
  const int samples = detail::nearest_sample_count(n);
  plan.nearest_samples.resize(2 * static_cast<std::size_t>(samples + 1));
  for (int k = 0; k <= samples; ++k) {
    const auto p = detail::curve_point(plan, static_cast<double>(k) / samples);
    plan.nearest_samples[2 * k] = p[0];
    plan.nearest_samples[2 * k + 1] = p[1];
  }

  detail::horner_coefficients(plan);
  detail::isolation_pieces(plan);
  plan.straight_line = n >= 2 && on_a_line(plan);
  plan.near_lower_degree = n >= 3 && near_lower_degree(plan);
  if (n >= 2) plan.linear_formula = linear_direction_formula(plan);

  if (plan.diagonal == 0.0) {
    plan.usable = false;
    plan.reason = "degenerate curve: all control points coincide";
    return plan;
  }
  plan.low_degree_formula = linear_inversion_formula(plan);
  if (plan.common_denominator) {
    const auto [lightest, heaviest] = std::minmax_element(plan.x_den.begin(), plan.x_den.end());
    plan.formula_weights_moderate = (*lightest > 0.0 && *heaviest <= kFormulaPathMaxWeightRatio * *lightest) ||
                                    (*heaviest < 0.0 && *lightest >= kFormulaPathMaxWeightRatio * *heaviest);
  }
  return plan;
}

const OffCurveData& off_curve_data(const PlanData& plan) {
  return plan.off_curve.get([&](OffCurveData& data) {
    stationary_pieces(plan, data);
    extension_pieces(plan, data);
  });
}

}  // namespace detail

InversionPlan::InversionPlan() {
  static const auto empty = [] {
    auto data = std::make_shared<detail::PlanData>();
    data->usable = false;
    data->reason = "no curve (an empty plan)";
    return std::shared_ptr<const detail::PlanData>(std::move(data));
  }();
  data_ = empty;
}

InversionPlan::InversionPlan(std::shared_ptr<const detail::PlanData> data) : data_(std::move(data)) {}

const Curve& InversionPlan::curve() const { return data_->space ? data_->space->curve : data_->curve; }
int InversionPlan::input_degree() const { return data_->input_degree; }
int InversionPlan::degree() const { return data_->degree; }
double InversionPlan::diagonal() const { return data_->space ? data_->space->diagonal : data_->diagonal; }
int InversionPlan::dimension() const {
  if (data_->piecewise) return data_->piecewise->dimension;
  return data_->space ? 3 : 2;
}
bool InversionPlan::usable() const { return data_->usable; }
const char* InversionPlan::reason() const { return data_->reason; }
void InversionPlan::prepare_off_curve() const {
  if (data_->piecewise) {
    for (const detail::PiecewiseSpan& span : data_->piecewise->spans) span.plan.prepare_off_curve();
    return;
  }
  (void)detail::off_curve_data(*data_);
}

InversionPlan make_plan(const Curve& curve) {
  if (piecewise(curve)) {
    // The plans of its spans (piecewise/piecewise_plan.hpp); this plan only holds them.
    auto spans = std::make_shared<const detail::PiecewiseData>(detail::make_piecewise_data(curve));
    detail::PlanData data;
    data.curve = curve;
    data.input_degree = data.degree = curve.degree();
    data.diagonal = spans->diagonal;
    data.usable = std::any_of(spans->spans.begin(), spans->spans.end(), [](const auto& s) { return s.plan.usable(); });
    if (!data.usable) data.reason = spans->spans.front().plan.reason();
    data.piecewise = std::move(spans);
    return InversionPlan(std::make_shared<const detail::PlanData>(std::move(data)));
  }
  if (curve.dimension() == 3) {
    // A space curve: the plan of its projection, with the space data beside it (space_curve.hpp).
    validate(curve);
    auto space = std::make_shared<const detail::SpaceData>(detail::make_space_data(curve));
    detail::PlanData data = detail::make_plan_data(detail::projected_curve(*space));
    data.space = std::move(space);
    return InversionPlan(std::make_shared<const detail::PlanData>(std::move(data)));
  }
  return InversionPlan(std::make_shared<const detail::PlanData>(detail::make_plan_data(curve)));
}

void make_plans(std::span<const Curve> curves, std::span<const std::size_t> indices, std::span<InversionPlan> plans,
                int threads) {
  std::mutex mutex;
  std::optional<PlansError> first_error;  // of the lowest index, whichever thread meets it first
  tbb::task_arena arena(threads > 0 ? threads : int{tbb::task_arena::automatic});
  arena.execute([&] {
    tbb::parallel_for(tbb::blocked_range<std::size_t>(0, indices.size()), [&](const auto& range) {
      for (std::size_t k = range.begin(); k != range.end(); ++k) {
        const std::size_t i = indices[k];
        try {
          plans[i] = make_plan(curves[i]);
        } catch (const CurveError& e) {
          const std::lock_guard<std::mutex> lock(mutex);
          if (!first_error || i < first_error->index) first_error.emplace(i, e);
        }
      }
    });
  });
  if (first_error) throw *first_error;
}

std::vector<InversionPlan> make_plans(std::span<const Curve> curves, int threads) {
  std::vector<InversionPlan> plans(curves.size());
  std::vector<std::size_t> all(curves.size());
  std::iota(all.begin(), all.end(), std::size_t{0});
  make_plans(curves, all, plans, threads);
  return plans;
}

}  // namespace bezinv
