// Lane-batched Bezout matrices B(u, v) = B0 - u Bx - v By + (u v) Bxy, one point per lane
// (bezinv/kernels/batch.hpp, Implementation::bezout_matrix). Re-included once per instruction set
// by hwy/foreach_target.h (see bezout_matrix.cpp).
//
// Each entry is computed as the engine wrote it, ((B0 - u Bx) - v By) + (u v) Bxy, without fused
// multiply-add (the file is compiled with -ffp-contract=off): the same bits on every instruction set.
#if defined(BEZINV_KERNELS_BATCH_BEZOUT_MATRIX_INL_H_) == defined(HWY_TARGET_TOGGLE)
#ifdef BEZINV_KERNELS_BATCH_BEZOUT_MATRIX_INL_H_
#undef BEZINV_KERNELS_BATCH_BEZOUT_MATRIX_INL_H_
#else
#define BEZINV_KERNELS_BATCH_BEZOUT_MATRIX_INL_H_
#endif

#include <hwy/highway.h>

#include <algorithm>
#include <cstddef>

HWY_BEFORE_NAMESPACE();
namespace bezinv::kernels::HWY_NAMESPACE {
namespace hn = hwy::HWY_NAMESPACE;

void bezout_matrix_batch(int n, std::size_t count, std::size_t stride, const double* B0, const double* Bx,
                         const double* By, const double* Bxy, const double* u, const double* v, double* B,
                         double* poison) {
  const hn::ScalableTag<double> d;
  constexpr std::size_t L = hn::MaxLanes(hn::ScalableTag<double>());
  HWY_ALIGN double lanes[L];
  // The group's points, 0 past `count` (those lanes then get B0: finite, as the layout asks).
  auto load = [&](const double* p, std::size_t first) {
    if (first + L <= count) return hn::LoadU(d, p + first);
    for (std::size_t l = 0; l < L; ++l) lanes[l] = first + l < count ? p[first + l] : 0.0;
    return hn::Load(d, lanes);
  };
  // Whole vectors: rows are `stride` long, a multiple of kBatchAlignment >= L.
  for (std::size_t first = 0; first < count; first += L) {
    const auto pu = load(u, first), pv = load(v, first);
    const auto uv = hn::Mul(pu, pv);
    auto sum = hn::Zero(d);
    for (int r = 0; r < n; ++r)
      for (int c = 0; c <= r; ++c) {  // the lower triangle: the kernels read nothing else
        const std::size_t i = static_cast<std::size_t>(r * n + c);
        const auto entry = hn::Add(hn::Sub(hn::Sub(hn::Set(d, B0[i]), hn::Mul(pu, hn::Set(d, Bx[i]))),
                                           hn::Mul(pv, hn::Set(d, By[i]))),
                                   hn::Mul(uv, hn::Set(d, Bxy[i])));
        hn::StoreU(entry, d, B + i * stride + first);  // B need not be vector-aligned
        sum = hn::Add(sum, hn::Mul(entry, hn::Zero(d)));  // NaN once an entry is not finite
      }
    if (first + L <= count) {
      hn::StoreU(sum, d, poison + first);
    } else {
      hn::Store(sum, d, lanes);
      std::copy_n(lanes, count - first, poison + first);
    }
  }
}

}  // namespace bezinv::kernels::HWY_NAMESPACE
HWY_AFTER_NAMESPACE();

#endif  // BEZINV_KERNELS_BATCH_BEZOUT_MATRIX_INL_H_
