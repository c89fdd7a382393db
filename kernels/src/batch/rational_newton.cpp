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
#include "batch/per_target.hpp"

namespace bezinv::kernels::batch {

RationalNewtonKernel rational_newton_kernel(std::int64_t target) {
  return for_target<RationalNewtonKernel>(target, BEZINV_PER_TARGET(rational_newton_batch));
}

RationalSlopeKernel rational_slope_kernel(std::int64_t target) {
  return for_target<RationalSlopeKernel>(target, BEZINV_PER_TARGET(rational_slope_batch));
}

}  // namespace bezinv::kernels::batch
#endif  // HWY_ONCE
