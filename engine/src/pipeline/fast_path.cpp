#include "pipeline/fast_path.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <limits>

#include "bezinv/kernels/batch.hpp"
#include "degree_drop.hpp"
#include "isolation.hpp"
#include "pipeline/candidate.hpp"
#include "pipeline/decide.hpp"
#include "pipeline/form_b.hpp"
#include "pipeline/formula_path.hpp"
#include "pipeline/off_curve_path.hpp"
#include "refine.hpp"

namespace bezinv::detail {

void full_kernel(const PlanData& plan, std::size_t waiting, BatchWorkspace& w, int iterations) {
  const int n = plan.degree;
  const std::size_t stride = kBatchLanes;
  {
    std::array<double, kBatchLanes> u{}, v{};
    for (std::size_t k = 0; k < waiting; ++k) u[k] = w.u[w.gap_lane_of[k]], v[k] = w.v[w.gap_lane_of[k]];
    form_compacted_b(plan, u.data(), v.data(), waiting, w.gap_B.data());
  }
  kernels::active_implementation().null_vector_iterations(n, iterations, waiting, stride, w.gap_B.data(),
                                                          w.gap_z.data(), w.gap_defect.data(), w.gap_estimate.data(),
                                                          /*second=*/nullptr);
  for (std::size_t k = 0; k < waiting; ++k) {
    const std::size_t l = w.gap_lane_of[k];
    for (int r = 0; r < n; ++r) w.z[r * stride + l] = w.gap_z[r * stride + k];
    w.defect[l] = w.gap_defect[k];
    w.estimate[l] = w.gap_estimate[k];
    w.estimate[stride + l] = w.gap_estimate[stride + k];
  }
}

namespace {

// Pass 2, the gap pass: the full kernel for the `waiting` lanes w.gap_lane_of[0..waiting), then
// decide_with_gap with the refined point they kept.
void gap_pass(const PlanData& plan, std::size_t waiting, double tolerance, BatchWorkspace& w,
              LaneRows rows, StageClock& clock) {
  full_kernel(plan, waiting, w, kernels::kNullVectorIterations);
  clock.lap(&StageSeconds::kernel);
  for (std::size_t k = 0; k < waiting; ++k) {
    const std::size_t l = w.gap_lane_of[k];
    if (gap_decides(w, l)) decide_with_gap(plan, w, l, w.main[l], tolerance, true, rows[l]);
  }
  clock.lap(&StageSeconds::refine);
}

// The seed of B's null vector formed in registers (bezout_null_vector_seed), for the lanes that
// may use it: a lane far from the segment (segment_far: beyond kSegmentFarDistance of every point
// of it, by plan.segment_far_near) gets what a seed that did not settle gives, defect and residual
// +inf, without it. So far off the curve a seed seldom settles (B's two smallest singular values
// are not apart), and where it does it only gives the off-curve path a start: at noise 1e-2 the
// seed was 46% of the time at degree 20 and answered nothing. The lane then goes where an
// unsettled one goes, to the off-curve path from its samples, so its answer depends on its own
// point alone. Not where the tolerance reaches a quarter of that distance (a point within it
// is better seeded).
// Returns whether it read t out too (w.t_algebraic, every lane): where it seeded some lanes only,
// the seeded lanes' t is read from their compacted z, and no z goes back to w.z (nothing after the
// read-out uses a seed's z).
bool formed_seed(const PlanData& plan, std::size_t count, double tolerance, BatchWorkspace& w,
                 std::array<double, kBatchLanes>& poison, FarLanes far) {
  const int n = plan.degree;
  const std::size_t stride = kBatchLanes;
  const kernels::Implementation& kernel = kernels::active_implementation();
  std::array<std::uint8_t, kBatchLanes> seeded_of;
  std::size_t seeded = 0;
  if (skips_far_seeds(plan, tolerance)) {
    for (std::size_t l = 0; l < count; ++l)
      if (far.known ? !far.lanes.has(l) : !segment_far(plan, w.u[l], w.v[l]))
        seeded_of[seeded++] = static_cast<std::uint8_t>(l);
  } else {
    seeded = count;
  }
  if (seeded == count) {  // every lane (the common case near the curve): in place
    kernel.bezout_null_vector_seed(n, count, stride, plan.B0.data(), plan.Bx.data(), plan.By.data(),
                                   bilinear_coefficients(plan), w.u.data(), w.v.data(), w.z.data(), w.defect.data(),
                                   w.estimate.data(), poison.data(), kFastPathMaxDefect);
    return false;
  }
  std::array<double, kBatchLanes> u, v, seeded_poison, t;
  for (std::size_t k = 0; k < seeded; ++k) u[k] = w.u[seeded_of[k]], v[k] = w.v[seeded_of[k]];
  if (seeded > 0) {
    kernel.bezout_null_vector_seed(n, seeded, stride, plan.B0.data(), plan.Bx.data(), plan.By.data(),
                                   bilinear_coefficients(plan), u.data(), v.data(), w.gap_z.data(),
                                   w.gap_defect.data(), w.gap_estimate.data(), seeded_poison.data(),
                                   kFastPathMaxDefect);
    kernel.bernstein_parameter(n, seeded, stride, w.gap_z.data(), t.data());
  }
  // Lane l is seeded lane k where seeded_of[k] == l (in order); the others get an unsettled
  // seed's numbers (no t: its defect).
  const double inf = std::numeric_limits<double>::infinity();
  for (std::size_t l = 0, k = 0; l < count; ++l) {
    const bool from_seed = k < seeded && seeded_of[k] == l;
    w.t_algebraic[l] = from_seed ? t[k] : PointResult::nan;
    w.defect[l] = from_seed ? w.gap_defect[k] : inf;
    w.estimate[l] = from_seed ? w.gap_estimate[k] : inf;
    poison[l] = from_seed ? seeded_poison[k] : 0.0;
    k += from_seed;
  }
  return true;
}

// refine_grouped's lanes off the curve, w's lanes far_of[0..far), by nearest_newton.
[[gnu::noinline]] void refine_off_curve(const kernels::Implementation& kernel, const PlanData& plan, std::size_t far,
                                        const std::array<std::uint8_t, kBatchLanes>& far_of, BatchWorkspace& w) {
  const kernels::RationalCurve curve = kernel_curve(plan);
  std::array<double, kBatchLanes> u{}, v{}, t{}, distance{};
  for (std::size_t k = 0; k < far; ++k) {
    const std::size_t l = far_of[k];
    u[k] = w.u[l], v[k] = w.v[l], t[k] = w.t_refined[l];
  }
  kernel.nearest_newton(kernel_curve(plan, /*horner=*/true), kNearestNewtonSettings, far, u.data(), v.data(), t.data(),
                        distance.data());
  // Those that ended at an end, again from their start, compacted.
  std::size_t ends = 0;
  std::array<std::uint8_t, kBatchLanes> again_of;
  for (std::size_t k = 0; k < far; ++k)
    if (t[k] == 0.0 || t[k] == 1.0) again_of[ends++] = static_cast<std::uint8_t>(k);
  std::array<double, kBatchLanes> eu, ev, et, ed;
  for (std::size_t e = 0; e < ends; ++e) {
    const std::size_t k = again_of[e], l = far_of[k];
    eu[e] = u[k], ev[e] = v[k], et[e] = w.t_refined[l];
  }
  if (ends > 0) kernel.rational_newton(curve, kNewtonSettings, ends, eu.data(), ev.data(), et.data(), ed.data());
  for (std::size_t e = 0; e < ends; ++e) t[again_of[e]] = et[e], distance[again_of[e]] = ed[e];
  for (std::size_t k = 0; k < far; ++k) {
    const std::size_t l = far_of[k];
    w.t_refined[l] = t[k], w.distance[l] = distance[k];
  }
}

}  // namespace

kernels::NewtonSettings on_curve_newton_settings(bool formula) {
  constexpr double kFormulaOffCurveDistance = 1e-10;  // refine_grouped says why
  kernels::NewtonSettings settings = kNewtonSettings;
  if (formula) {
    settings.leave_distance = kFormulaOffCurveDistance;
    settings.final_step = kFormulaNewtonFinalStep;
  }
  return settings;
}

namespace {

// Lane-batched refinement of every lane from t_algebraic (t_refined, distance), in two groups by
// B's sigma_min estimate (||B z|| / ||B||): the lanes whose seed put them on the curve (at rounding
// level) by rational_newton, refine.cpp's Newton bit for bit; the others, off the curve (beyond
// ~1e-12 of it), by nearest_newton, the off-curve path's cheaper kernel, whose t the isolation
// certificate or the off-curve path's proofs then take.
// A lane given t by the formula has no B, so no estimate: it starts with the on-curve lanes, and
// rational_newton leaves it to the others where its first distance, |P(t*) - P0|, is beyond
// kFormulaOffCurveDistance (normalized units, the diagonal of order 1: on the curve ~1e-15, 1e-6 of the
// diagonal off it at least ~1e-6, wherever the formula's projection put t*). Without that, every
// formula lane off the curve would take rational_newton's dearer iterations. On the formula path
// its last step may be up to kFormulaNewtonFinalStep (the formula's start is less accurate than
// the seed's; tolerances.hpp): refine.cpp's Newton bit for bit but for that. A plan on the formula
// path leaves its few lanes seeded by B (the formula undefined there) the same way.
// Except where that ends at an end of the segment: whether a point by an end is within the
// tolerance there, or nearer the extension, turns on the distance's last bits, so those lanes are
// refined again by rational_newton, as the scalar code (and the SVD path) would.
// Grouping also keeps the Newton kernels' SIMD groups of one kind: a group runs until its slowest
// lane settles, and a point off the curve takes several steps where a point on it takes one. A
// lane's group depends on its own estimate or distance alone, so its answer does not depend on its
// batch. A seed that did not settle has no t and an infinite estimate (the seeds leave its residual
// uncomputed): it is not in the on-curve lanes' groups, and, like every off-curve lane without a
// start in [0, 1], it takes no place in nearest_newton's either (off the curve, most lanes).
// The lanes of newton_left are left as rational_newton's first iteration would leave them (distance
// +inf, t unmoved): formula_first ran that iteration for them.
[[gnu::noinline]] void refine_grouped(const kernels::Implementation& kernel, const PlanData& plan, std::size_t count,
                                      bool formula, BatchWorkspace& w, LaneSet newton_left) {
  constexpr double kOnCurveEstimate = 1e-12;  // on the curve: ~1e-16; 1e-6 of the diagonal off it: ~1e-7
  const kernels::RationalCurve curve = kernel_curve(plan);
  const kernels::NewtonSettings settings = on_curve_newton_settings(formula);
  std::array<std::uint8_t, kBatchLanes> near_of, far_of;
  std::size_t near = 0, far = 0;
  for (std::size_t l = 0; l < count; ++l) {
    if (!(w.estimate[l] > kOnCurveEstimate)) near_of[near++] = static_cast<std::uint8_t>(l);
    else if (w.t_refined[l] >= 0.0 && w.t_refined[l] <= 1.0) far_of[far++] = static_cast<std::uint8_t>(l);
    else w.distance[l] = PointResult::nan;  // as nearest_newton would give it back
  }
  std::size_t left = 0;
  const bool known_left = !newton_left.empty();
  if (near == count && !known_left) {  // the common case on the curve: in place
    left = kernel.rational_newton(curve, settings, count, w.u.data(), w.v.data(), w.t_refined.data(),
                                  w.distance.data());
  } else if (near > 0) {
    std::array<double, kBatchLanes> u, v, t, distance;
    std::array<std::uint8_t, kBatchLanes> newton_of;  // the near lanes rational_newton runs for
    std::size_t m = 0;
    for (std::size_t k = 0; k < near; ++k) {
      const std::size_t l = near_of[k];
      if (known_left && newton_left.has(l)) {
        w.distance[l] = std::numeric_limits<double>::infinity();
        ++left;
        continue;
      }
      newton_of[m] = static_cast<std::uint8_t>(l);
      u[m] = w.u[l], v[m] = w.v[l], t[m] = w.t_refined[l], ++m;
    }
    if (m > 0) left += kernel.rational_newton(curve, settings, m, u.data(), v.data(), t.data(), distance.data());
    for (std::size_t k = 0; k < m; ++k) {
      const std::size_t l = newton_of[k];
      w.t_refined[l] = t[k], w.distance[l] = distance[k];
    }
  }
  if (left > 0)  // the lanes rational_newton left (their t unmoved) join the others
    for (std::size_t k = 0; k < near; ++k)
      if (w.distance[near_of[k]] == std::numeric_limits<double>::infinity()) far_of[far++] = near_of[k];
  if (far > 0) refine_off_curve(kernel, plan, far, far_of, w);
}

// The lanes the loop of fast_path leaves to the off-curve path go there before it: those the
// seed did not settle, those refined onto the segment farther than the tolerance, and those whose
// algebraic t is off the segment (a formula's t for a point off the curve, its projection from the
// centre past an end, mostly), which the kernel leaves to settle(): two scalar walks, along the
// extension and on the segment. Where the off-curve path proves such a point off the curve
// (nothing of the segment or of the extension within the tolerance) those walks could find nothing
// within it, and the lane would have gone on to the same proofs from the same start. The lanes
// they do not prove go on as before (settle() then runs for them); off_curve_path does not look at
// them again. One call for all of them keeps the kernel's groups full.
void off_curve_first(const PlanData& plan, const InvertOptions& options, double tolerance, std::size_t count,
                     BatchWorkspace& w, LaneRows rows, StageClock& clock) {
  std::uint8_t any_active = 0;  // on the curve, every lane is usually done by now
  for (std::size_t l = 0; l < count; ++l) any_active |= w.active[l];
  if (!any_active) return;
  std::array<std::uint8_t, kBatchLanes> active, leaves;
  std::size_t left = 0;
  // t off [0, 1] (NaN included), or refined to a finite distance beyond the tolerance.
  for (std::size_t l = 0; l < count; ++l) {
    const double t = w.t_algebraic[l], d = w.distance[l];
    const bool inside = (t >= 0.0) & (t <= 1.0);
    const bool beyond = (d > tolerance) & (d <= std::numeric_limits<double>::max());
    leaves[l] = w.active[l] & !w.drops[l] & (!inside | beyond);
    left += leaves[l];
  }
  if (left == 0) return;
  clock.lap(&StageSeconds::refine);
  for (std::size_t l = 0; l < count; ++l) active[l] = w.active[l], w.active[l] = leaves[l];
  off_curve_path(plan, options, count, w, rows, clock);
  for (std::size_t l = 0; l < count; ++l)
    if (!leaves[l]) w.active[l] = active[l];
}

// Degree 2 decides each lane with B's gap at once (the pivoted kernel gives it); a conic's
// formula lanes have no B, so on the formula path they take the two passes: the isolation
// certificate, then the gap pass for the lanes it leaves.
bool takes_two_passes(const PlanData& plan, bool formula) { return plan.degree >= 3 || formula; }

}  // namespace

void fast_path_seed(const PlanData& plan, const Point* points, LaneRows rows, std::size_t count,
                    const InvertOptions& options, BatchWorkspace& w, StageClock& clock, FarLanes far,
                    bool formula_given) {
  const int n = plan.degree;
  const std::size_t stride = kBatchLanes;
  const double tolerance = normalized_tolerance(plan, options);
  const bool formed_b = forms_b_in_seed(plan, options);
  const kernels::Implementation& kernel = kernels::active_implementation();
  const bool formula = takes_formula_path(plan, options);
  const bool two_passes = takes_two_passes(plan, formula);
  bool read_out = true;  // t still to be read from w.z
  if (formula) {
    formula_or_seed(plan, points, rows, count, w, formula_given);
    clock.lap(&StageSeconds::kernel);
  } else if (formed_b) {
    std::array<double, kBatchLanes> poison;
    read_out = !formed_seed(plan, count, tolerance, w, poison, far);
    mark_overflowing_b(plan, points, poison.data(), count, w, rows);
  } else if (two_passes) {
    kernel.null_vector_seed(n, count, stride, w.B.data(), w.z.data(), w.defect.data(), w.estimate.data(),
                            kFastPathMaxDefect);
  } else {
    kernel.null_vector(n, count, stride, w.B.data(), w.z.data(), w.defect.data(), w.estimate.data(),
                       /*second=*/nullptr);
  }
  if (!formula) {
    clock.lap(&StageSeconds::kernel);
    if (read_out) kernel.bernstein_parameter(n, count, stride, w.z.data(), w.t_algebraic.data());
  }
  for (std::size_t l = 0; l < count; ++l)
    if (!w.active[l] || !(w.defect[l] <= kFastPathMaxDefect) ||
        (!two_passes && !(w.estimate[stride + l] >= kFastPathMinGap)))
      w.t_algebraic[l] = PointResult::nan;
  clock.lap(&StageSeconds::read_out);
}

void fast_path_decide(const PlanData& plan, LaneRows rows, std::size_t count, const InvertOptions& options,
                      BatchWorkspace& w, StageClock& clock, LaneSet newton_left) {
  const double tolerance = normalized_tolerance(plan, options);
  const kernels::Implementation& kernel = kernels::active_implementation();
  const bool formula = takes_formula_path(plan, options);
  const bool two_passes = takes_two_passes(plan, formula);
  std::fill_n(w.off_curve_tried.begin(), count, std::uint8_t{0});
  // Where the formula gave t, the lane's path says so.
  auto path_of = [&](std::size_t l) { return formula && w.from_formula[l] ? Path::formula : Path::bezout_lu; };
  // Refinement, lane-batched: the kernel runs refine.cpp's safeguarded Newton for every lane whose
  // t_algebraic is in [0,1] and gives settle()'s numbers bit for bit. It leaves the rest to
  // settle(), as it does a lane that ends at an end of the segment off the curve (settle() then
  // also looks along the extension).
  std::copy_n(w.t_algebraic.begin(), count, w.t_refined.begin());
  refine_grouped(kernel, plan, count, formula, w, newton_left);
  detail::degree_drops_batch(plan, w.u.data(), w.v.data(), count, w.drops.data());
  if (two_passes) {
    // The common case of pass 1, for the whole batch first: a lane refined onto the segment within
    // the tolerance (the kernel clamps to [0, 1]) that the certificate's first test settles. The
    // loop below would answer it the same way, at a higher cost per lane. Where p and q both drop
    // degree at the point, B's null vector is not the point's, but a start from the formula is as
    // good as anywhere (a function's graph drops at every point: x(t) linear, y(t)'s top tiny).
    detail::isolated_by_far_boxes(plan, w.t_refined.data(), w.distance.data(), tolerance, count,
                                  w.certified.data());
    for (std::size_t l = 0; l < count; ++l)
      if (w.certified[l] && w.active[l] && (!w.drops[l] || (formula && w.from_formula[l])) &&
          std::isfinite(w.t_algebraic[l]) && w.distance[l] <= tolerance) {
        w.active[l] = 0;
        answer_fast(plan, w.t_refined[l], w.distance[l], w.estimate[l], PointResult::nan, rows[l], path_of(l));
      }
  }
  if (two_passes) off_curve_first(plan, options, tolerance, count, w, rows, clock);
  std::size_t waiting = 0;  // lanes of pass 2
  for (std::size_t l = 0; l < count; ++l) {
    if (!w.active[l] || w.drops[l]) continue;
    Candidate& c = w.main[l];
    const bool refined = std::isfinite(w.t_algebraic[l]);
    if (refined) {
      const bool at_end = w.t_refined[l] == 0.0 || w.t_refined[l] == 1.0;
      // Off the segment at an end: the off-curve path looks at the extension (off_curve_path.hpp),
      // where settle() would walk it.
      if (at_end && w.distance[l] > tolerance) continue;
      if (std::isfinite(w.distance[l])) {
        c = Candidate{};
        c.t = w.t_refined[l];
        c.distance = w.distance[l];
        c.path = path_of(l);
        classify(c, tolerance);
      } else {
        c = settle(plan, w.u[l], w.v[l], w.t_algebraic[l], path_of(l), tolerance, true);
      }
    }
    if (!two_passes) {
      if (refined) decide_with_gap(plan, w, l, c, tolerance, false, rows[l]);
      continue;
    }
    if (!refined) continue;  // z did not settle: the SVD path
    if (c.on_segment && detail::isolated(plan, w.u[l], w.v[l], c.t, c.distance, tolerance)) {
      w.active[l] = 0;
      answer_fast(plan, c.t, c.distance, w.estimate[l], PointResult::nan, rows[l], path_of(l));
    } else if (c.on_segment) {
      w.gap_lane_of[waiting++] = static_cast<std::uint8_t>(l);
    }  // off the curve: the off-curve path, then (if it cannot prove its answer) the SVD path
  }
  clock.lap(&StageSeconds::refine);
  if (waiting > 0) gap_pass(plan, waiting, tolerance, w, rows, clock);
}

}  // namespace bezinv::detail
