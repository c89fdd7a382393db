// Compiles batch/space_check-inl.hpp once per instruction set and exports the entry points.
#include "batch/targets.hpp"
// clang-format off
#undef HWY_TARGET_INCLUDE
#define HWY_TARGET_INCLUDE "batch/space_check.cpp"
#include <hwy/foreach_target.h>  // re-includes this file once per target
// clang-format on
#include <hwy/highway.h>

#include "batch/space_check-inl.hpp"

#if HWY_ONCE
#include "batch/kernels.hpp"
#include "batch/per_target.hpp"

namespace bezinv::kernels::batch {

SpaceCheckKernel space_check_kernel(std::int64_t target) {
  return for_target<SpaceCheckKernel>(target, BEZINV_PER_TARGET(space_check_batch));
}

}  // namespace bezinv::kernels::batch
#endif  // HWY_ONCE
