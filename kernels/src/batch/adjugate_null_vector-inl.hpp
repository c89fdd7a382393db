// The seed kernel at n = 3 (Implementation::null_vector_seed): the null vector of a symmetric
// 3 x 3 matrix from its adjugate, one matrix per lane. Re-included once per instruction set by
// hwy/foreach_target.h (see null_vector_seed.cpp).
//
// Why. adj(B) B = det(B) I, so for B of rank 2 every nonzero column of adj(B) spans the null
// space, and for regular B, adj(B) = det(B) B^-1: multiplying by it is one step of inverse
// iteration without a factorization or a division, faster than the L D L^T seed at this size
// (docs/kernels.md).
//
// What it computes, per lane, on B normalised to ||B||_F = 1:
//   x = adj(B) (1, 1, 1), the L D L^T seed's start: every Bernstein basis vector is positive, so
//       for rank 2, where adj(B) = +-sigma_1 sigma_2 z z^T, x = +-sigma_1 sigma_2 (z . 1) z is far
//       from 0. (Starting from the largest column of adj(B) instead, the settling measure below
//       is much larger on points off the curve, and twice as many of them miss the engine's gate.)
//   z = adj(B) x / ||adj(B) x||, a second step, so that the angle between x and z measures how
//       far the iteration is from settling, as the L D L^T seed's two iterates do (for regular B
//       it shrinks with sigma_3 / sigma_2; rank 2 leaves rounding);
//   the residual ||B z|| / ||B||_F from B's own entries.
// Where x or z vanishes (B of rank 1 or 0, nullity 2 or 3, to rounding: kVanishing2): defect 1
// and z = (1, 1, 1) / sqrt(3).
// Only B's lower triangle is read.
#if defined(BEZINV_KERNELS_BATCH_ADJUGATE_NULL_VECTOR_INL_H_) == defined(HWY_TARGET_TOGGLE)
#ifdef BEZINV_KERNELS_BATCH_ADJUGATE_NULL_VECTOR_INL_H_
#undef BEZINV_KERNELS_BATCH_ADJUGATE_NULL_VECTOR_INL_H_
#else
#define BEZINV_KERNELS_BATCH_ADJUGATE_NULL_VECTOR_INL_H_
#endif

#include <hwy/highway.h>

#include <algorithm>
#include <cstddef>
#include <vector>

#include "batch/matrix_source-inl.hpp"
#include "batch/wide-inl.hpp"

HWY_BEFORE_NAMESPACE();
namespace bezinv::kernels::HWY_NAMESPACE {
namespace adjugate {
namespace hn = wide;

// Below this |v|^2 a vector of the adjugate of a normalised B is treated as vanishing (B of rank
// 1 or 0 up to rounding): its square would underflow in the settling measure below, and
// sigma_1 sigma_2 < 1e-140 is far below any Bezout matrix a seed is asked for.
inline constexpr double kVanishing2 = 1e-280;

template <class Source, class D>
HWY_NOINLINE void seed_group(D d, std::size_t stride, std::size_t first, std::size_t lanes, const Source& source,
                             double* HWY_RESTRICT z, double* HWY_RESTRICT defect, double* HWY_RESTRICT residual) {
  using V = hn::Vec<D>;
  constexpr std::size_t L = hn::MaxLanes(D());
  const V one = hn::Set(d, 1.0);
  const GroupMatrix<Source, D> matrix(d, source, stride, first, lanes);
  auto entry = [&](int r, int c) { return matrix.entry(static_cast<std::size_t>(r * 3 + c)); };
  V b00 = entry(0, 0), b10 = entry(1, 0), b11 = entry(1, 1), b20 = entry(2, 0), b21 = entry(2, 1), b22 = entry(2, 2);
  if constexpr (GroupMatrix<Source, D>::kFormed) {  // as bezout_matrix's: NaN once an entry is not finite
    const V zero = hn::Zero(d);
    V poison = zero;
    for (const V& e : {b00, b10, b11, b20, b21, b22}) poison = hn::Add(poison, hn::Mul(e, zero));
    matrix.write_poison(poison);
  }
  // ||B||_F^2: the off-diagonal entries count twice.
  const V off2 = hn::MulAdd(b10, b10, hn::MulAdd(b20, b20, hn::Mul(b21, b21)));
  const V norm = hn::Sqrt(hn::MulAdd(hn::Set(d, 2.0), off2, hn::MulAdd(b00, b00, hn::MulAdd(b11, b11, hn::Mul(b22, b22)))));
  const auto zero_matrix = hn::Eq(norm, hn::Zero(d));
  const V scale = hn::IfThenElse(zero_matrix, one, hn::Div(one, norm));
  b00 = hn::Mul(b00, scale), b10 = hn::Mul(b10, scale), b11 = hn::Mul(b11, scale);
  b20 = hn::Mul(b20, scale), b21 = hn::Mul(b21, scale), b22 = hn::Mul(b22, scale);

  // The cofactors (adj(B) is symmetric for symmetric B).
  const V a00 = hn::MulSub(b11, b22, hn::Mul(b21, b21));
  const V a11 = hn::MulSub(b00, b22, hn::Mul(b20, b20));
  const V a22 = hn::MulSub(b00, b11, hn::Mul(b10, b10));
  const V a10 = hn::MulSub(b20, b21, hn::Mul(b10, b22));
  const V a20 = hn::MulSub(b10, b21, hn::Mul(b11, b20));
  const V a21 = hn::MulSub(b10, b20, hn::Mul(b00, b21));

  // x = adj(B) (1, 1, 1): the first step, from the start the L D L^T seed takes too.
  const V x0 = hn::Add(hn::Add(a00, a10), a20);
  const V x1 = hn::Add(hn::Add(a10, a11), a21);
  const V x2 = hn::Add(hn::Add(a20, a21), a22);
  const V xx = hn::MulAdd(x0, x0, hn::MulAdd(x1, x1, hn::Mul(x2, x2)));

  // z = adj(B) x, normalised: the second iterate.
  V z0 = hn::MulAdd(a00, x0, hn::MulAdd(a10, x1, hn::Mul(a20, x2)));
  V z1 = hn::MulAdd(a10, x0, hn::MulAdd(a11, x1, hn::Mul(a21, x2)));
  V z2 = hn::MulAdd(a20, x0, hn::MulAdd(a21, x1, hn::Mul(a22, x2)));
  const V zz = hn::MulAdd(z0, z0, hn::MulAdd(z1, z1, hn::Mul(z2, z2)));
  const V vanishing = hn::Set(d, kVanishing2);
  const auto degenerate = hn::Not(hn::And(hn::Gt(xx, vanishing), hn::Gt(zz, vanishing)));  // NaN too
  const V inv_z = hn::Div(one, hn::Sqrt(zz));
  const V fallback = hn::Set(d, 0.57735026918962573);  // 1 / sqrt(3)
  z0 = hn::IfThenElse(degenerate, fallback, hn::Mul(z0, inv_z));
  z1 = hn::IfThenElse(degenerate, fallback, hn::Mul(z1, inv_z));
  z2 = hn::IfThenElse(degenerate, fallback, hn::Mul(z2, inv_z));

  // The settling measure: sin of the angle between x and z, |x x z| / |x| (the cross product keeps
  // its relative accuracy for tiny angles, as the chord of null_vector-inl.hpp does, and needs
  // neither x normalised nor a sign; for small angles the two measures agree to O(angle^3)).
  const V c0 = hn::MulSub(x1, z2, hn::Mul(x2, z1));
  const V c1 = hn::MulSub(x2, z0, hn::Mul(x0, z2));
  const V c2 = hn::MulSub(x0, z1, hn::Mul(x1, z0));
  V unsettled = hn::Sqrt(hn::Div(hn::MulAdd(c0, c0, hn::MulAdd(c1, c1, hn::Mul(c2, c2))), xx));

  // ||B z|| / ||B||_F.
  const V r0 = hn::MulAdd(b00, z0, hn::MulAdd(b10, z1, hn::Mul(b20, z2)));
  const V r1 = hn::MulAdd(b10, z0, hn::MulAdd(b11, z1, hn::Mul(b21, z2)));
  const V r2 = hn::MulAdd(b20, z0, hn::MulAdd(b21, z1, hn::Mul(b22, z2)));
  V res = hn::Sqrt(hn::MulAdd(r0, r0, hn::MulAdd(r1, r1, hn::Mul(r2, r2))));

  // As null_vector_group: a zero matrix (nullity 3) and a vanishing adjugate are flagged, NaN
  // (an overflow) compares false and becomes 1, the defect is capped at 1.
  unsettled = hn::IfThenElse(hn::Or(zero_matrix, degenerate), one, unsettled);
  unsettled = hn::IfThenElse(hn::Le(unsettled, one), unsettled, one);
  res = hn::IfThenElse(zero_matrix, hn::Zero(d), res);

  if (lanes == L) {
    hn::StoreU(unsettled, d, defect + first);
    hn::StoreU(res, d, residual + first);
    hn::StoreU(z0, d, z + first);
    hn::StoreU(z1, d, z + stride + first);
    hn::StoreU(z2, d, z + 2 * stride + first);
    return;
  }
  HWY_ALIGN double out[5][L];
  hn::Store(unsettled, d, out[0]);
  hn::Store(res, d, out[1]);
  hn::Store(z0, d, out[2]);
  hn::Store(z1, d, out[3]);
  hn::Store(z2, d, out[4]);
  for (std::size_t l = 0; l < lanes; ++l) {
    defect[first + l] = out[0][l];
    residual[first + l] = out[1][l];
    for (int r = 0; r < 3; ++r) z[r * stride + first + l] = out[2 + r][l];
  }
}

// Lanes per group: as null_vector_fixed (kWideVectors<3>, 4 vectors on the SIMD targets), the last
// group too (copied into a batch of its own where a stored batch's rows end before it); each lane
// computes the same numbers whatever the group.
template <int G, class Source>
void seed(std::size_t count, std::size_t stride, const Source& B, double* z, double* defect, double* residual) {
  using Wide = wide::Tag<G>;
  constexpr std::size_t LW = wide::MaxLanes(Wide());
  constexpr bool kPastTheRows = !GroupMatrix<Source, Wide>::kFormed;
  std::size_t first = 0;
  for (; first < count && (!kPastTheRows || first + LW <= stride); first += LW)
    seed_group(Wide(), stride, first, std::min(LW, count - first), B, z, defect, residual);
  if constexpr (kPastTheRows) {
    if (first >= count) return;
    const std::size_t lanes = count - first;
    std::vector<double> padded(9 * LW, 0.0), z_lanes(3 * LW), defect_lanes(LW), residual_lanes(LW);
    for (std::size_t i = 0; i < 9; ++i) std::copy_n(B.B + i * stride + first, lanes, padded.data() + i * LW);
    seed_group(Wide(), LW, 0, lanes, StoredMatrices{padded.data()}, z_lanes.data(), defect_lanes.data(),
               residual_lanes.data());
    for (std::size_t l = 0; l < lanes; ++l) {
      defect[first + l] = defect_lanes[l];
      residual[first + l] = residual_lanes[l];
      for (std::size_t r = 0; r < 3; ++r) z[r * stride + first + l] = z_lanes[r * LW + l];
    }
  }
}

}  // namespace adjugate
}  // namespace bezinv::kernels::HWY_NAMESPACE
HWY_AFTER_NAMESPACE();

#endif  // BEZINV_KERNELS_BATCH_ADJUGATE_NULL_VECTOR_INL_H_
