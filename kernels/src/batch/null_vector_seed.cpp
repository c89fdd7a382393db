// Compiles batch/null_vector-inl.hpp once per instruction set and exports the seed kernels (L D L^T
// without pivoting, batch/ldlt-inl.hpp, no gap; at n = 3 the adjugate, adjugate_null_vector-inl.hpp):
// null_vector_seed on stored matrices, and bezout_null_vector_seed on Bezout matrices it forms
// itself (batch/matrix_source-inl.hpp). Both in this one translation unit, so that the
// factorizations and solves of the sizes they share are compiled once; the file is compiled
// without contraction, as bezout_matrix.cpp is, so that the entries the second
// forms are that kernel's bits (the seed's own arithmetic is written with explicit fused
// multiply-adds, so contraction changes nothing else). null_vector.cpp exports the pivoted kernel.
#include "batch/targets.hpp"
// clang-format off
#undef HWY_TARGET_INCLUDE
#define HWY_TARGET_INCLUDE "batch/null_vector_seed.cpp"
#include <hwy/foreach_target.h>  // re-includes this file once per target
// clang-format on
#include <hwy/highway.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <limits>

#include "batch/adjugate_null_vector-inl.hpp"
#include "batch/matrix_source-inl.hpp"
#include "batch/null_vector-inl.hpp"

HWY_BEFORE_NAMESPACE();
namespace bezinv::kernels::HWY_NAMESPACE {

// The seed of every lane's matrix stored in the batch: the adjugate at n = 3, L D L^T without
// pivoting above; the residual only where the defect is at most settled_defect (+inf elsewhere).
template <int N>
void seed_stored(std::size_t count, std::size_t stride, const StoredMatrices& source, double* z, double* defect,
                 double* residual, double settled_defect) {
  if constexpr (N == 3) {
    adjugate::seed<kWideVectors<3>>(count, stride, source, z, defect, residual);
    for (std::size_t l = 0; l < count; ++l)
      if (!(defect[l] <= settled_defect)) residual[l] = std::numeric_limits<double>::infinity();
  } else {
    null_vector_fixed<N, false>(count, stride, source, z, defect, residual, nullptr, settled_defect);
  }
}

// The seed of every lane's Bezout matrix, formed from the coefficients (matrix_source-inl.hpp),
// kChunk lanes at a time: first every group of the chunk, which leaves the residual of the
// settled lanes of its groups where fewer than a quarter settled (null_vector_group); then those
// lanes, compacted into groups of their own, B formed again for them. Each lane computes the same
// numbers in either: the residual's operations are the same, from the z and 1 / ||B||_F its group
// stored.
template <int N, bool kBilinear>
void seed_formed(std::size_t count, std::size_t stride, const BezoutMatrices<kBilinear>& source, double* z,
                 double* defect, double* residual, double settled_defect) {
  using Wide = wide::Tag<kWideVectors<N>>;
  constexpr std::size_t L = wide::MaxLanes(Wide());
  constexpr std::size_t kChunk = 64;
  static_assert(kChunk % L == 0);
  for (std::size_t chunk = 0; chunk < count; chunk += kChunk) {
    const std::size_t lanes = std::min(kChunk, count - chunk);
    std::array<double, kChunk> scale{};  // written by the groups that defer lanes, for their lanes
    std::array<std::uint8_t, kChunk> lane_of;
    std::size_t deferred = 0;
    for (std::size_t group = 0; group < lanes; group += L) {
      const std::size_t group_lanes = std::min(L, lanes - group);
      if (null_vector_group<N, false>(Wide(), stride, chunk + group, group_lanes, source, z, defect, residual,
                                      nullptr, settled_defect, scale.data() + group))
        for (std::size_t l = group; l < group + group_lanes; ++l)
          if (!std::isnan(scale[l])) lane_of[deferred++] = static_cast<std::uint8_t>(l);
    }
    if (deferred == 0) continue;
    HWY_ALIGN double u[kChunk], v[kChunk], lane_scale[kChunk];
    for (std::size_t k = 0; k < deferred; ++k) {
      const std::size_t l = chunk + lane_of[k];
      u[k] = source.u[l], v[k] = source.v[l], lane_scale[k] = scale[lane_of[k]];
    }
    BezoutMatrices<kBilinear> compacted = source;
    compacted.u = u, compacted.v = v, compacted.poison = nullptr;  // poison: written by the first pass
    for (std::size_t first = 0; first < deferred; first += L) {
      const std::size_t count_here = std::min(L, deferred - first);
      const GroupMatrix<BezoutMatrices<kBilinear>, Wide> matrix(Wide(), compacted, stride, first, count_here);
      HWY_ALIGN double x[N * L] = {};
      for (std::size_t j = 0; j < count_here; ++j)
        for (int r = 0; r < N; ++r) x[r * L + j] = z[static_cast<std::size_t>(r) * stride + chunk + lane_of[first + j]];
      HWY_ALIGN double out[L];
      wide::Store(wide::Mul(residual_norm<N>(Wide(), matrix, x), wide::LoadGroup(Wide(), lane_scale, first, count_here, 0.0)),
                  Wide(), out);
      for (std::size_t j = 0; j < count_here; ++j) residual[chunk + lane_of[first + j]] = out[j];
    }
  }
}

void null_vector_seed_batch(int n, std::size_t count, std::size_t stride, const double* B, double* z,
                            double* defect, double* residual, double settled_defect) {
  dispatch_size<kNullVectorSeedMinSize, kNullVectorSeedMaxSize>("null_vector_seed", n, [&](auto size) {
    seed_stored<decltype(size)::value>(count, stride, StoredMatrices{B}, z, defect, residual, settled_defect);
  });
}

void bezout_null_vector_seed_batch(int n, std::size_t count, std::size_t stride, const double* B0, const double* Bx,
                                   const double* By, const double* Bxy, const double* u, const double* v, double* z,
                                   double* defect, double* residual, double* poison, double settled_defect) {
  dispatch_size<kBezoutNullVectorSeedMinSize, kBezoutNullVectorSeedMaxSize>(
      "bezout_null_vector_seed", n, [&](auto size) {
        constexpr int N = decltype(size)::value;
        // One denominator (Bxy null): B is affine in (u, v), see matrix_source-inl.hpp.
        if (Bxy == nullptr)
          seed_formed<N>(count, stride, BezoutMatrices<false>{B0, Bx, By, Bxy, u, v, poison}, z, defect, residual,
                         settled_defect);
        else
          seed_formed<N>(count, stride, BezoutMatrices<true>{B0, Bx, By, Bxy, u, v, poison}, z, defect, residual,
                         settled_defect);
      });
}

}  // namespace bezinv::kernels::HWY_NAMESPACE
HWY_AFTER_NAMESPACE();

#if HWY_ONCE
#include "batch/kernels.hpp"
#include "batch/per_target.hpp"

namespace bezinv::kernels::batch {

NullVectorSeedKernel null_vector_seed_kernel(std::int64_t target) {
  return for_target<NullVectorSeedKernel>(target, BEZINV_PER_TARGET(null_vector_seed_batch));
}

BezoutNullVectorSeedKernel bezout_null_vector_seed_kernel(std::int64_t target) {
  return for_target<BezoutNullVectorSeedKernel>(target, BEZINV_PER_TARGET(bezout_null_vector_seed_batch));
}

}  // namespace bezinv::kernels::batch
#endif  // HWY_ONCE
