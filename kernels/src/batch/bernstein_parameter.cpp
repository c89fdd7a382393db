// Compiles batch/bernstein_parameter-inl.hpp once per instruction set and exports the entry points.
#include "batch/targets.hpp"
// clang-format off
#undef HWY_TARGET_INCLUDE
#define HWY_TARGET_INCLUDE "batch/bernstein_parameter.cpp"
#include <hwy/foreach_target.h>  // re-includes this file once per target
// clang-format on
#include <hwy/highway.h>

#include "batch/bernstein_parameter-inl.hpp"

#if HWY_ONCE
#include "batch/kernels.hpp"

namespace bezinv::kernels::batch {

BernsteinParameterKernel bernstein_parameter_kernel(std::int64_t target) {
  switch (target) {
#if HWY_TARGETS & HWY_SCALAR
    case HWY_SCALAR: return &N_SCALAR::bernstein_parameter_batch;
#endif
#if HWY_TARGETS & HWY_EMU128
    case HWY_EMU128: return &N_EMU128::bernstein_parameter_batch;
#endif
#if HWY_TARGETS & HWY_AVX2
    case HWY_AVX2: return &N_AVX2::bernstein_parameter_batch;
#endif
#if HWY_TARGETS & HWY_AVX3
    case HWY_AVX3: return &N_AVX3::bernstein_parameter_batch;
#endif
    default: return nullptr;
  }
}

}  // namespace bezinv::kernels::batch
#endif  // HWY_ONCE
