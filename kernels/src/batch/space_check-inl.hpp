// Lane-batched check in space of a space curve's answers, one point per lane
// (bezinv/kernels/batch.hpp, Implementation::space_check). Re-included once per instruction set by
// hwy/foreach_target.h (see space_check.cpp).
//
// Every lane runs the operations of the engine's scalar check (engine/src/space/space_curve.cpp:
// horner_point, first_order_jet, space_distance and space_refine's first test) in the same order,
// without fused multiply-add (the file is compiled with -ffp-contract=off): a lane settled here
// has the bits the scalar code would have computed, on every instruction set.
#if defined(BEZINV_KERNELS_BATCH_SPACE_CHECK_INL_H_) == defined(HWY_TARGET_TOGGLE)
#ifdef BEZINV_KERNELS_BATCH_SPACE_CHECK_INL_H_
#undef BEZINV_KERNELS_BATCH_SPACE_CHECK_INL_H_
#else
#define BEZINV_KERNELS_BATCH_SPACE_CHECK_INL_H_
#endif

#include <hwy/highway.h>

#include <algorithm>
#include <cstddef>
#include <limits>

#include "batch/sizes-inl.hpp"
#include "bezinv/kernels/batch.hpp"

HWY_BEFORE_NAMESPACE();
namespace bezinv::kernels::HWY_NAMESPACE {
namespace hn = hwy::HWY_NAMESPACE;

// |P(t) - P0| where t is the nearest parameter to rounding, else NaN, for one vector of lanes.
//
// P and P' by Horner's rule in s, the W polynomials (x, y, z, the denominators and their
// derivatives; W = 8 with one denominator, 16 with three) side by side: for t <= 1/2,
// s = t / (1 - t) and p(t) = (1 - t)^m sum_i c_i C(m, i) s^i, from the top coefficient down; past
// 1/2, s = (1 - t) / t and p(t) = t^m sum_i c_i C(m, i) s^(m - i), from coefficient 0 up (|s| <= 1
// either way, so Horner's rule is stable). A lane takes the forward or the backward coefficient at
// each step by a blend: one loop for lanes of both halves. Then each coordinate N / D and its
// derivative (N' - D' x) / D with one division per denominator, and the test of space_refine: the
// Newton step g / |P'|^2 of (P - P0) . P' is below rounding of t (2 eps, t in [0, 1]) and of the
// point over the speed (2 eps / |P'|).
template <int W, class D>
HWY_INLINE hn::Vec<D> space_check_group(D d, const SpaceCurve& curve, hn::Vec<D> t, hn::Vec<D> x, hn::Vec<D> y,
                                        hn::Vec<D> z) {
  using V = hn::Vec<D>;
  constexpr double eps = std::numeric_limits<double>::epsilon();
  constexpr int slopes = W / 2;  // where the derivatives start
  const int n = curve.degree;
  const V one = hn::Set(d, 1.0);
  const auto forward = hn::Le(t, hn::Set(d, 0.5));
  const V u = hn::IfThenElse(forward, hn::Sub(one, t), t);
  const V s = hn::Div(hn::IfThenElse(forward, t, hn::Sub(one, t)), u);
  // u^n and u^(n-1), the factors of the values and of the derivatives (degree n - 1).
  V power = one;
  for (int i = 0; i < n - 2; ++i) power = hn::Mul(power, u);
  V power_0 = one, power_1 = one;
  if (n >= 2) {
    power_1 = hn::Mul(power, u);
    power_0 = hn::Mul(power_1, u);
  } else if (n == 1) {
    power_0 = u;
  }
  const double* F = curve.forward;
  const double* B = curve.backward;
  V v[W];
  for (int j = 0; j < W; ++j) v[j] = hn::IfThenElse(forward, hn::Set(d, F[W * n + j]), hn::Set(d, B[j]));
  for (int k = 1; k <= n; ++k) {
    const double* f = F + W * (n - k);
    const double* b = B + W * k;
    for (int j = 0; j < W; ++j) v[j] = hn::Add(hn::Mul(v[j], s), hn::IfThenElse(forward, hn::Set(d, f[j]), hn::Set(d, b[j])));
  }
  const V point[3] = {x, y, z};
  V e[3], dp[3];
  for (int k = 0; k < 3; ++k) {
    const int j = W == 8 ? 3 : 3 + k;  // the coordinate's denominator
    const V den = hn::Mul(v[j], power_0), den_1 = hn::Mul(v[slopes + j], power_1);
    const V inverse = hn::Div(one, den);
    const V p = hn::Mul(hn::Mul(v[k], power_0), inverse);
    dp[k] = hn::Mul(hn::Sub(hn::Mul(v[slopes + k], power_1), hn::Mul(den_1, p)), inverse);
    e[k] = hn::Sub(p, point[k]);
  }
  const V distance = hn::Sqrt(hn::Add(hn::Add(hn::Mul(e[0], e[0]), hn::Mul(e[1], e[1])), hn::Mul(e[2], e[2])));
  const V g = hn::Add(hn::Add(hn::Mul(e[0], dp[0]), hn::Mul(e[1], dp[1])), hn::Mul(e[2], dp[2]));
  const V speed2 = hn::Add(hn::Add(hn::Mul(dp[0], dp[0]), hn::Mul(dp[1], dp[1])), hn::Mul(dp[2], dp[2]));
  const V two_eps = hn::Set(d, 2 * eps);
  const V bound = hn::Add(two_eps, hn::Div(two_eps, hn::Sqrt(speed2)));
  const auto in_segment = hn::And(hn::Ge(t, hn::Zero(d)), hn::Le(t, one));
  const auto settled = hn::And(hn::And(in_segment, hn::IsFinite(distance)),
                               hn::And(hn::Gt(speed2, hn::Zero(d)), hn::Le(hn::Abs(hn::Div(g, speed2)), bound)));
  return hn::IfThenElse(settled, distance, hn::Set(d, std::numeric_limits<double>::quiet_NaN()));
}

template <int W>
void space_check_lanes(const SpaceCurve& curve, std::size_t count, const double* t, const double* x, const double* y,
                       const double* z, double* distance) {
  const hn::ScalableTag<double> d;
  constexpr std::size_t L = hn::MaxLanes(hn::ScalableTag<double>());
  std::size_t first = 0;
  for (; first + L <= count; first += L)
    hn::StoreU(space_check_group<W>(d, curve, hn::LoadU(d, t + first), hn::LoadU(d, x + first),
                                    hn::LoadU(d, y + first), hn::LoadU(d, z + first)),
               d, distance + first);
  if (first == count) return;
  // The last lanes, padded with t = 0 at the origin (any finite lane would do; it is not stored).
  HWY_ALIGN double lanes[4][L] = {};
  const std::size_t left = count - first;
  std::copy_n(t + first, left, lanes[0]);
  std::copy_n(x + first, left, lanes[1]);
  std::copy_n(y + first, left, lanes[2]);
  std::copy_n(z + first, left, lanes[3]);
  HWY_ALIGN double result[L];
  hn::Store(space_check_group<W>(d, curve, hn::Load(d, lanes[0]), hn::Load(d, lanes[1]), hn::Load(d, lanes[2]),
                                 hn::Load(d, lanes[3])),
            d, result);
  std::copy_n(result, left, distance + first);
}

void space_check_batch(const SpaceCurve& curve, std::size_t count, const double* t, const double* x, const double* y,
                       const double* z, double* distance) {
  if (curve.degree < kSpaceCheckMinDegree || curve.degree > kSpaceCheckMaxDegree)
    batch::size_out_of_range("space_check", curve.degree, kSpaceCheckMinDegree, kSpaceCheckMaxDegree);
  if (curve.denominators == 1)
    space_check_lanes<8>(curve, count, t, x, y, z, distance);
  else
    space_check_lanes<16>(curve, count, t, x, y, z, distance);
}

}  // namespace bezinv::kernels::HWY_NAMESPACE
HWY_AFTER_NAMESPACE();

#endif  // BEZINV_KERNELS_BATCH_SPACE_CHECK_INL_H_
