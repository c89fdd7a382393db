#pragma once
// The one place that knows which Highway targets a kernel translation unit was compiled for, for
// the entry-point lookups of batch/kernels.hpp. Include after hwy/foreach_target.h, under HWY_ONCE
// (where the per-target namespaces N_SCALAR, N_EMU128, N_AVX2, N_AVX3 of the kernels exist):
//
//     NullVectorKernel null_vector_kernel(std::int64_t target) {
//       return batch::for_target(target, BEZINV_PER_TARGET(null_vector_batch));
//     }
#include <hwy/highway.h>

#include <array>
#include <cstdint>

#if HWY_TARGETS & HWY_SCALAR
#define BEZINV_IN_SCALAR(function) &::bezinv::kernels::N_SCALAR::function
#else
#define BEZINV_IN_SCALAR(function) nullptr
#endif
#if HWY_TARGETS & HWY_EMU128
#define BEZINV_IN_EMU128(function) &::bezinv::kernels::N_EMU128::function
#else
#define BEZINV_IN_EMU128(function) nullptr
#endif
#if HWY_TARGETS & HWY_AVX2
#define BEZINV_IN_AVX2(function) &::bezinv::kernels::N_AVX2::function
#else
#define BEZINV_IN_AVX2(function) nullptr
#endif
#if HWY_TARGETS & HWY_AVX3
#define BEZINV_IN_AVX3(function) &::bezinv::kernels::N_AVX3::function
#else
#define BEZINV_IN_AVX3(function) nullptr
#endif

// `function` as compiled for each target, nullptr where it was not: {scalar, emu128, avx2, avx3}.
#define BEZINV_PER_TARGET(function) \
  { BEZINV_IN_SCALAR(function), BEZINV_IN_EMU128(function), BEZINV_IN_AVX2(function), BEZINV_IN_AVX3(function) }

namespace bezinv::kernels::batch {

// The entry of `per_target` (BEZINV_PER_TARGET's order) for the Highway target bit `target`.
template <class Kernel>
Kernel for_target(std::int64_t target, const std::array<Kernel, 4>& per_target) {
  switch (target) {
    case HWY_SCALAR: return per_target[0];
    case HWY_EMU128: return per_target[1];
    case HWY_AVX2: return per_target[2];
    case HWY_AVX3: return per_target[3];
    default: return nullptr;
  }
}

}  // namespace bezinv::kernels::batch
