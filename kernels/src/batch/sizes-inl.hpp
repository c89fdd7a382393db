// n -> kernel<n> for n in a kernel's range [MinSize, MaxSize] (bezinv/kernels/batch.hpp), per
// instruction set (re-included by foreach_target so the dispatching function carries the same
// target attributes as the kernels it calls). Every size is one instantiation per instruction
// set, so each kernel is compiled only for the sizes the engine calls.
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
// Throws std::out_of_range naming the kernel and its range (implementation.cpp).
[[noreturn]] void size_out_of_range(const char* kernel, int n, int min_size, int max_size);
}  // namespace bezinv::kernels::batch

HWY_BEFORE_NAMESPACE();
namespace bezinv::kernels::HWY_NAMESPACE {

// f(std::integral_constant<int, n>{}) if n is one of MinSize + Ns; whether it was.
template <int MinSize, class F, int... Ns>
HWY_INLINE bool call_for_size(int n, F&& f, std::integer_sequence<int, Ns...>) {
  return ((n == MinSize + Ns ? (f(std::integral_constant<int, MinSize + Ns>{}), true) : false) || ...);
}

// Calls f(std::integral_constant<int, n>{}) for n in [MinSize, MaxSize]; any other n throws
// std::out_of_range naming `kernel` and its range (a caller outside it is a bug, never silently
// skipped).
template <int MinSize, int MaxSize, class F>
HWY_INLINE void dispatch_size(const char* kernel, int n, F&& f) {
  static_assert(1 <= MinSize && MinSize <= MaxSize && MaxSize <= kMaxBatchSize);
  if (!call_for_size<MinSize>(n, f, std::make_integer_sequence<int, MaxSize - MinSize + 1>{}))
    batch::size_out_of_range(kernel, n, MinSize, MaxSize);
}

// The same check for a kernel whose loops take n at run time (one instantiation for every size).
template <int MinSize, int MaxSize>
HWY_INLINE void check_size(const char* kernel, int n) {
  static_assert(1 <= MinSize && MinSize <= MaxSize && MaxSize <= kMaxBatchSize);
  if (n < MinSize || n > MaxSize) batch::size_out_of_range(kernel, n, MinSize, MaxSize);
}

}  // namespace bezinv::kernels::HWY_NAMESPACE
HWY_AFTER_NAMESPACE();

#endif  // BEZINV_KERNELS_BATCH_SIZES_INL_H_
