// Compiles batch/bezout_matrix-inl.hpp once per instruction set and exports the entry points.
#include "batch/targets.hpp"
// clang-format off
#undef HWY_TARGET_INCLUDE
#define HWY_TARGET_INCLUDE "batch/bezout_matrix.cpp"
#include <hwy/foreach_target.h>  // re-includes this file once per target
// clang-format on
#include <hwy/highway.h>

#include "batch/bezout_matrix-inl.hpp"

#if HWY_ONCE
#include "batch/kernels.hpp"
#include "batch/per_target.hpp"

namespace bezinv::kernels::batch {

BezoutMatrixKernel bezout_matrix_kernel(std::int64_t target) {
  return for_target<BezoutMatrixKernel>(target, BEZINV_PER_TARGET(bezout_matrix_batch));
}

}  // namespace bezinv::kernels::batch
#endif  // HWY_ONCE
