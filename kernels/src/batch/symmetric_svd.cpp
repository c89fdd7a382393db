// Compiles batch/symmetric_svd-inl.hpp once per instruction set and exports the entry points.
#include "batch/targets.hpp"
// clang-format off
#undef HWY_TARGET_INCLUDE
#define HWY_TARGET_INCLUDE "batch/symmetric_svd.cpp"
#include <hwy/foreach_target.h>  // re-includes this file once per target
// clang-format on
#include <hwy/highway.h>

#include "batch/symmetric_svd-inl.hpp"

#if HWY_ONCE
#include "batch/kernels.hpp"
#include "batch/per_target.hpp"

namespace bezinv::kernels::batch {

SymmetricSvdKernel symmetric_svd_kernel(std::int64_t target) {
  return for_target<SymmetricSvdKernel>(target, BEZINV_PER_TARGET(symmetric_svd_batch));
}

}  // namespace bezinv::kernels::batch
#endif  // HWY_ONCE
