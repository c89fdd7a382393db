// Compiles the off-curve path's kernels, batch/nearest_sample-inl.hpp and
// batch/nearest_newton-inl.hpp, once per instruction set and exports their entry points.
#include "batch/targets.hpp"
// clang-format off
#undef HWY_TARGET_INCLUDE
#define HWY_TARGET_INCLUDE "batch/nearest_newton.cpp"
#include <hwy/foreach_target.h>  // re-includes this file once per target
// clang-format on
#include <hwy/highway.h>

#include "batch/nearest_newton-inl.hpp"
#include "batch/nearest_sample-inl.hpp"

#if HWY_ONCE
#include "batch/kernels.hpp"
#include "batch/per_target.hpp"

namespace bezinv::kernels::batch {

NearestSampleKernel nearest_sample_kernel(std::int64_t target) {
  return for_target<NearestSampleKernel>(target, BEZINV_PER_TARGET(nearest_sample_batch));
}

NearestNewtonKernel nearest_newton_kernel(std::int64_t target) {
  return for_target<NearestNewtonKernel>(target, BEZINV_PER_TARGET(nearest_newton_batch));
}

}  // namespace bezinv::kernels::batch
#endif  // HWY_ONCE
