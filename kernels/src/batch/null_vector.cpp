// Compiles batch/null_vector-inl.hpp once per instruction set and exports null_vector (pivoted LU,
// with the gap) and null_vector_iterations (the same with more solves); null_vector_seed.cpp exports the seed.
#include "batch/targets.hpp"
// clang-format off
#undef HWY_TARGET_INCLUDE
#define HWY_TARGET_INCLUDE "batch/null_vector.cpp"
#include <hwy/foreach_target.h>  // re-includes this file once per target
// clang-format on
#include <hwy/highway.h>

#include <stdexcept>
#include <string>

#include "batch/null_vector-inl.hpp"

HWY_BEFORE_NAMESPACE();
namespace bezinv::kernels::HWY_NAMESPACE {

void null_vector_iterations_batch(int n, int iterations, std::size_t count, std::size_t stride, const double* B,
                                  double* z, double* defect, double* estimate, double* second) {
  if (iterations < batch::kInverseIterations)
    throw std::invalid_argument("null_vector_iterations: iterations must be at least " +
                                std::to_string(batch::kInverseIterations));
  dispatch_size<kNullVectorMinSize, kNullVectorMaxSize>("null_vector", n, [&](auto size) {
    null_vector_fixed<decltype(size)::value, true>(count, stride, StoredMatrices{B}, z, defect, estimate, second,
                                                   1.0, iterations);
  });
}

void null_vector_batch(int n, std::size_t count, std::size_t stride, const double* B, double* z, double* defect,
                       double* estimate, double* second) {
  null_vector_iterations_batch(n, batch::kInverseIterations, count, stride, B, z, defect, estimate, second);
}

}  // namespace bezinv::kernels::HWY_NAMESPACE
HWY_AFTER_NAMESPACE();

#if HWY_ONCE
#include "batch/kernels.hpp"
#include "batch/per_target.hpp"

namespace bezinv::kernels::batch {

NullVectorKernel null_vector_kernel(std::int64_t target) {
  return for_target<NullVectorKernel>(target, BEZINV_PER_TARGET(null_vector_batch));
}

NullVectorIterationsKernel null_vector_iterations_kernel(std::int64_t target) {
  return for_target<NullVectorIterationsKernel>(target, BEZINV_PER_TARGET(null_vector_iterations_batch));
}

}  // namespace bezinv::kernels::batch
#endif  // HWY_ONCE
