// Vectors of N components in the lane-major layout of a group (component i of every lane at
// x + i * MaxLanes(d)): the dot products, norms and copies of the inverse iterations.
// Re-included once per instruction set by hwy/foreach_target.h (see null_vector.cpp).
#if defined(BEZINV_KERNELS_BATCH_LANE_VECTORS_INL_H_) == defined(HWY_TARGET_TOGGLE)
#ifdef BEZINV_KERNELS_BATCH_LANE_VECTORS_INL_H_
#undef BEZINV_KERNELS_BATCH_LANE_VECTORS_INL_H_
#else
#define BEZINV_KERNELS_BATCH_LANE_VECTORS_INL_H_
#endif

#include <hwy/highway.h>

#include <cstddef>

#include "batch/wide-inl.hpp"

HWY_BEFORE_NAMESPACE();
namespace bezinv::kernels::HWY_NAMESPACE {
namespace hn = wide;

// x . y
template <int N, class D>
HWY_INLINE hn::Vec<D> dot(D d, const double* HWY_RESTRICT x, const double* HWY_RESTRICT y) {
  constexpr std::size_t L = hn::MaxLanes(D());
  auto sum = hn::Zero(d);
  for (int i = 0; i < N; ++i) sum = hn::MulAdd(hn::Load(d, x + i * L), hn::Load(d, y + i * L), sum);
  return sum;
}

// to <- from, vector by vector (std::copy becomes `rep movsq`, slow to start for a few hundred bytes).
template <int N, class D>
HWY_INLINE void copy(D d, const double* HWY_RESTRICT from, double* HWY_RESTRICT to) {
  constexpr std::size_t L = hn::MaxLanes(D());
  for (int i = 0; i < N; ++i) hn::Store(hn::Load(d, from + i * L), d, to + i * L);
}

// x <- x / ||x||_2, returning ||x||_2.
template <int N, class D>
HWY_INLINE hn::Vec<D> normalize(D d, double* HWY_RESTRICT x) {
  constexpr std::size_t L = hn::MaxLanes(D());
  const auto norm = hn::Sqrt(dot<N>(d, x, x));
  const auto inv = hn::Div(hn::Set(d, 1.0), norm);
  for (int i = 0; i < N; ++i) hn::Store(hn::Mul(hn::Load(d, x + i * L), inv), d, x + i * L);
  return norm;
}

// Sign-insensitive chordal distance min ||x -+ y|| = 2 sin(angle / 2) between unit vectors. Unlike
// sqrt(1 - (x.y)^2) it keeps its relative accuracy for tiny angles (1e-10 is not lost in 1 - c^2).
template <int N, class D>
HWY_INLINE hn::Vec<D> chord(D d, const double* HWY_RESTRICT x, const double* HWY_RESTRICT y) {
  constexpr std::size_t L = hn::MaxLanes(D());
  auto minus = hn::Zero(d), plus = hn::Zero(d);
  for (int i = 0; i < N; ++i) {
    const auto a = hn::Load(d, x + i * L), b = hn::Load(d, y + i * L);
    const auto dm = hn::Sub(a, b), dp = hn::Add(a, b);
    minus = hn::MulAdd(dm, dm, minus);
    plus = hn::MulAdd(dp, dp, plus);
  }
  return hn::Sqrt(hn::Min(minus, plus));
}

}  // namespace bezinv::kernels::HWY_NAMESPACE
HWY_AFTER_NAMESPACE();

#endif  // BEZINV_KERNELS_BATCH_LANE_VECTORS_INL_H_
