// Compiles batch/rational_newton-inl.hpp once per instruction set and exports the entry points.
#include "batch/targets.hpp"
// clang-format off
#undef HWY_TARGET_INCLUDE
#define HWY_TARGET_INCLUDE "batch/rational_newton.cpp"
#include <hwy/foreach_target.h>  // re-includes this file once per target
// clang-format on
#include <hwy/highway.h>

#include "batch/rational_newton-inl.hpp"

#if HWY_ONCE
#include "batch/kernels.hpp"

namespace bezinv::kernels::batch {

RationalNewtonKernel rational_newton_kernel(std::int64_t target) {
  switch (target) {
#if HWY_TARGETS & HWY_SCALAR
    case HWY_SCALAR: return &N_SCALAR::rational_newton_batch;
#endif
#if HWY_TARGETS & HWY_EMU128
    case HWY_EMU128: return &N_EMU128::rational_newton_batch;
#endif
#if HWY_TARGETS & HWY_AVX2
    case HWY_AVX2: return &N_AVX2::rational_newton_batch;
#endif
#if HWY_TARGETS & HWY_AVX3
    case HWY_AVX3: return &N_AVX3::rational_newton_batch;
#endif
    default: return nullptr;
  }
}

}  // namespace bezinv::kernels::batch
#endif  // HWY_ONCE
