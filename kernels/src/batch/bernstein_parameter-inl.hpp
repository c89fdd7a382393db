// Lane-batched read-out of the parameter from a null vector (Marco & Martinez Sect. 3), one vector
// per lane (bezinv/kernels/batch.hpp, Implementation::bernstein_parameter). Re-included once per
// instruction set by hwy/foreach_target.h (see bernstein_parameter.cpp).
//
// Each lane makes the comparisons and the arithmetic of the engine's parameter_from_null_vector
// (engine/src/null_vector.cpp) in the same order, without fused multiply-add (the file is compiled
// with -ffp-contract=off): the same bits on every instruction set.
#if defined(BEZINV_KERNELS_BATCH_BERNSTEIN_PARAMETER_INL_H_) == defined(HWY_TARGET_TOGGLE)
#ifdef BEZINV_KERNELS_BATCH_BERNSTEIN_PARAMETER_INL_H_
#undef BEZINV_KERNELS_BATCH_BERNSTEIN_PARAMETER_INL_H_
#else
#define BEZINV_KERNELS_BATCH_BERNSTEIN_PARAMETER_INL_H_
#endif

#include <hwy/highway.h>

#include <algorithm>
#include <cstddef>
#include <limits>

#include "batch/sizes-inl.hpp"

HWY_BEFORE_NAMESPACE();
namespace bezinv::kernels::HWY_NAMESPACE {
namespace hn = hwy::HWY_NAMESPACE;

// z = alpha (beta_0(t), ..., beta_{N-1}(t)) (degree N-1) gives z_i / z_{i-1} = (N-i) t / (i (1-t)), so
//     t = i z_i / (i z_i + (N-i) z_{i-1})
// from the pair (z_{i-1}, z_i) made of the largest component (the first, if several) and the larger
// of its neighbours (the left one on a tie): the largest components are the least sensitive to
// perturbations of z (Demmel et al. 2008).
template <int N, class D>
HWY_INLINE hn::Vec<D> bernstein_parameter_group(D d, std::size_t stride, const double* HWY_RESTRICT z) {
  using V = hn::Vec<D>;
  auto component = [&](int i) { return hn::LoadU(d, z + static_cast<std::size_t>(i) * stride); };
  auto index = [&](int i) { return hn::Set(d, static_cast<double>(i)); };
  // The largest component k.
  V best = hn::Abs(component(0)), k = hn::Zero(d);
  for (int i = 1; i < N; ++i) {
    const V size = hn::Abs(component(i));
    const auto larger = hn::Gt(size, best);
    best = hn::IfThenElse(larger, size, best);
    k = hn::IfThenElse(larger, index(i), k);
  }
  // Its neighbours' sizes, |z_{k-1}| and |z_{k+1}| (read only where they exist).
  V left = hn::Zero(d), right = hn::Zero(d);
  for (int i = 0; i < N; ++i) {
    const V size = hn::Abs(component(i));
    left = hn::IfThenElse(hn::Eq(k, index(i + 1)), size, left);
    right = hn::IfThenElse(hn::Eq(k, index(i - 1)), size, right);
  }
  // The pair's index i: 1 at the first component, N-1 at the last, else k or k+1.
  V pair = hn::IfThenElse(hn::Ge(left, right), k, hn::Add(k, index(1)));
  pair = hn::IfThenElse(hn::Eq(k, hn::Zero(d)), index(1), pair);
  pair = hn::IfThenElse(hn::Eq(k, index(N - 1)), index(N - 1), pair);
  V zi = hn::Zero(d), zi_1 = hn::Zero(d);
  for (int i = 1; i < N; ++i) {
    const auto here = hn::Eq(pair, index(i));
    zi = hn::IfThenElse(here, component(i), zi);
    zi_1 = hn::IfThenElse(here, component(i - 1), zi_1);
  }
  const V a = hn::Mul(pair, zi);
  const V denominator = hn::Add(a, hn::Mul(hn::Sub(index(N), pair), zi_1));
  return hn::IfThenElse(hn::Eq(denominator, hn::Zero(d)), hn::Set(d, std::numeric_limits<double>::quiet_NaN()),
                        hn::Div(a, denominator));
}

template <int N>
void bernstein_parameter_fixed(std::size_t count, std::size_t stride, const double* z, double* t) {
  const hn::ScalableTag<double> d;
  constexpr std::size_t L = hn::MaxLanes(hn::ScalableTag<double>());
  HWY_ALIGN double lanes[L];
  // Whole vectors only: rows are `stride` long, a multiple of kBatchAlignment >= L.
  for (std::size_t first = 0; first < count; first += L) {
    hn::Store(bernstein_parameter_group<N>(d, stride, z + first), d, lanes);
    std::copy_n(lanes, std::min(L, count - first), t + first);
  }
}

void bernstein_parameter_batch(int n, std::size_t count, std::size_t stride, const double* z, double* t) {
  dispatch_size<kBernsteinParameterMinSize, kBernsteinParameterMaxSize>("bernstein_parameter", n, [&](auto size) {
    bernstein_parameter_fixed<decltype(size)::value>(count, stride, z, t);
  });
}

}  // namespace bezinv::kernels::HWY_NAMESPACE
HWY_AFTER_NAMESPACE();

#endif  // BEZINV_KERNELS_BATCH_BERNSTEIN_PARAMETER_INL_H_
