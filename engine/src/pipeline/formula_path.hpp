#pragma once
// The formula path: the fast path's algebraic step by the curve's inversion formula t = N/M
// (Wang & Joe, bezinv/inversion_formula.hpp) instead of B's null vector. Where the formula is valid
// at a lane's point, t_algebraic = N/M and no B is formed; the other lanes (near the formula's base
// points, far from the curve) get the seed as on the fast path. From there every lane goes on as
// there: refinement, the isolation certificate, the gap pass, the SVD path.
#include <array>
#include <cstddef>

#include "bezinv/invert.hpp"
#include "bezinv/kernels/batch.hpp"
#include "bezinv/tolerances.hpp"
#include "plan_data.hpp"
#include "pipeline/workspace.hpp"

namespace bezinv::detail {

// The formula the formula path evaluates: the plan's linear one where it has one (a function's
// graph: PlanData::linear_formula), else a conic's or cubic's made with the plan
// (PlanData::low_degree_formula), else the curve's inversion formula (formula_path_data).
const FormulaPathData& fast_path_formula(const PlanData& plan);

// Whether a batch of this plan takes the formula path: asked for (Algebraic::formula; or automatic
// on a conic or cubic with one denominator and moderate weights, or on a plan close to a lower
// degree that has a linear formula), with the fast path, from degree 2, where the plan has a
// formula: its linear one (any degree), its conic's or cubic's, or the curve's, made and accurate
// on the segment (up to kFormulaPathMaxDegree).
bool takes_formula_path(const PlanData& plan, const InvertOptions& options);

// Algebraic::automatic takes the curve's own inversion formula (degree 4 to kFormulaPathMaxDegree)
// for a call of at least kCurveFormulaMinPoints[degree] points. Making the formula costs ~0.07 ms at
// degree 4, ~0.75 ms at 8, ~4 ms at 12, ~17 ms at 16 and ~55 ms at 20 (least squares on a sampled
// system, once per plan); the formula path then saves ~14 ns a point at degree 4, ~29 at 8, ~60 at
// 12, ~130 at 16 and ~200 at 20 against the Bezout seed (bench/, AVX-512, one thread). The table is
// twice the break-even, making cost over saving, rounded up: on one thread the formula is taken
// where it clearly pays, and on two, whose other thread waits while one makes it, where it pays at
// all (docs/inversion-formula.md; the savings were measured before kFormulaNewtonFinalStep, which
// made the path 1.01-1.19 times faster: the table errs on the side of bezout). By the call's points,
// not per thread: a call's rows do not depend on the number of threads.
inline constexpr std::array<std::size_t, 21> kCurveFormulaMinPoints{
    0,      0,      0,      0,      10000,  15000,  21000,  29000,  53000,  70000, 98000,
    114000, 140000, 176000, 222000, 236000, 264000, 326000, 378000, 467000, 541000};
static_assert(kCurveFormulaMinPoints.size() == kFormulaPathMaxDegree + 1);

// Whether Algebraic::automatic takes the curve's own formula for a call of `points` points on this
// plan: refined, with the fast path, one denominator with moderate weights
// (formula_weights_moderate), degree 4..kFormulaPathMaxDegree, and kCurveFormulaMinPoints. The
// call then runs as with Algebraic::formula. The choice depends on the call alone, never on the
// batch, the thread or the thread count.
bool repays_curve_formula(const PlanData& plan, const InvertOptions& options, std::size_t points);

// Whether refine is off and the formula asked for (InvertOptions::algebraic), and the plan has one:
// formula_unrefined answers what it can, B is formed late for the other lanes.
bool reports_formula_unrefined(const PlanData& plan, const InvertOptions& options);

// N/M at the plan-normalized point (u, v) (f from formula_path_data, usable), or NaN where the
// formula is not used there: M within kFormulaPathMinDenominator of the size of its terms (a base
// point near), or the point farther than kFormulaPathMaxCoordinate.
double formula_parameter(const FormulaPathData& f, double u, double v);

// The formula as the formula_parameter kernel takes it (the same N/M, the same NaNs, the same bits:
// the formula path's batches take the kernel, at every degree; f outlives it).
kernels::PlaneFormula plane_formula(const FormulaPathData& f);

// The algebraic step of the fast path for every active lane: t_algebraic, defect and the sigma_min
// estimate (NaN on formula lanes), from_formula. The seed's lanes have their B formed here; a lane
// whose B overflows is answered as a far point. formula_given: w.t_algebraic holds N / M for every
// lane already (formula_first left it there), else the formula_parameter kernel computes it.
void formula_or_seed(const PlanData& plan, const Point* points, LaneRows rows, std::size_t count,
                     BatchWorkspace& w, bool formula_given = false);

// With refine off: every active lane whose N/M is a parameter of the segment within the tolerance
// of the point, with no degree drop there and the isolation certificate proving no other branch
// within the tolerance (any stationary point of the distance near t is within
// kDistinctParameterGap of it; isolation.hpp), is answered ok with t = N/M itself, path formula.
// The others go on to the SVD path, whose algebraic t they get as with bezout.
void formula_unrefined(const PlanData& plan, const InvertOptions& options, std::size_t count, BatchWorkspace& w,
                       LaneRows rows);

}  // namespace bezinv::detail
