// Compiles batch/null_vector-inl.hpp once per instruction set and exports the entry points.
#include "batch/targets.hpp"
// clang-format off
#undef HWY_TARGET_INCLUDE
#define HWY_TARGET_INCLUDE "batch/null_vector.cpp"
#include <hwy/foreach_target.h>  // re-includes this file once per target
// clang-format on
#include <hwy/highway.h>

#include "batch/null_vector-inl.hpp"

#if HWY_ONCE
#include "batch/kernels.hpp"
#include "batch/per_target.hpp"

namespace bezinv::kernels::batch {

NullVectorKernel null_vector_kernel(std::int64_t target) {
  return for_target<NullVectorKernel>(target, BEZINV_PER_TARGET(null_vector_batch));
}

NullVectorSeedKernel null_vector_seed_kernel(std::int64_t target) {
  return for_target<NullVectorSeedKernel>(target, BEZINV_PER_TARGET(null_vector_seed_batch));
}

}  // namespace bezinv::kernels::batch
#endif  // HWY_ONCE
