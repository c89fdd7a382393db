#pragma once
// The per-curve precomputation ("plan"). Everything that does not depend on the point is done once
// per curve, so that inverting a point costs: form the Bezout matrix B from four fixed matrices,
// find its null vector, read the parameter out, refine it. What a plan holds (the curve
// normalized, at its effective degree, B's coefficient matrices, the isolation certificate) is
// the engine's; docs/README.md walks through it.
#include <cstddef>
#include <memory>
#include <span>
#include <vector>

#include "bezinv/curve.hpp"

namespace bezinv {

class InversionPlan;
namespace detail {
struct PlanData;
const PlanData& plan_data(const InversionPlan& plan);
}  // namespace detail

// Immutable once made (copies share it), so one plan may be used from many threads.
class InversionPlan {
 public:
  // An empty plan (no curve: usable() is false); make_plan makes real ones.
  InversionPlan();

  const Curve& curve() const;  // as given (validated)
  int input_degree() const;    // the degree as given
  // The effective degree n: after an exact common factor and a degree elevation are taken out
  // (the size of B is n x n).
  int degree() const;
  // Diagonal of the bounding box of the control points (input units): the on-curve tolerance is
  // relative to it (inf for a box wider than the largest double). Where a denominator coefficient
  // is zero or of the other sign, so the control points do not bound the curve, the box of the
  // segment itself.
  double diagonal() const;
  // 2 for a plane curve, 3 for a space curve (whose points need z: invert.hpp's Point3 overloads).
  int dimension() const;
  // False when no point of the curve can be given one parameter (all its points coincide); every
  // point of it is then reported `failed` with reason(), a static text.
  bool usable() const;
  const char* reason() const;

  // What only points off the curve use (the certified nearest point, the clearance of the
  // extension) is made by the first such point, and costs up to about four times make_plan.
  // This makes it now: before timing, or in parallel over many plans. Safe from any thread, any
  // number of times (made once).
  void prepare_off_curve() const;

 private:
  friend InversionPlan make_plan(const Curve& curve);
  friend const detail::PlanData& detail::plan_data(const InversionPlan& plan);
  explicit InversionPlan(std::shared_ptr<const detail::PlanData> data);
  std::shared_ptr<const detail::PlanData> data_;
};

// Builds the plan. Throws CurveError for a curve that fails validate().
InversionPlan make_plan(const Curve& curve);

// The plans of many curves, built in parallel (threads as InvertOptions::threads: 0 = all cores):
// for a file of many curves of few points each the plans, not the points, set the time. The same
// plans make_plan gives, in order. If curves fail validate(), throws PlansError for the first of them.
std::vector<InversionPlan> make_plans(std::span<const Curve> curves, int threads = 0);

// The plans of curves[i] for each i in `indices` only, into plans[i] (plans.size() ==
// curves.size(); the others are left as they are), in parallel: a job needs the plans of the
// curves its points name, not of every curve in the file. Throws PlansError as make_plans.
void make_plans(std::span<const Curve> curves, std::span<const std::size_t> indices, std::span<InversionPlan> plans,
                int threads = 0);

class PlansError : public CurveError {
 public:
  PlansError(std::size_t index, const CurveError& error) : CurveError(error), index(index) {}
  std::size_t index;  // the curve's position in `curves`; what() is its CurveError's
};

}  // namespace bezinv
