// The formula path's common case for a conic or a cubic in one kernel (bezinv/kernels/batch.hpp,
// Implementation::formula_newton): per point, the engine's normalization, the inversion formula's
// t = N / M, the first iteration of the Newton refinement from it, and the isolation
// certificate's first test. Re-included once per instruction set by hwy/foreach_target.h (see
// formula_newton.cpp).
//
// Why fused: for a point on a conic or a cubic each of those steps is a few dozen operations, and
// run as separate kernels and engine loops over a batch, the loads, stores and loop overheads
// between them cost as much as the arithmetic. A point on the curve, given t by the formula, is
// settled by the first Newton iteration (its last step): this kernel runs that iteration alone,
// with rational_newton's own code (NewtonJet, SmallStep), and leaves every lane it would take
// further, so each lane it settles has the three kernels' bits. Compiled with -ffp-contract=off,
// as they are.
#if defined(BEZINV_KERNELS_BATCH_FORMULA_NEWTON_INL_H_) == defined(HWY_TARGET_TOGGLE)
#ifdef BEZINV_KERNELS_BATCH_FORMULA_NEWTON_INL_H_
#undef BEZINV_KERNELS_BATCH_FORMULA_NEWTON_INL_H_
#else
#define BEZINV_KERNELS_BATCH_FORMULA_NEWTON_INL_H_
#endif

#include <hwy/highway.h>

#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <limits>

#include "batch/formula_parameter-inl.hpp"
#include "batch/rational_newton-inl.hpp"
#include "batch/sizes-inl.hpp"
#include "bezinv/kernels/batch.hpp"

HWY_BEFORE_NAMESPACE();
namespace bezinv::kernels::HWY_NAMESPACE {

// Sets in `words` (lane l: bit l % 64 of word l / 64) the bits of `bits` (bit k: lane first + k).
HWY_INLINE void or_lane_bits(std::uint64_t bits, std::size_t first, std::uint64_t* words) {
  const std::size_t shift = first % 64;
  words[first / 64] |= bits << shift;
  if (shift != 0 && (bits >> (64 - shift)) != 0) words[first / 64 + 1] |= bits >> (64 - shift);
}

// A group's mask as bits (bit k: the group's lane k), gathered in a register: a vector of doubles
// has at most eight lanes, one byte of mask bits.
template <class D>
HWY_INLINE std::uint64_t group_bits(D, const hn::Mask<D>& m) {
  namespace hw = hwy::HWY_NAMESPACE;
  using DN = typename D::D;
  const DN dn;
  constexpr std::size_t L = hw::MaxLanes(DN());
  static_assert(L <= 8 && hn::MaxLanes(D()) < 64);  // group_lane_bits shifts by the group's lanes
  std::uint64_t bits = 0;
  for (int g = 0; g < D::kVectors; ++g) {
    std::uint8_t byte = 0;
    hw::StoreMaskBits(dn, m.m[g], &byte);
    bits |= std::uint64_t{byte} << (static_cast<std::size_t>(g) * L);
  }
  return bits;
}

// After a group's stores, the bits of its lanes not settled (t NaN) and of those that
// rational_newton's first iteration from N / M leaves: N / M (t0, the group's array) in [0, 1], and
// the first distance h (distance_out, where not settled) in length()'s own range (there the
// iteration's first test keeps the lane) and beyond the leave distance. Out of line and from memory:
// made in the kernel from its registers, the masks it needs live through the certificate measured
// 3-5% slower on a curve, where no group calls this.
template <class D>
HWY_NOINLINE void group_lane_bits(D d, const NewtonSettings& settings, const double* HWY_RESTRICT t0,
                                  std::size_t first, std::size_t lanes, const double* HWY_RESTRICT t_out,
                                  const double* HWY_RESTRICT distance_out, const FormulaLanes& bits) {
  using M = hn::Mask<D>;
  const double nan = std::numeric_limits<double>::quiet_NaN();
  const auto t = hn::LoadGroup(d, t_out, first, lanes, nan), h = hn::LoadGroup(d, distance_out, first, lanes, nan);
  const auto start = hn::Load(d, t0);
  const M left = hn::IsNaN(t);
  const M inside = hn::And(hn::Ge(start, hn::Zero(d)), hn::Le(start, hn::Set(d, 1.0)));
  const M in_range = hn::And(hn::Gt(h, hn::Set(d, 1e-150)), hn::Lt(h, hn::Set(d, 1e150)));
  const M leaves = hn::And(left, hn::And(inside, hn::And(in_range, hn::Gt(h, hn::Set(d, settings.leave_distance)))));
  const std::uint64_t group = (std::uint64_t{1} << lanes) - 1;  // lanes < 64: padding lanes masked off
  or_lane_bits(group_bits(d, left) & group, first, bits.left);
  or_lane_bits(group_bits(d, leaves) & group, first, bits.leaves);
}

// One group of LW = MaxLanes(D) points, xy[2 first ..] (`lanes` of them; the others padded with
// NaN points, which no step settles).
template <int N, class D>
HWY_INLINE std::size_t formula_newton_group(D d, const PlaneFormula& formula, const RationalCurve& curve,
                                            const NewtonSettings& settings, const PointFrame& frame,
                                            const PieceCertificate& certificate, double tolerance,
                                            std::size_t first, std::size_t lanes, const double* HWY_RESTRICT xy,
                                            double* HWY_RESTRICT t_out, double* HWY_RESTRICT distance_out,
                                            const FormulaStart* on_the_way, const FormulaLanes* lane_bits) {
  namespace hw = hwy::HWY_NAMESPACE;
  using DN = typename D::D;
  using V = hn::Vec<D>;
  using M = hn::Mask<D>;
  constexpr std::size_t LW = hn::MaxLanes(D()), L = hw::MaxLanes(DN());
  const DN dn;
  HWY_ALIGN double u[LW], v[LW], t0[LW];
  {
    HWY_ALIGN double padded[2 * LW];
    const double* points = xy + 2 * first;
    if (lanes < LW) {
      std::fill_n(padded, 2 * LW, std::numeric_limits<double>::quiet_NaN());
      std::copy_n(points, 2 * lanes, padded);
      points = padded;
    }
    // PlanData::normalize: scaled before the difference, then rotated.
    const auto scale = hw::Set(dn, frame.scale), cx = hw::Set(dn, frame.centre_x), cy = hw::Set(dn, frame.centre_y);
    const auto c = hw::Set(dn, frame.cos), s = hw::Set(dn, frame.sin);
    for (int g = 0; g < D::kVectors; ++g) {
      hw::Vec<DN> x, y;
      hw::LoadInterleaved2(dn, points + 2 * g * L, x, y);
      const auto dx = hw::Sub(hw::Mul(x, scale), cx), dy = hw::Sub(hw::Mul(y, scale), cy);
      hw::Store(hw::Sub(hw::Mul(c, dx), hw::Mul(s, dy)), dn, u + g * L);
      hw::Store(hw::Add(hw::Mul(s, dx), hw::Mul(c, dy)), dn, v + g * L);
    }
  }
  formula_parameter_groups<D::kVectors>(dn, formula, u, v, t0);
  if (on_the_way != nullptr) {  // now, from the arrays: kept in registers for later, they would spill others
    hn::StoreGroup(hn::Load(d, u), d, on_the_way->u, first, lanes);
    hn::StoreGroup(hn::Load(d, v), d, on_the_way->v, first, lanes);
    hn::StoreGroup(hn::Load(d, t0), d, on_the_way->t, first, lanes);
  }

  // rational_newton_group's first iteration, for the lanes it settles there (its last step, or a
  // step that converged where t's last ulps do not move P), kLeaving included: a lane whose first
  // distance exceeds settings.leave_distance is not settled.
  const V uw = hn::Load(d, u), vw = hn::Load(d, v), t = hn::Load(d, t0);
  const V zero = hn::Zero(d), one = hn::Set(d, 1.0);
  const M inside = hn::And(hn::Ge(t, zero), hn::Le(t, one));  // false for NaN
  const V start = hn::IfThenElse(inside, t, zero);
  const NewtonJet<D> jet(d, CasteljauCurve<N>{curve}, uw, vw, start, hn::Set(d, settings.max_step));
  const M going = hn::And(hn::And(inside, hn::And(jet.plain, hn::IsFinite(jet.h))),
                          hn::And(hn::Le(jet.h, hn::Set(d, settings.leave_distance)), jet.steps));
  const M small = hn::And(going, hn::Le(hn::Abs(jet.step), hn::Set(d, settings.trusted_step)));
  const SmallStep<D> taken(d, jet, start, small, hn::Set(d, settings.final_step));
  const M last = hn::And(taken.last, taken.last_plain);
  const M converged = hn::AndNot(taken.fast, taken.converged);
  const V distance = hn::IfThenElse(last, taken.updated, jet.h);
  M settled = hn::And(hn::Or(last, converged), hn::Le(distance, hn::Set(d, tolerance)));

  // The isolation certificate's first test (the engine's isolated_by_far_boxes): by its floors,
  // and for the lanes they do not pass, by the bounds of their piece (gathers; a lane not settled
  // looks up piece 0, so that every index is in range).
  const hw::RebindToSigned<DN> di;
  const auto last_piece = hw::Set(di, certificate.pieces - 1);
  const auto pieces = hw::Set(dn, static_cast<double>(certificate.pieces));
  const auto factor = hw::Set(dn, certificate.monotone_factor), limit = hw::Set(dn, certificate.limit);
  const auto around_floor = hw::Set(dn, certificate.around_floor), far_floor = hw::Set(dn, certificate.far_floor);
  std::size_t count = 0;
  for (int g = 0; g < D::kVectors; ++g) {
    const auto dg = distance.v[g];
    const auto floors = hw::And(hw::Lt(dg, around_floor), hw::Gt(hw::Sub(far_floor, dg), limit));
    if (!hw::AllFalse(dn, hw::AndNot(floors, settled.m[g]))) {
      const auto tg = hw::IfThenElseZero(settled.m[g], taken.next.v[g]);
      const auto j = hw::Min(hw::ConvertTo(di, hw::Mul(tg, pieces)), last_piece);
      const auto around = hw::Or(hw::Lt(dg, hw::Mul(hw::GatherIndex(dn, certificate.monotone, j), factor)),
                                 hw::Lt(dg, hw::GatherIndex(dn, certificate.unique, j)));
      const auto far = hw::Gt(hw::Sub(hw::GatherIndex(dn, certificate.far, j), dg), limit);
      settled.m[g] = hw::And(settled.m[g], hw::Or(floors, hw::And(around, far)));
    }
    count += hw::CountTrue(dn, settled.m[g]);
  }
  // A lane not settled: t NaN, and its first distance, from which the caller tells whether
  // rational_newton's first iteration leaves it (so as not to run that iteration again).
  hn::StoreGroup(hn::IfThenElse(settled, taken.next, hn::Set(d, std::numeric_limits<double>::quiet_NaN())), d, t_out,
                 first, lanes);
  hn::StoreGroup(hn::IfThenElse(settled, distance, jet.h), d, distance_out, first, lanes);
  if (lane_bits != nullptr && count < lanes)  // (a group all settled, as on a curve, sets no bit)
    group_lane_bits(d, settings, t0, first, lanes, t_out, distance_out, *lane_bits);
  return count;
}

std::size_t formula_newton_batch(const PlaneFormula& formula, const RationalCurve& curve,
                                 const NewtonSettings& settings, const PointFrame& frame,
                                 const PieceCertificate& certificate, double tolerance, std::size_t count,
                                 const double* xy, double* t, double* distance, const FormulaStart* start,
                                 const FormulaLanes* lane_bits) {
  check_size<kFormulaParameterMinDegree, kFormulaParameterMaxDegree>("formula_newton's formula", formula.degree);
  std::size_t settled = 0;
  dispatch_size<kFormulaNewtonMinDegree, kFormulaNewtonMaxDegree>("formula_newton", curve.degree, [&](auto size) {
    constexpr int N = decltype(size)::value;
    wide::ForEachGroup<kNewtonWideVectors<N>>(count, [&](auto group, std::size_t first, std::size_t lanes) {
      settled += formula_newton_group<N>(group, formula, curve, settings, frame, certificate, tolerance, first, lanes,
                                         xy, t, distance, start, lane_bits);
    });
  });
  return settled;
}

}  // namespace bezinv::kernels::HWY_NAMESPACE
HWY_AFTER_NAMESPACE();

#endif  // BEZINV_KERNELS_BATCH_FORMULA_NEWTON_INL_H_
