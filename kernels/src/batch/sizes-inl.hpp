// n -> kernel<n> for n = 1..(the kernel's largest size), per instruction set (re-included by
// foreach_target so the dispatching function carries the same target attributes as the kernels it
// calls). Every size is one instantiation per instruction set, so each kernel is compiled only for
// the sizes the engine calls (its limit in bezinv/kernels/batch.hpp).
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

namespace bezinv::kernels::batch {
// Throws std::out_of_range naming the kernel and its sizes (implementation.cpp).
[[noreturn]] void size_out_of_range(const char* kernel, int n, int max_size);
}  // namespace bezinv::kernels::batch

HWY_BEFORE_NAMESPACE();
namespace bezinv::kernels::HWY_NAMESPACE {

template <class F, int... Ns>
HWY_INLINE bool dispatch_size(int n, F&& f, std::integer_sequence<int, Ns...>) {
  return ((n == Ns + 1 ? (f(std::integral_constant<int, Ns + 1>{}), true) : false) || ...);
}

// Calls f(std::integral_constant<int, n>{}) for n = 1..MaxSize; any other n throws
// std::out_of_range naming `kernel` (a caller above the limit is a bug, never silently skipped).
template <int MaxSize, class F>
HWY_INLINE void dispatch_size(const char* kernel, int n, F&& f) {
  static_assert(MaxSize >= 1 && MaxSize <= kMaxBatchSize);
  if (!dispatch_size(n, f, std::make_integer_sequence<int, MaxSize>{})) batch::size_out_of_range(kernel, n, MaxSize);
}

}  // namespace bezinv::kernels::HWY_NAMESPACE
HWY_AFTER_NAMESPACE();

#endif  // BEZINV_KERNELS_BATCH_SIZES_INL_H_
