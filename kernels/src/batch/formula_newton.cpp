// Compiles batch/formula_newton-inl.hpp once per instruction set and exports the entry point.
#include "batch/targets.hpp"
// clang-format off
#undef HWY_TARGET_INCLUDE
#define HWY_TARGET_INCLUDE "batch/formula_newton.cpp"
#include <hwy/foreach_target.h>  // re-includes this file once per target
// clang-format on
#include <hwy/highway.h>

#include "batch/formula_newton-inl.hpp"

#if HWY_ONCE
#include "batch/kernels.hpp"
#include "batch/per_target.hpp"

namespace bezinv::kernels::batch {

FormulaNewtonKernel formula_newton_kernel(std::int64_t target) {
  return for_target<FormulaNewtonKernel>(target, BEZINV_PER_TARGET(formula_newton_batch));
}

}  // namespace bezinv::kernels::batch
#endif  // HWY_ONCE
