// Lane-batched evaluation of an inversion formula t = N(u, v) / M(u, v) (Wang & Joe), one point
// per lane (bezinv/kernels/batch.hpp, Implementation::formula_parameter). Re-included once per
// instruction set by hwy/foreach_target.h (see formula_parameter.cpp).
//
// Each lane makes the operations of the engine's formula_parameter
// (engine/src/pipeline/formula_path.cpp) in the same order, without fused multiply-add (the file
// is compiled with -ffp-contract=off): the same bits on every instruction set.
#if defined(BEZINV_KERNELS_BATCH_FORMULA_PARAMETER_INL_H_) == defined(HWY_TARGET_TOGGLE)
#ifdef BEZINV_KERNELS_BATCH_FORMULA_PARAMETER_INL_H_
#undef BEZINV_KERNELS_BATCH_FORMULA_PARAMETER_INL_H_
#else
#define BEZINV_KERNELS_BATCH_FORMULA_PARAMETER_INL_H_
#endif

#include <hwy/highway.h>

#include <algorithm>
#include <cstddef>
#include <limits>

#include "batch/sizes-inl.hpp"
#include "bezinv/kernels/batch.hpp"

HWY_BEFORE_NAMESPACE();
namespace bezinv::kernels::HWY_NAMESPACE {
// (Highway's operations are named in each function, hn below, not for the whole namespace: the
// fused formula_newton kernel includes this file beside the Newton kernel's, whose hn is its wide
// vectors.)

// N / M for G vectors of lanes at once, (u, v) read from u[g * L ..], v[g * L ..].
//
// With a = (u - centre_u) / half_u and b alike, the Chebyshev values T_k(a) and T_k(b), k <= d,
// by T_{k+1} = 2 a T_k - T_{k-1}; then N = sum_{i + j <= d} n_ij T_i(a) T_j(b) and M alike, term by
// term in PlanePolynomial::index order, with S = sum |m_ij T_i(a) T_j(b)|, the size M's terms
// cancel from. t is N / M where |u|, |v| <= max_coordinate and |M| >= min_denominator S, else NaN.
//
// The terms are summed one after the other into one sum per lane, as the scalar code does: that
// order is what gives its bits. The G vectors' sums are independent chains, so the additions'
// latency overlaps (one chain alone would wait on each addition: ~190 of them at d = 18).
template <int G, class D>
HWY_INLINE void formula_parameter_groups(D d, const PlaneFormula& f, const double* HWY_RESTRICT u,
                                         const double* HWY_RESTRICT v, double* HWY_RESTRICT t) {
  namespace hn = hwy::HWY_NAMESPACE;
  using V = hn::Vec<D>;
  const std::size_t L = hn::Lanes(d);
  const int degree = f.degree;
  V ta[kFormulaParameterMaxDegree + 1][G], tb[kFormulaParameterMaxDegree + 1][G];
  V numerator[G], denominator[G], size[G];
  hn::Mask<D> near[G];
  const V one = hn::Set(d, 1.0), limit = hn::Set(d, f.max_coordinate);
  for (int g = 0; g < G; ++g) {
    const V x = hn::LoadU(d, u + g * L), y = hn::LoadU(d, v + g * L);
    near[g] = hn::And(hn::Le(hn::Abs(x), limit), hn::Le(hn::Abs(y), limit));
    const V a = hn::Mul(hn::Sub(x, hn::Set(d, f.centre_u)), hn::Set(d, f.inverse_half_u));
    const V b = hn::Mul(hn::Sub(y, hn::Set(d, f.centre_v)), hn::Set(d, f.inverse_half_v));
    ta[0][g] = tb[0][g] = one;
    ta[1][g] = a;
    tb[1][g] = b;
    const V twice_a = hn::Add(a, a), twice_b = hn::Add(b, b);  // 2 a, exactly
    for (int k = 1; k < degree; ++k) {
      ta[k + 1][g] = hn::Sub(hn::Mul(twice_a, ta[k][g]), ta[k - 1][g]);
      tb[k + 1][g] = hn::Sub(hn::Mul(twice_b, tb[k][g]), tb[k - 1][g]);
    }
    numerator[g] = denominator[g] = size[g] = hn::Zero(d);
  }
  const double* n = f.n;
  const double* m = f.m;
  for (int k = 0; k <= degree; ++k)
    for (int j = 0; j <= k; ++j, ++n, ++m) {
      const V nk = hn::Set(d, *n), mk = hn::Set(d, *m);
      for (int g = 0; g < G; ++g) {
        const V term = hn::Mul(ta[k - j][g], tb[j][g]);
        numerator[g] = hn::Add(numerator[g], hn::Mul(nk, term));
        const V weighted = hn::Mul(mk, term);
        denominator[g] = hn::Add(denominator[g], weighted);
        size[g] = hn::Add(size[g], hn::Abs(weighted));
      }
    }
  const V nan = hn::Set(d, std::numeric_limits<double>::quiet_NaN()), min_denominator = hn::Set(d, f.min_denominator);
  for (int g = 0; g < G; ++g) {
    const auto defined = hn::And(near[g], hn::Ge(hn::Abs(denominator[g]), hn::Mul(min_denominator, size[g])));
    hn::StoreU(hn::IfThenElse(defined, hn::Div(numerator[g], denominator[g]), nan), d, t + g * L);
  }
}

// inline: formula_newton.cpp includes this file too.
inline void formula_parameter_batch(const PlaneFormula& formula, std::size_t count, const double* u,
                                    const double* v, double* t) {
  namespace hn = hwy::HWY_NAMESPACE;
  if (formula.degree < kFormulaParameterMinDegree || formula.degree > kFormulaParameterMaxDegree)
    batch::size_out_of_range("formula_parameter", formula.degree, kFormulaParameterMinDegree,
                             kFormulaParameterMaxDegree);
  const hn::ScalableTag<double> d;
  constexpr std::size_t L = hn::MaxLanes(hn::ScalableTag<double>());
  constexpr int G = 4;
  std::size_t first = 0;
  for (; first + G * L <= count; first += G * L) formula_parameter_groups<G>(d, formula, u + first, v + first, t + first);
  for (; first + L <= count; first += L) formula_parameter_groups<1>(d, formula, u + first, v + first, t + first);
  if (first == count) return;
  // The last lanes, padded with the point (0, 0) (any finite lane would do; it is not stored).
  HWY_ALIGN double lanes[2][L] = {};
  const std::size_t left = count - first;
  std::copy_n(u + first, left, lanes[0]);
  std::copy_n(v + first, left, lanes[1]);
  HWY_ALIGN double result[L];
  formula_parameter_groups<1>(d, formula, lanes[0], lanes[1], result);
  std::copy_n(result, left, t + first);
}

}  // namespace bezinv::kernels::HWY_NAMESPACE
HWY_AFTER_NAMESPACE();

#endif  // BEZINV_KERNELS_BATCH_FORMULA_PARAMETER_INL_H_
