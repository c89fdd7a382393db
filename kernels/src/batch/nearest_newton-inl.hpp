// Lane-batched Newton's method towards the nearest point of a plane rational curve, for points off
// it (bezinv/kernels/batch.hpp, Implementation::nearest_newton). Re-included once per instruction
// set by hwy/foreach_target.h (see nearest_newton.cpp).
//
// rational_newton repeats the engine's scalar refinement step for step, so that an on-curve
// answer does not depend on the path that computed it. The off-curve path needs no such twin: the
// certified search proves whatever t it is given. So this kernel does the same Newton iteration at
// a fraction of the cost:
//   - the jets by Horner's rule with fused multiply-adds, without the factors base^m (they cancel
//     in the quotients but for one power of base per derivative), one division per denominator;
//   - the descent test (of steps above settings.trusted_step) folded into the next jet (its value is the distance there): a step that
//     made the distance larger is halved back from the point it left, instead of a separate
//     evaluation of the distance before every large step;
//   - the last step taken once it is at most settings.final_step where f' >= |P'|^2 / 2 and
//     s^2 |P''| is below rounding: Newton converges quadratically there, so what remains after it
//     is about |f'' / 2 f'| s^2 (1e-18 in t for s = 1e-9 and a moderate curvature; P moves by
//     ~s^2 |P''| whatever the curvature), and the distance after it comes from the jet's Taylor
//     polynomial, |E + P' s + P'' s^2 / 2|, instead of one more iteration that only confirms it.
// Every implementation gives the same bits: the portable targets fuse with std::fma (one rounding,
// as the SIMD targets' multiply-add instructions), and the file is compiled with
// -ffp-contract=off so that the compiler fuses nothing else.
#if defined(BEZINV_KERNELS_BATCH_NEAREST_NEWTON_INL_H_) == defined(HWY_TARGET_TOGGLE)
#ifdef BEZINV_KERNELS_BATCH_NEAREST_NEWTON_INL_H_
#undef BEZINV_KERNELS_BATCH_NEAREST_NEWTON_INL_H_
#else
#define BEZINV_KERNELS_BATCH_NEAREST_NEWTON_INL_H_
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
namespace nearest {
namespace hn = wide;

// a * b + c rounded once, on every target.
template <class V>
HWY_INLINE V fused(const V& a, const V& b, const V& c) {
#if HWY_TARGET == HWY_SCALAR || HWY_TARGET == HWY_EMU128
  // Highway's portable targets compute a * b + c with two roundings.
  using D = hn::DFromV<V>;
  const D d;
  constexpr std::size_t L = hn::MaxLanes(D());
  HWY_ALIGN double x[L], y[L], z[L];
  hn::Store(a, d, x), hn::Store(b, d, y), hn::Store(c, d, z);
  for (std::size_t l = 0; l < L; ++l) x[l] = std::fma(x[l], y[l], z[l]);
  return hn::Load(d, x);
#else
  return hn::MulAdd(a, b, c);
#endif
}

// The curve's jet by Horner's rule on curve.horner (RationalCurve's layout):
//     sum a_i (1-t)^(m-i) t^i = base^m sum a_i r^i,   base = 1-t, r = t / (1-t)   (t <= 1/2),
//                             = base^m sum a_i r^(m-i), base = t, r = (1-t) / t   (above),
// r <= 1 either way. The factor base^m is left out: level j (the j-th derivatives, m = n - j) is
// base^(n-j) times the sum, so in x = N / D the values' factors cancel, x' = (N' - D' x) / D
// keeps one 1 / base and x'' = (N'' - 2 D' x' - D'' x) / D two. kShared: x and y have one
// denominator (its levels are evaluated once).
template <bool kShared>
struct FusedHorner {
  const RationalCurve& curve;

  template <class D, class V = hn::Vec<D>>
  HWY_INLINE void jet(D d, const V& t, V& x, V& dx, V& ddx, V& y, V& dy, V& ddy) const {
    constexpr int kPolynomials = kShared ? 3 : 4;  // x_num, x_den, y_num (, y_den)
    const int n = curve.degree, stride = 3 * n;
    const V one = hn::Set(d, 1.0), s = hn::Sub(one, t);
    const hn::Mask<D> low = hn::Le(t, hn::Set(d, 0.5));
    const V base = hn::IfThenElse(low, s, t);
    const V inverse_base = hn::Div(one, base);
    const V r = hn::Mul(hn::IfThenElse(low, t, s), inverse_base);
    V level[3][kPolynomials];
    for (int j = 0; j < 3; ++j) {
      if (j > n) {
        for (int p = 0; p < kPolynomials; ++p) level[j][p] = hn::Zero(d);
        continue;
      }
      const int m = n - j, offset = j == 0 ? 0 : (j == 1 ? n + 1 : 2 * n + 1);
      const double* c[kPolynomials];
      for (int p = 0; p < kPolynomials; ++p) {
        c[p] = curve.horner + p * stride + offset;
        level[j][p] = hn::IfThenElse(low, hn::Set(d, c[p][m]), hn::Set(d, c[p][0]));
      }
      for (int k = 1; k <= m; ++k)
        for (int p = 0; p < kPolynomials; ++p)
          level[j][p] = fused(level[j][p], r, hn::IfThenElse(low, hn::Set(d, c[p][m - k]), hn::Set(d, c[p][k])));
    }
    const V two_base = hn::Add(base, base);
    const auto quotient = [&](int num, int den, const V& inverse, V& q, V& dq, V& ddq) {
      const V w = hn::Mul(inverse, inverse_base);  // 1 / (D base)
      q = hn::Mul(level[0][num], inverse);
      dq = hn::Mul(fused(hn::Neg(level[1][den]), q, level[1][num]), w);
      // (N'' - D'' x - 2 base D' x') / (D base^2)
      const V top = fused(hn::Neg(hn::Mul(two_base, level[1][den])), dq, fused(hn::Neg(level[2][den]), q, level[2][num]));
      ddq = hn::Mul(hn::Mul(top, w), inverse_base);
    };
    const V inverse_x = hn::Div(one, level[0][1]);
    quotient(0, 1, inverse_x, x, dx, ddx);
    if constexpr (kShared) {
      quotient(2, 1, inverse_x, y, dy, ddy);
    } else {
      const V inverse_y = hn::Div(one, level[0][3]);
      quotient(2, 3, inverse_y, y, dy, ddy);
    }
  }
};

// |(a, b)|, fused.
template <class V>
HWY_INLINE V norm(const V& a, const V& b) {
  return hn::Sqrt(fused(a, a, hn::Mul(b, b)));
}

// One group of lanes (Implementation::nearest_newton says what each lane gets).
template <class Curve, class D>
HWY_NOINLINE void group(D d, const Curve& curve, const NearestNewtonSettings& settings, std::size_t first,
                        std::size_t lanes, const double* HWY_RESTRICT u_in, const double* HWY_RESTRICT v_in,
                        double* HWY_RESTRICT t_inout, double* HWY_RESTRICT distance_out) {
  using V = hn::Vec<D>;
  using M = hn::Mask<D>;
  const double nan = std::numeric_limits<double>::quiet_NaN();
  // Padding lanes start at NaN: inactive from the start, they cost no iterations.
  const V u = hn::LoadGroup(d, u_in, first, lanes, 0.0), v = hn::LoadGroup(d, v_in, first, lanes, 0.0);
  const V t0 = hn::LoadGroup(d, t_inout, first, lanes, nan);
  const V zero = hn::Zero(d), one = hn::Set(d, 1.0), half = hn::Set(d, 0.5);
  const V max_step = hn::Set(d, settings.max_step), final_step = hn::Set(d, settings.final_step);
  const V trusted = hn::Set(d, settings.trusted_step);
  const V four_eps = hn::Set(d, 4 * std::numeric_limits<double>::epsilon());
  const V eps = hn::Set(d, std::numeric_limits<double>::epsilon());
  const V sixteen_eps2 = hn::Mul(four_eps, four_eps);
  const V max_halvings = hn::Set(d, settings.max_halvings);

  M active = hn::And(hn::Ge(t0, zero), hn::Le(t0, one));  // false for NaN
  M unsettled = hn::Not(active);                          // given back: NaN distance, t kept
  V t = hn::IfThenElse(active, t0, zero);
  // The last point whose distance did not increase (`kept`), the step taken from it, and how many
  // times that step has been halved.
  V t_kept = t, d_kept = hn::Set(d, std::numeric_limits<double>::infinity()), step = zero, halvings = zero;
  V t_out = t, result = zero;
  auto finish = [&](const M& done, const V& at, const V& value) {
    t_out = hn::IfThenElse(done, at, t_out);
    result = hn::IfThenElse(done, value, result);
    active = hn::AndNot(done, active);
  };

  for (int iteration = 0; iteration < settings.max_iterations && !hn::AllFalse(d, active); ++iteration) {
    V x, dx, ddx, y, dy, ddy;
    curve.jet(d, t, x, dx, ddx, y, dy, ddy);
    const V ex = hn::Sub(x, u), ey = hn::Sub(y, v);
    const V h = norm(ex, ey);
    const M bad = hn::And(active, hn::Not(hn::IsFinite(h)));
    unsettled = hn::Or(unsettled, bad);
    active = hn::AndNot(bad, active);

    // The step that led here made the distance larger: halve it, from the point it left. (Not
    // below trusted_step: off the curve the distance changes by ~s^2 there, at its rounding.)
    const M worse = hn::And(hn::And(active, hn::Gt(hn::Abs(step), trusted)), hn::Gt(h, d_kept));
    if (!hn::AllFalse(d, worse)) {
      step = hn::IfThenElse(worse, hn::Mul(step, half), step);
      halvings = hn::IfThenElse(worse, hn::Add(halvings, one), halvings);
      const V back = hn::Add(t_kept, step);
      const M give_up = hn::And(worse, hn::Or(hn::Gt(halvings, max_halvings), hn::Eq(back, t_kept)));
      finish(give_up, t_kept, d_kept);
      t = hn::IfThenElse(hn::AndNot(give_up, worse), back, t);
    }
    const M here = hn::AndNot(worse, active);
    t_kept = hn::IfThenElse(here, t, t_kept);
    d_kept = hn::IfThenElse(here, h, d_kept);
    halvings = hn::IfThenElse(here, zero, halvings);

    // Newton's step on f(t) = (P - P0) . P', f' = |P'|^2 + (P - P0) . P'' (Gauss-Newton's |P'|^2
    // where the distance is concave), capped and clamped to the segment.
    const V g1 = fused(ex, dx, hn::Mul(ey, dy));
    const V speed2 = fused(dx, dx, hn::Mul(dy, dy));
    const V slope = fused(ex, ddx, fused(ey, ddy, speed2));
    const V g2 = hn::IfThenElse(hn::Gt(slope, zero), slope, speed2);
    finish(hn::And(here, hn::Not(hn::And(hn::Gt(g2, zero), hn::IsFinite(g1)))), t, h);
    const V newton = hn::Min(hn::Max(hn::Div(hn::Neg(g1), g2), hn::Neg(max_step)), max_step);
    const V next = hn::Min(hn::Max(hn::Add(t, newton), zero), one);
    const V s = hn::Sub(next, t);
    const V moved = hn::Abs(s);
    const M moving = hn::And(here, active);

    // The last step: its distance by the jet's Taylor polynomial at t. Not where s^2 |P''| exceeds
    // the rounding (rational_newton's test): what Newton leaves of t, ~|f''/2f'| s^2 with
    // |f''/f'| ~ 3 |P''| / |P'|, then moves P by ~s^2 |P''|, which near a heavy weight (|P''| 1e8
    // times |P'|) is not below t's resolution; the lane takes one more step instead.
    const M flat = hn::Le(hn::Mul(hn::Mul(s, s), hn::Add(hn::Abs(ddx), hn::Abs(ddy))), eps);
    const M last = hn::And(hn::And(moving, flat),
                           hn::And(hn::Le(moved, final_step), hn::Ge(slope, hn::Mul(half, speed2))));
    // Converged without that (at an end of the segment, or where the distance is not convex): at t,
    // but where the step still moves P by more than a few ulps (|P'| s > 4 eps: a fast curve, |P'|
    // 1e3 and more), at the new t with the last step's distance, as rational_newton measures it
    // there: stopped before it, P would be off by up to 4 eps |P'|.
    const M still = hn::AndNot(last, moving);
    const M converged = hn::And(still, hn::Le(moved, hn::Mul(four_eps, hn::Max(one, hn::Abs(t)))));
    const M fast = hn::And(converged, hn::Gt(hn::Mul(hn::Mul(moved, moved), speed2), sixteen_eps2));
    finish(hn::AndNot(fast, converged), t, h);
    const M taylor = hn::Or(last, fast);
    if (!hn::AllFalse(d, taylor)) {
      const V half_s = hn::Mul(half, s);
      const V lx = fused(fused(ddx, half_s, dx), s, ex), ly = fused(fused(ddy, half_s, dy), s, ey);
      finish(taylor, next, norm(lx, ly));
    }
    const M go = hn::And(still, active);
    t = hn::IfThenElse(go, next, t);
    step = hn::IfThenElse(go, s, step);
  }
  // Out of iterations: the last point kept.
  finish(active, t_kept, d_kept);

  result = hn::IfThenElse(unsettled, hn::Set(d, nan), result);
  t_out = hn::IfThenElse(unsettled, t0, t_out);
  hn::StoreGroup(result, d, distance_out, first, lanes);
  hn::StoreGroup(t_out, d, t_inout, first, lanes);
}

// Two vectors side by side on SIMD targets: their dependency chains (Horner's rule is one per
// polynomial) overlap.
inline constexpr int kWideVectors = (HWY_TARGET == HWY_SCALAR || HWY_TARGET == HWY_EMU128) ? 1 : 2;

// A last group that one vector holds runs as one vector (wide::ForEachGroup): a batch of both kinds
// hands this kernel half its lanes, so its last group is a larger share of the work.
template <class Curve>
void groups(const Curve& curve, const NearestNewtonSettings& settings, std::size_t count, const double* u,
            const double* v, double* t, double* distance) {
  wide::ForEachGroup<kWideVectors>(count, [&](auto d, std::size_t first, std::size_t lanes) {
    group(d, curve, settings, first, lanes, u, v, t, distance);
  });
}

}  // namespace nearest

void nearest_newton_batch(const RationalCurve& curve, const NearestNewtonSettings& settings, std::size_t count,
                          const double* u, const double* v, double* t, double* distance) {
  check_size<kRationalNewtonMinDegree, kRationalNewtonMaxDegree>("nearest_newton", curve.degree);
  // One denominator (the layout's x_den and y_den blocks equal): its levels once.
  const int n = curve.degree;
  const bool shared = std::equal(curve.horner + 3 * n, curve.horner + 6 * n, curve.horner + 9 * n);
  if (shared)
    nearest::groups(nearest::FusedHorner<true>{curve}, settings, count, u, v, t, distance);
  else
    nearest::groups(nearest::FusedHorner<false>{curve}, settings, count, u, v, t, distance);
}

}  // namespace bezinv::kernels::HWY_NAMESPACE
HWY_AFTER_NAMESPACE();

#endif  // BEZINV_KERNELS_BATCH_NEAREST_NEWTON_INL_H_
