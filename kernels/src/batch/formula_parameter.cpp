// Compiles batch/formula_parameter-inl.hpp once per instruction set and exports the entry point.
#include "batch/targets.hpp"
// clang-format off
#undef HWY_TARGET_INCLUDE
#define HWY_TARGET_INCLUDE "batch/formula_parameter.cpp"
#include <hwy/foreach_target.h>  // re-includes this file once per target
// clang-format on
#include <hwy/highway.h>

#include "batch/formula_parameter-inl.hpp"

#if HWY_ONCE
#include "batch/kernels.hpp"
#include "batch/per_target.hpp"

namespace bezinv::kernels::batch {

FormulaParameterKernel formula_parameter_kernel(std::int64_t target) {
  return for_target<FormulaParameterKernel>(target, BEZINV_PER_TARGET(formula_parameter_batch));
}

}  // namespace bezinv::kernels::batch
#endif  // HWY_ONCE
