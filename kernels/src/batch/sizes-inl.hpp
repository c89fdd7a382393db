// n -> kernel<n> for n = 1..kMaxBatchSize, per instruction set (re-included by foreach_target so
// the dispatching function carries the same target attributes as the kernels it calls).
#if defined(BEZINV_KERNELS_BATCH_SIZES_INL_H_) == defined(HWY_TARGET_TOGGLE)
#ifdef BEZINV_KERNELS_BATCH_SIZES_INL_H_
#undef BEZINV_KERNELS_BATCH_SIZES_INL_H_
#else
#define BEZINV_KERNELS_BATCH_SIZES_INL_H_
#endif

#include <hwy/highway.h>

#include <type_traits>
#include <utility>

#include "bezinv/kernels/batch.hpp"

HWY_BEFORE_NAMESPACE();
namespace bezinv::kernels::HWY_NAMESPACE {

template <class F, int... Ns>
HWY_INLINE void dispatch_size(int n, F&& f, std::integer_sequence<int, Ns...>) {
  (void)((n == Ns + 1 ? (f(std::integral_constant<int, Ns + 1>{}), true) : false) || ...);
}

// Calls f(std::integral_constant<int, n>{}); sizes outside 1..kMaxBatchSize do nothing.
template <class F>
HWY_INLINE void dispatch_size(int n, F&& f) {
  dispatch_size(n, f, std::make_integer_sequence<int, kMaxBatchSize>{});
}

}  // namespace bezinv::kernels::HWY_NAMESPACE
HWY_AFTER_NAMESPACE();

#endif  // BEZINV_KERNELS_BATCH_SIZES_INL_H_
