// Lane-batched Newton's method for the nearest point of a plane curve given as quotients of
// polynomials in the Bernstein basis, one point per lane (bezinv/kernels/batch.hpp,
// Implementation::rational_newton). Re-included once per instruction set by hwy/foreach_target.h
// (see rational_newton.cpp).
//
// Every lane runs the same operations, in the same order, as the engine's scalar refinement
// (engine/src/refine.cpp: de Casteljau on the four polynomials, the jet read off the last three
// points, the Newton step of f(t) = (P(t) - P0) . P'(t)). No fused multiply-add is used and the
// file is compiled with -ffp-contract=off, so a lane settled here has the very bits the scalar
// code would have produced from the same start, on every instruction set. The file also holds
// rational_slope: P and P' by Horner's rule (HornerCurve), as the engine's curve_slope_horner.
#if defined(BEZINV_KERNELS_BATCH_RATIONAL_NEWTON_INL_H_) == defined(HWY_TARGET_TOGGLE)
#ifdef BEZINV_KERNELS_BATCH_RATIONAL_NEWTON_INL_H_
#undef BEZINV_KERNELS_BATCH_RATIONAL_NEWTON_INL_H_
#else
#define BEZINV_KERNELS_BATCH_RATIONAL_NEWTON_INL_H_
#endif

#include <hwy/highway.h>

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <limits>

#include "batch/sizes-inl.hpp"
#include "batch/wide-inl.hpp"
#include "bezinv/kernels/batch.hpp"

HWY_BEFORE_NAMESPACE();
namespace bezinv::kernels::HWY_NAMESPACE {
// Highway's operations on wide vectors (batch/wide-inl.hpp): D is a wide::Tag<G>, G vectors of
// lanes processed side by side.
namespace hn = wide;

// `Steps` rounds of de Casteljau, f_i <- (1 - t) f_i + t f_{i+1}, on the coefficients f = c[0..N]
// of one polynomial at one t per lane of a native vector; out[k] = the f_k left over, k < Count.
// Written out (every loop unrolled) so that f lives in registers: with the loops rolled GCC keeps
// the four polynomials' f on the stack, every update a store and a reload.
template <int N, int Steps, int Count, class DN>
HWY_INLINE void de_casteljau_inline(DN d, const double* HWY_RESTRICT c, hwy::HWY_NAMESPACE::Vec<DN> t,
                                    hwy::HWY_NAMESPACE::Vec<DN>* HWY_RESTRICT out) {
  namespace hw = hwy::HWY_NAMESPACE;
  static_assert(0 <= Steps && Steps <= N && Count <= N + 1 - Steps);
  const auto s = hw::Sub(hw::Set(d, 1.0), t);
  hw::Vec<DN> f[N + 1];
#pragma GCC unroll 33
  for (int i = 0; i <= N; ++i) f[i] = hw::Set(d, c[i]);
#pragma GCC unroll 32
  for (int r = 1; r <= Steps; ++r) {
#pragma GCC unroll 32
    for (int i = 0; i <= N - r; ++i) f[i] = hw::Add(hw::Mul(s, f[i]), hw::Mul(t, f[i + 1]));
  }
  for (int k = 0; k < Count; ++k) out[k] = f[k];
}

// The same, not inlined: one copy per size instead of one per call site and group width (inlined
// at every size, the copies multiply this file's compile time; docs/kernels.md).
template <int N, int Steps, int Count, class DN>
HWY_NOINLINE void de_casteljau_native(DN d, const double* HWY_RESTRICT c, hwy::HWY_NAMESPACE::Vec<DN> t,
                                      hwy::HWY_NAMESPACE::Vec<DN>* HWY_RESTRICT out) {
  de_casteljau_inline<N, Steps, Count>(d, c, t, out);
}

// The same for a wide group, native vector by native vector.
template <int N, int Steps, int Count, class D>
HWY_INLINE void de_casteljau(D, const double* HWY_RESTRICT c, const hn::Vec<D>& t, hn::Vec<D>* HWY_RESTRICT out) {
  using DN = typename D::D;
  for (int g = 0; g < D::kVectors; ++g) {
    hwy::HWY_NAMESPACE::Vec<DN> f[Count];
    if constexpr (N <= 4)  // the call would cost more than these few steps
      de_casteljau_inline<N, Steps, Count>(DN(), c, t.v[g], f);
    else
      de_casteljau_native<N, Steps, Count>(DN(), c, t.v[g], f);
    for (int k = 0; k < Count; ++k) out[k].v[g] = f[k];
  }
}

// p, p', p'' of one polynomial from the three points left after N-2 de Casteljau steps (the
// quadratic they define: its second difference, first difference and value; as the engine's
// bernstein_jet_from_last_points).
template <int N, class V>
struct Jet1 {
  V value, first, second;
  Jet1(V t, V b0, V b1, V b2) {
    const hn::DFromV<V> d;
    const V s = hn::Sub(hn::Set(d, 1.0), t);
    second = hn::Zero(d);
    if constexpr (N >= 2) {
      second = hn::Mul(hn::Set(d, N * (N - 1.0)), hn::Add(hn::Sub(b2, hn::Mul(hn::Set(d, 2.0), b1)), b0));
      b0 = hn::Add(hn::Mul(s, b0), hn::Mul(t, b1));
      b1 = hn::Add(hn::Mul(s, b1), hn::Mul(t, b2));
    }
    value = hn::Add(hn::Mul(s, b0), hn::Mul(t, b1));
    first = hn::Mul(hn::Set(d, static_cast<double>(N)), hn::Sub(b1, b0));
  }
};

// x = num/den and its two derivatives: x' = (num' - den' x) / den, x'' = (num'' - 2 den' x' - den'' x) / den.
template <int N, class V>
HWY_INLINE void quotient_jet(const Jet1<N, V>& num, const Jet1<N, V>& den, V& x, V& dx, V& ddx) {
  const hn::DFromV<V> d;
  x = hn::Div(num.value, den.value);
  dx = hn::Div(hn::Sub(num.first, hn::Mul(den.first, x)), den.value);
  ddx = hn::Div(hn::Sub(hn::Sub(num.second, hn::Mul(hn::Mul(hn::Set(d, 2.0), den.first), dx)), hn::Mul(den.second, x)),
                den.value);
}

// |(ex, ey)| as the engine's length(): sqrt(ex^2 + ey^2), which the engine replaces by std::hypot
// outside (1e-150, 1e150). `plain` marks the lanes where both agree (0 included): elsewhere the
// kernel leaves the lane to the scalar code rather than imitate hypot's rounding.
template <class V>
HWY_INLINE V plain_length(V ex, V ey, hn::Mask<hn::DFromV<V>>& plain) {
  const hn::DFromV<V> d;
  const V h = hn::Sqrt(hn::Add(hn::Mul(ex, ex), hn::Mul(ey, ey)));
  plain = hn::Or(hn::And(hn::Lt(h, hn::Set(d, 1e150)), hn::Gt(h, hn::Set(d, 1e-150))),
                 hn::And(hn::Eq(ex, hn::Zero(d)), hn::Eq(ey, hn::Zero(d))));
  return h;
}

// |P(t) - (u, v)| by a full de Casteljau pass (the engine's distance()).
template <int N, class D>
HWY_INLINE hn::Vec<D> point_distance(D d, const RationalCurve& curve, hn::Vec<D> u, hn::Vec<D> v, hn::Vec<D> t,
                                     hn::Mask<D>& plain) {
  hn::Vec<D> a[1], b[1], c[1], e[1];
  de_casteljau<N, N, 1>(d, curve.x_num, t, a);
  de_casteljau<N, N, 1>(d, curve.x_den, t, b);
  de_casteljau<N, N, 1>(d, curve.y_num, t, c);
  if (curve.y_den == curve.x_den)  // one denominator (RationalCurve): the same numbers
    e[0] = b[0];
  else
    de_casteljau<N, N, 1>(d, curve.y_den, t, e);
  return plain_length(hn::Sub(hn::Div(a[0], b[0]), u), hn::Sub(hn::Div(c[0], e[0]), v), plain);
}

// The curve as the Newton iterations below see it: its jet (P, P', P'') at t, and |P(t) - P0|.
// By de Casteljau, the scalar refinement's operations (degree N at compile time):
template <int N>
struct CasteljauCurve {
  const RationalCurve& curve;

  template <class D, class V = hn::Vec<D>>
  HWY_INLINE void jet(D d, const V& t, V& x, V& dx, V& ddx, V& y, V& dy, V& ddy) const {
    // The last three points of N - 2 de Casteljau steps (the two coefficients at N = 1, and 0).
    constexpr int kSteps = N >= 2 ? N - 2 : 0, kLeft = N >= 2 ? 3 : 2;
    const V zero = hn::Zero(d);
    V a[3] = {zero, zero, zero}, b[3] = {zero, zero, zero}, c[3] = {zero, zero, zero}, e[3] = {zero, zero, zero};
    de_casteljau<N, kSteps, kLeft>(d, curve.x_num, t, a);
    de_casteljau<N, kSteps, kLeft>(d, curve.x_den, t, b);
    de_casteljau<N, kSteps, kLeft>(d, curve.y_num, t, c);
    const Jet1<N, V> xn(t, a[0], a[1], a[2]), xd(t, b[0], b[1], b[2]);
    const Jet1<N, V> yn(t, c[0], c[1], c[2]);
    quotient_jet(xn, xd, x, dx, ddx);
    if (curve.y_den == curve.x_den) {  // one denominator (RationalCurve): its jet once, the same numbers
      quotient_jet(yn, xd, y, dy, ddy);
      return;
    }
    de_casteljau<N, kSteps, kLeft>(d, curve.y_den, t, e);
    quotient_jet(yn, Jet1<N, V>(t, e[0], e[1], e[2]), y, dy, ddy);
  }

  template <class D, class V = hn::Vec<D>>
  HWY_INLINE V distance(D d, const V& u, const V& v, const V& t, hn::Mask<D>& plain) const {
    return point_distance<N>(d, curve, u, v, t, plain);
  }
};

// By Horner's rule on curve.horner (RationalCurve), as the engine's curve_slope_horner:
//     sum a_i (1-t)^(m-i) t^i = (1-t)^m sum a_i r^i,   r = t / (1-t)   (t <= 1/2),
//                             = t^m sum a_i r^(m-i),    r = (1-t) / t   (above),
// r <= 1 either way, so the sum stays as well conditioned as the Bernstein form. Each lane picks
// its end's coefficient at every step (a blend of two broadcasts); the degree is a run-time
// number (no array of intermediate values to keep in registers, so one copy serves every degree).
struct HornerCurve {
  const RationalCurve& curve;

  // Level `level` (0: values, 1: first derivatives, 2: second) of the four polynomials, before the
  // factor base^m.
  template <class D, class V = hn::Vec<D>>
  HWY_INLINE void level(D d, int level, const V& r, const hn::Mask<D>& low, V out[4]) const {
    const int n = curve.degree, m = n - level, stride = 3 * n;
    const int offset = level == 0 ? 0 : (level == 1 ? n + 1 : 2 * n + 1);
    const double* c[4];
    for (int p = 0; p < 4; ++p) {
      c[p] = curve.horner + p * stride + offset;
      out[p] = hn::IfThenElse(low, hn::Set(d, c[p][m]), hn::Set(d, c[p][0]));
    }
    for (int k = 1; k <= m; ++k)
      for (int p = 0; p < 4; ++p)
        out[p] = hn::Add(hn::Mul(out[p], r), hn::IfThenElse(low, hn::Set(d, c[p][m - k]), hn::Set(d, c[p][k])));
  }

  // r, and whether the lane is in the lower half (r = t / (1-t) there).
  template <class D, class V = hn::Vec<D>>
  HWY_INLINE hn::Mask<D> ratio(D d, const V& t, V& r) const {
    const V s = hn::Sub(hn::Set(d, 1.0), t);
    const hn::Mask<D> low = hn::Le(t, hn::Set(d, 0.5));
    r = hn::Div(hn::IfThenElse(low, t, s), hn::IfThenElse(low, s, t));
    return low;
  }

  // Levels 0 .. kLevels - 1 of the four polynomials at t, each times its factor base^m (base^n,
  // base^(n-1), base^(n-2); base = 1 - t, or t above 1/2); a level the degree does not have, 0.
  template <int kLevels, class D, class V = hn::Vec<D>>
  HWY_INLINE void levels(D d, const V& t, V value[kLevels][4]) const {
    const int n = curve.degree;
    V r;
    const hn::Mask<D> low = ratio(d, t, r);
    const V one = hn::Set(d, 1.0), base = hn::IfThenElse(low, hn::Sub(one, t), t);
    V base_n2 = one;
    for (int k = 2; k < n; ++k) base_n2 = hn::Mul(base_n2, base);
    const V base_n1 = n >= 2 ? hn::Mul(base_n2, base) : one;
    const V powers[3] = {n >= 2 ? hn::Mul(base_n1, base) : base, base_n1, base_n2};
    for (int j = 0; j < kLevels; ++j) {
      if (j > n) {
        for (int p = 0; p < 4; ++p) value[j][p] = hn::Zero(d);
        continue;
      }
      level(d, j, r, low, value[j]);
      for (int p = 0; p < 4; ++p) value[j][p] = hn::Mul(value[j][p], powers[j]);
    }
  }

  // x = num / den and x' = (num' - den' x) / den from the levels, polynomials num and den.
  template <class V>
  static HWY_INLINE void quotient(const V value[][4], int num, int den, V& q, V& dq) {
    q = hn::Div(value[0][num], value[0][den]);
    dq = hn::Div(hn::Sub(value[1][num], hn::Mul(value[1][den], q)), value[0][den]);
  }

  // P and P' (the engine's curve_slope_horner).
  template <class D, class V = hn::Vec<D>>
  HWY_INLINE void slope(D d, const V& t, V& x, V& dx, V& y, V& dy) const {
    V value[2][4];
    levels<2>(d, t, value);
    quotient(value, 0, 1, x, dx);
    quotient(value, 2, 3, y, dy);
  }
};

// The first half of one of rational_newton_group's iterations, at t: the jet, E = P(t) - P0 and
// its length h (plain: as the engine's length() computes it), f = E . P' (g1), |P'|^2 (speed2),
// f' = |P'|^2 + E . P'' (slope; g2 = |P'|^2 where that is not positive: Gauss-Newton where the
// distance is concave), and Newton's step -f / g2 capped at max_step. `steps`: where g2 > 0 and f
// is finite (elsewhere the iteration stops, with the distance h).
template <class D>
struct NewtonJet {
  using V = hn::Vec<D>;
  V ex, ey, dx, dy, ddx, ddy, h, g1, speed2, slope, step;
  hn::Mask<D> plain, steps;
  template <class Curve>
  HWY_INLINE NewtonJet(D d, const Curve& curve, const V& u, const V& v, const V& t, const V& max_step) {
    V x, y;
    curve.jet(d, t, x, dx, ddx, y, dy, ddy);
    ex = hn::Sub(x, u);
    ey = hn::Sub(y, v);
    h = plain_length(ex, ey, plain);
    const V zero = hn::Zero(d);
    g1 = hn::Add(hn::Mul(ex, dx), hn::Mul(ey, dy));
    speed2 = hn::Add(hn::Mul(dx, dx), hn::Mul(dy, dy));
    slope = hn::Add(hn::Add(speed2, hn::Mul(ex, ddx)), hn::Mul(ey, ddy));
    const V g2 = hn::IfThenElse(hn::Gt(slope, zero), slope, speed2);
    steps = hn::And(hn::Gt(g2, zero), hn::IsFinite(g1));
    step = hn::Min(hn::Max(hn::Div(hn::Neg(g1), g2), hn::Neg(max_step)), max_step);
  }
};

// A small step of the jet's (|step| <= trusted_step, the lanes `small`), taken as Newton gives it:
// next = t + step clamped to [0, 1]. `last`: the last step (at most final_step, not cut short by
// the clamp, f' >= |P'|^2 / 2, and s^2 |P''| below the rounding: refine.cpp), its distance by the
// first-order update |E + P' s| (`updated`; last_plain: as the engine's length() computes it, else
// the scalar code would take it with hypot). `converged`, of the others: t moved by at most
// 4 eps max(1, |t|), where the distance is the one before the step (refine.cpp says why) unless
// `fast`: those ulps of t move P by more than a few ulps (|P'| moved > 4 eps), measured at the new
// t then.
template <class D>
struct SmallStep {
  using V = hn::Vec<D>;
  V next, updated;
  hn::Mask<D> last, last_plain, converged, fast;
  HWY_INLINE SmallStep(D d, const NewtonJet<D>& jet, const V& t, const hn::Mask<D>& small, const V& final_step) {
    const V zero = hn::Zero(d), one = hn::Set(d, 1.0);
    const V unclamped = hn::Add(t, jet.step);
    next = hn::Min(hn::Max(unclamped, zero), one);
    const V moved = hn::Abs(hn::Sub(next, t));
    const V s = hn::Sub(next, t);
    const hn::Mask<D> flat =
        hn::Le(hn::Mul(hn::Mul(s, s), hn::Add(hn::Abs(jet.ddx), hn::Abs(jet.ddy))),
               hn::Set(d, std::numeric_limits<double>::epsilon()));
    last = hn::And(flat, hn::And(small, hn::And(hn::And(hn::Le(moved, final_step), hn::Eq(next, unclamped)),
                                                 hn::Ge(jet.slope, hn::Mul(hn::Set(d, 0.5), jet.speed2)))));
    updated = plain_length(hn::Add(jet.ex, hn::Mul(jet.dx, s)), hn::Add(jet.ey, hn::Mul(jet.dy, s)), last_plain);
    const V new_t = hn::IfThenElse(small, next, t);
    converged = hn::And(hn::AndNot(last, small),
                        hn::Le(moved, hn::Mul(hn::Set(d, 4 * std::numeric_limits<double>::epsilon()),
                                              hn::Max(one, hn::Abs(new_t)))));
    constexpr double kEps = std::numeric_limits<double>::epsilon();
    fast = hn::Gt(hn::Mul(hn::Mul(moved, moved), jet.speed2), hn::Set(d, 16 * kEps * kEps));
  }
};

// rational_newton_groups' first round, in iterations.
inline constexpr int kNewtonFirstRound = 2;

// The engine's refine_parameter(..., stay_on_segment = true), one lane per point, each lane through
// exactly the scalar code's sequence of steps (the masks only say which lanes are still at which
// point of it):
//   iteration: jet at t; d = |P(t) - P0|; Newton step -f/f' (Gauss-Newton where f' <= 0), capped
//   at max_step; a step of at most trusted_step is taken as it is (the last, with the distance by
//   the first-order update |P - P0 + P' s|, when it moves t by at most final_step, unclamped,
//   where f' >= |P'|^2 / 2 and s^2 (|x''| + |y''|) <= eps; else converged, with the distance
//   measured before it, when it moves t by at most 4 eps max(1, |t|) and P by |P'| moved <= 4 eps,
//   measured at the new t when only the first holds); a larger one is halved until the distance does not increase (at
//   most max_halvings times; if none is found, or it does not move t, the iteration stops).
// With `pending` (the first of rational_newton_groups' two rounds): after kNewtonFirstRound
// iterations, where at most three quarters of the group's lanes are still iterating and one of
// them is still far from its root (else the group goes on to the end, as without), the group
// stops; a lane still iterating then gets its t so far in pending (the others NaN), keeps its t
// as it came, and its distance is the second round's to write. Returns whether there is such a
// lane. Without, `iterations` is what remains of max_iterations and every lane finishes as above.
// kLeaving (not in the second round: its lanes have moved): settings.leave_distance applies to the
// first distance, and the lanes it stops are added to *left_lanes. A template argument, so that
// the callers without it run the loop they would without the test.
template <bool kLeaving, class Curve, class D>
HWY_NOINLINE bool rational_newton_group(D d, const Curve& curve, const NewtonSettings& settings, int iterations,
                                        std::size_t* left_lanes,
                                        std::size_t first, std::size_t lanes, const double* HWY_RESTRICT u_in,
                                        const double* HWY_RESTRICT v_in, double* HWY_RESTRICT t_inout,
                                        double* HWY_RESTRICT distance_out, double* HWY_RESTRICT pending) {
  using V = hn::Vec<D>;
  using M = hn::Mask<D>;
  // Padding lanes start at NaN: inactive from the start, they cost no iterations.
  const V u = hn::LoadGroup(d, u_in, first, lanes, 0.0), v = hn::LoadGroup(d, v_in, first, lanes, 0.0);
  const V t0 = hn::LoadGroup(d, t_inout, first, lanes, std::numeric_limits<double>::quiet_NaN());
  const V zero = hn::Zero(d), one = hn::Set(d, 1.0), half = hn::Set(d, 0.5);
  const V trusted = hn::Set(d, settings.trusted_step), max_step = hn::Set(d, settings.max_step);
  const V final_step = hn::Set(d, settings.final_step);
  const V four_eps = hn::Set(d, 4 * std::numeric_limits<double>::epsilon());
  auto converged = [&](V moved, V t) { return hn::Le(moved, hn::Mul(four_eps, hn::Max(one, hn::Abs(t)))); };

  M active = hn::And(hn::Ge(t0, zero), hn::Le(t0, one));  // false for NaN; in [0,1] clamp(t0) = t0
  M unsettled = hn::Not(active);                          // given back to the scalar code
  M final_distance = hn::FirstN(d, 0);                    // finished, distance to be measured at t
  V t = hn::IfThenElse(active, t0, zero);
  V dist = zero;     // |P(t) - P0| at the current t while current
  M current = hn::FirstN(d, 0);
  V result = zero;   // the distance a finished lane reports
  auto finish = [&](M lanes_done, V value) {
    result = hn::IfThenElse(lanes_done, value, result);
    active = hn::AndNot(lanes_done, active);
  };
  auto give_back = [&](M lanes) {
    unsettled = hn::Or(unsettled, lanes);
    active = hn::AndNot(lanes, active);
  };

  M stopped = hn::FirstN(d, 0);  // the lanes a first round leaves pending
  V last_step = zero;            // the Newton step of the iteration before
  for (int iteration = 0; iteration < iterations && !hn::AllFalse(d, active); ++iteration) {
    if (pending && iteration == kNewtonFirstRound) {
      // Stopped where that saves iterations: a quarter of the lanes settled, and one still far
      // from its root (its last Newton step above 1e-4: several iterations to go). Otherwise on
      // to the end, as in one round.
      const M far = hn::And(active, hn::Gt(hn::Abs(last_step), hn::Set(d, 1e-4)));
      if (!hn::AllFalse(d, far) && 4 * hn::CountTrue(d, active) <= 3 * lanes) {
        stopped = active;
        active = hn::FirstN(d, 0);
        break;
      }
    }
    const NewtonJet<D> jet(d, curve, u, v, t, max_step);
    give_back(hn::And(active, hn::Not(hn::And(jet.plain, hn::IsFinite(jet.h)))));  // the scalar code stops on inf/NaN
    if (kLeaving && iteration == 0) {  // off the curve from the start, by the caller's measure: left to it
      const M left = hn::And(active, hn::Gt(jet.h, hn::Set(d, settings.leave_distance)));
      result = hn::IfThenElse(left, hn::Set(d, std::numeric_limits<double>::infinity()), result);
      active = hn::AndNot(left, active);
      *left_lanes += hn::CountTrue(d, left);
    }
    dist = hn::IfThenElse(active, jet.h, dist);
    current = hn::Or(current, active);
    finish(hn::AndNot(jet.steps, active), dist);
    V step = jet.step;
    last_step = step;

    // Small steps: taken as Newton gives them.
    const M small = hn::And(active, hn::Le(hn::Abs(step), trusted));
    {
      const SmallStep<D> taken(d, jet, t, small, final_step);
      t = hn::IfThenElse(small, taken.next, t);
      give_back(hn::AndNot(taken.last_plain, taken.last));
      finish(hn::And(taken.last, taken.last_plain), taken.updated);
      const M done = taken.converged;
      const M fast = taken.fast;
      finish(hn::AndNot(fast, done), dist);
      final_distance = hn::Or(final_distance, hn::And(done, fast));
      active = hn::AndNot(hn::And(done, fast), active);
      current = hn::AndNot(small, current);
    }

    // Larger steps: halved until the distance does not increase.
    M search = hn::AndNot(small, active);
    M accepted = hn::FirstN(d, 0);
    const M searched = search;
    for (int halving = 0; halving < settings.max_halvings && !hn::AllFalse(d, search); ++halving) {
      const V next = hn::Min(hn::Max(hn::Add(t, step), zero), one);
      M next_plain;
      const V dn = curve.distance(d, u, v, next, next_plain);
      const M bad = hn::And(search, hn::Not(next_plain));
      give_back(bad);
      search = hn::AndNot(bad, search);
      const M ok = hn::And(search, hn::Le(dn, dist));
      accepted = hn::Or(accepted, hn::And(ok, hn::Ne(next, t)));
      const V moved = hn::Abs(hn::Sub(next, t));
      t = hn::IfThenElse(ok, next, t);
      dist = hn::IfThenElse(ok, dn, dist);
      finish(hn::And(ok, converged(moved, t)), dist);
      search = hn::AndNot(ok, search);
      step = hn::IfThenElse(search, hn::Mul(step, half), step);
    }
    finish(hn::And(hn::And(searched, active), hn::Not(accepted)), dist);  // no descent found: stop here
  }
  // A lane still iterating at the end of the first round: its t so far, for the second. (An
  // active lane carries nothing else from one iteration to the next: the jet at t renews `dist`
  // and `current`.)
  if (pending)
    hn::StoreGroup(hn::IfThenElse(stopped, t, hn::Set(d, std::numeric_limits<double>::quiet_NaN())), d, pending, first,
                   lanes);
  // Out of iterations: the distance at hand, or measured at the last t.
  finish(hn::And(active, current), dist);
  final_distance = hn::Or(final_distance, active);

  if (!hn::AllFalse(d, final_distance)) {
    M plain;
    const V h = curve.distance(d, u, v, t, plain);
    unsettled = hn::Or(unsettled, hn::And(final_distance, hn::Not(plain)));
    result = hn::IfThenElse(final_distance, h, result);
  }

  result = hn::IfThenElse(unsettled, hn::Set(d, std::numeric_limits<double>::quiet_NaN()), result);
  // A lane left to the scalar code keeps its t (a lane left to the caller has not moved).
  hn::StoreGroup(result, d, distance_out, first, lanes);
  hn::StoreGroup(hn::IfThenElse(hn::Or(stopped, hn::IsNaN(result)), t0, t), d, t_inout, first, lanes);
  return !hn::AllFalse(d, stopped);
}

// Lanes per group: kNewtonWideVectors SIMD vectors side by side (their dependency chains overlap),
// the last group too, with padding lanes that start inactive; each lane computes the same numbers
// whatever the group. Two, not four: a group iterates as long as its slowest lane, so wider groups
// idle more (docs/kernels.md, "Wide groups"). SIMD targets and n <= 24 only, as null_vector's.
template <int N>
inline constexpr int kNewtonWideVectors = (HWY_TARGET == HWY_SCALAR || HWY_TARGET == HWY_EMU128 || N > 24) ? 1 : 2;

// In two rounds, kBatch lanes at a time: every group for kNewtonFirstRound iterations, then the
// lanes still iterating, compacted into groups of their own, for the rest. A lane on the curve
// settles in one or two iterations and one off it may take ten: in one round, a group with both
// iterates as long as its slowest lane (a batch of points half on the curve, half off, everywhere).
// Each lane computes exactly what it would in one round (rational_newton_group says why), so the
// bits are the same.
template <bool kLeaving, class Curve, int kWideVectors>
std::size_t rational_newton_groups(const Curve& curve, const NewtonSettings& settings, std::size_t count,
                                   const double* u, const double* v, double* t, double* distance) {
  using Wide = wide::Tag<kWideVectors>;
  constexpr std::size_t LW = wide::MaxLanes(Wide());
  std::size_t left = 0;
  if (LW == 1 || settings.max_iterations <= kNewtonFirstRound) {  // one lane a group: nothing waits
    for (std::size_t first = 0; first < count; first += LW)
      rational_newton_group<kLeaving>(Wide(), curve, settings, settings.max_iterations, &left, first,
                                      std::min(LW, count - first), u, v, t, distance, nullptr);
    return left;
  }
  constexpr std::size_t kBatch = 64;
  HWY_ALIGN double pending[kBatch], pu[kBatch], pv[kBatch], pt[kBatch], pd[kBatch];
  std::size_t lane_of[kBatch];
  for (std::size_t start = 0; start < count; start += kBatch) {
    const std::size_t lanes = std::min(kBatch, count - start);
    bool any = false;
    for (std::size_t first = 0; first < lanes; first += LW)
      any |= rational_newton_group<kLeaving>(Wide(), curve, settings, settings.max_iterations, &left, first,
                                             std::min(LW, lanes - first), u + start, v + start, t + start,
                                             distance + start, pending);
    if (!any) continue;
    std::size_t m = 0;
    for (std::size_t l = 0; l < lanes; ++l)
      if (!std::isnan(pending[l])) lane_of[m] = l, pu[m] = u[start + l], pv[m] = v[start + l], pt[m] = pending[l], ++m;
    for (std::size_t first = 0; first < m; first += LW)
      rational_newton_group<false>(Wide(), curve, settings, settings.max_iterations - kNewtonFirstRound, &left, first,
                                   std::min(LW, m - first), pu, pv, pt, pd, nullptr);
    // A lane given back to the scalar code keeps the t it came with (still in t), not the first
    // round's.
    for (std::size_t k = 0; k < m; ++k) {
      const std::size_t l = start + lane_of[k];
      distance[l] = pd[k];
      if (!std::isnan(pd[k])) t[l] = pt[k];
    }
  }
  return left;
}

// (inline, as rational_slope_batch: formula_newton.cpp includes this file too.)
inline std::size_t rational_newton_batch(const RationalCurve& curve, const NewtonSettings& settings, std::size_t count,
                                  const double* u, const double* v, double* t, double* distance) {
  for (std::size_t l = 0; l < count; ++l) distance[l] = std::numeric_limits<double>::quiet_NaN();
  const bool leaving = settings.leave_distance < std::numeric_limits<double>::infinity();
  std::size_t left = 0;
  dispatch_size<kRationalNewtonMinDegree, kRationalNewtonMaxDegree>("rational_newton", curve.degree, [&](auto size) {
    constexpr int N = decltype(size)::value;
    const CasteljauCurve<N> casteljau{curve};
    left = leaving ? rational_newton_groups<true, CasteljauCurve<N>, kNewtonWideVectors<N>>(casteljau, settings, count,
                                                                                           u, v, t, distance)
                   : rational_newton_groups<false, CasteljauCurve<N>, kNewtonWideVectors<N>>(casteljau, settings, count,
                                                                                            u, v, t, distance);
  });
  return left;
}

// P and P' by Horner's rule (HornerCurve::slope), lane by lane as the engine's curve_slope_horner.
inline void rational_slope_batch(const RationalCurve& curve, std::size_t count, const double* t, double* x, double* y,
                          double* dx, double* dy) {
  check_size<kRationalNewtonMinDegree, kRationalNewtonMaxDegree>("rational_slope", curve.degree);
  using D = wide::Tag<kNewtonWideVectors<2>>;
  using V = hn::Vec<D>;
  const D d;
  constexpr std::size_t L = hn::MaxLanes(D());
  const HornerCurve horner{curve};
  for (std::size_t first = 0; first < count; first += L) {
    const std::size_t lanes = std::min(L, count - first);
    V px, pdx, py, pdy;
    horner.slope(d, hn::LoadGroup(d, t, first, lanes, 0.0), px, pdx, py, pdy);
    hn::StoreGroup(px, d, x, first, lanes);
    hn::StoreGroup(py, d, y, first, lanes);
    hn::StoreGroup(pdx, d, dx, first, lanes);
    hn::StoreGroup(pdy, d, dy, first, lanes);
  }
}

}  // namespace bezinv::kernels::HWY_NAMESPACE
HWY_AFTER_NAMESPACE();

#endif  // BEZINV_KERNELS_BATCH_RATIONAL_NEWTON_INL_H_
