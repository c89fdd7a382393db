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
  // One entry of the lower triangle (the kernels read nothing else) for the point (pu, pv).
  auto entry = [&](std::size_t i, hn::Vec<decltype(d)> pu, hn::Vec<decltype(d)> pv, hn::Vec<decltype(d)> uv) {
    return hn::Add(hn::Sub(hn::Sub(hn::Set(d, B0[i]), hn::Mul(pu, hn::Set(d, Bx[i]))), hn::Mul(pv, hn::Set(d, By[i]))),
                   hn::Mul(uv, hn::Set(d, Bxy[i])));
  };
  // poison: the sum of entry * 0 (NaN once an entry is not finite, +0 otherwise, in any order of
  // the sum). One partial sum per row, added to the total at the row's end: a single running sum
  // was one dependent add per entry, the stage's critical path (BM_KernelBezoutMatrix).
  const auto zero = hn::Zero(d);
  std::size_t first = 0;
  // Two whole vectors at a time: each coefficient is broadcast once for both (the broadcasts are
  // loads, and were two thirds of the loads).
  for (; first + 2 * L <= count; first += 2 * L) {
    const auto pu0 = hn::LoadU(d, u + first), pv0 = hn::LoadU(d, v + first);
    const auto pu1 = hn::LoadU(d, u + first + L), pv1 = hn::LoadU(d, v + first + L);
    const auto uv0 = hn::Mul(pu0, pv0), uv1 = hn::Mul(pu1, pv1);
    auto sum0 = zero, sum1 = zero;
    for (int r = 0; r < n; ++r) {
      auto row0 = zero, row1 = zero;
      for (int c = 0; c <= r; ++c) {
        const std::size_t i = static_cast<std::size_t>(r * n + c);
        const auto b0 = hn::Set(d, B0[i]), bx = hn::Set(d, Bx[i]), by = hn::Set(d, By[i]), bxy = hn::Set(d, Bxy[i]);
        const auto e0 = hn::Add(hn::Sub(hn::Sub(b0, hn::Mul(pu0, bx)), hn::Mul(pv0, by)), hn::Mul(uv0, bxy));
        const auto e1 = hn::Add(hn::Sub(hn::Sub(b0, hn::Mul(pu1, bx)), hn::Mul(pv1, by)), hn::Mul(uv1, bxy));
        hn::StoreU(e0, d, B + i * stride + first);  // B need not be vector-aligned
        hn::StoreU(e1, d, B + i * stride + first + L);
        row0 = hn::Add(row0, hn::Mul(e0, zero));
        row1 = hn::Add(row1, hn::Mul(e1, zero));
      }
      sum0 = hn::Add(sum0, row0);
      sum1 = hn::Add(sum1, row1);
    }
    hn::StoreU(sum0, d, poison + first);
    hn::StoreU(sum1, d, poison + first + L);
  }
  // The rest one vector at a time (whole vectors: rows are `stride` long, a multiple of
  // kBatchAlignment >= L).
  for (; first < count; first += L) {
    const auto pu = load(u, first), pv = load(v, first);
    const auto uv = hn::Mul(pu, pv);
    auto sum = zero;
    for (int r = 0; r < n; ++r) {
      auto row = zero;
      for (int c = 0; c <= r; ++c) {
        const std::size_t i = static_cast<std::size_t>(r * n + c);
        const auto e = entry(i, pu, pv, uv);
        hn::StoreU(e, d, B + i * stride + first);
        row = hn::Add(row, hn::Mul(e, zero));
      }
      sum = hn::Add(sum, row);
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
