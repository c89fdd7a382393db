// Where the seed and null-vector kernels take a group's matrix entries from: the batch layout, or
// the Bezout matrices formed on the fly from a plan's coefficient matrices (no B stored at all).
// Re-included once per instruction set by hwy/foreach_target.h (see null_vector_seed.cpp).
#if defined(BEZINV_KERNELS_BATCH_MATRIX_SOURCE_INL_H_) == defined(HWY_TARGET_TOGGLE)
#ifdef BEZINV_KERNELS_BATCH_MATRIX_SOURCE_INL_H_
#undef BEZINV_KERNELS_BATCH_MATRIX_SOURCE_INL_H_
#else
#define BEZINV_KERNELS_BATCH_MATRIX_SOURCE_INL_H_
#endif

#include <hwy/highway.h>

#include <algorithm>
#include <cstddef>

#include "batch/wide-inl.hpp"

HWY_BEFORE_NAMESPACE();
namespace bezinv::kernels::HWY_NAMESPACE {

// The matrices as batch.hpp lays them out: lane l's entry at index i = r n + c is
// B[i * stride + l].
struct StoredMatrices {
  const double* B;
};

// The Bezout matrices of the points (u[l], v[l]) from a plan's coefficient matrices (n x n,
// row-major; engine/include/bezinv/plan.hpp), entry i formed at each use by
// GroupMatrix<BezoutMatrices>::entry, the one expression both bezout_matrix (which stores it) and
// the seed (which does not) use, in this order and without fused multiply-add (their translation
// units are compiled with -ffp-contract=off), so the engine's bits (bezout_at) on every
// instruction set:
//   kBilinear (separate denominators)  ((B0[i] - u Bx[i]) - v By[i]) + (u v) Bxy[i]
//   affine (one denominator W)          (B0[i] - u Bx[i]) - v By[i]
// With one denominator Bxy = Bez(W, W) = 0, so the affine form drops a multiplication, an
// addition and a broadcast load per entry that would add 0: a third of forming B, which the seed
// does twice per lane.
// The kernel writes poison[l] = the sum of the lane's entries times 0.
// Why form B at all: at high degree a batch's B no longer fits in L1 (n = 20: 107 KB for 64
// lanes), and reading it back from L2 would be most of the seed's time (docs/kernels.md).
template <bool kBilinear>
struct BezoutMatrices {
  const double *B0, *Bx, *By, *Bxy;  // Bxy unused (may be null) unless kBilinear
  const double *u, *v;               // `count` points
  double* poison;                    // out: `count` entries
};

// One group's view of a source: entry(i) is lanes first .. first + MaxLanes(d) - 1 of entry i.
template <class Source, class D>
class GroupMatrix;

template <class D>
class GroupMatrix<StoredMatrices, D> {
 public:
  static constexpr bool kFormed = false;
  GroupMatrix(D d, const StoredMatrices& source, std::size_t stride, std::size_t first, std::size_t)
      : d_(d), at_(source.B + first), stride_(stride) {}
  HWY_INLINE wide::Vec<D> entry(std::size_t i) const { return wide::LoadU(d_, at_ + i * stride_); }
  void write_poison(wide::Vec<D>) const {}

 private:
  D d_;
  const double* at_;
  std::size_t stride_;
};

template <bool kBilinear, class D>
class GroupMatrix<BezoutMatrices<kBilinear>, D> {
 public:
  static constexpr bool kFormed = true;
  static constexpr std::size_t L = wide::MaxLanes(D());
  // Lanes past `lanes` get the point (0, 0), so B0: finite, as the batch layout's padding.
  GroupMatrix(D d, const BezoutMatrices<kBilinear>& source, std::size_t, std::size_t first, std::size_t lanes)
      : d_(d), source_(source), first_(first), lanes_(lanes) {
    u_ = point(source.u);
    v_ = point(source.v);
    if constexpr (kBilinear) uv_ = wide::Mul(u_, v_);
  }
  HWY_INLINE wide::Vec<D> entry(std::size_t i) const {
    const auto affine =
        wide::Sub(wide::Sub(wide::Set(d_, source_.B0[i]), wide::Mul(u_, wide::Set(d_, source_.Bx[i]))),
                  wide::Mul(v_, wide::Set(d_, source_.By[i])));
    if constexpr (!kBilinear) return affine;
    else return wide::Add(affine, wide::Mul(uv_, wide::Set(d_, source_.Bxy[i])));
  }
  // The sum of the lane's entries times 0, as the caller accumulated it.
  void write_poison(wide::Vec<D> poison) const {
    if (lanes_ == L) return wide::StoreU(poison, d_, source_.poison + first_);
    HWY_ALIGN double lanes[L];
    wide::Store(poison, d_, lanes);
    std::copy_n(lanes, lanes_, source_.poison + first_);
  }

 private:
  wide::Vec<D> point(const double* p) const {
    if (lanes_ == L) return wide::LoadU(d_, p + first_);
    HWY_ALIGN double padded[L] = {};
    std::copy_n(p + first_, lanes_, padded);
    return wide::Load(d_, padded);
  }
  D d_;
  BezoutMatrices<kBilinear> source_;
  std::size_t first_, lanes_;
  wide::Vec<D> u_, v_, uv_;  // uv_ only where kBilinear
};

}  // namespace bezinv::kernels::HWY_NAMESPACE
HWY_AFTER_NAMESPACE();

#endif  // BEZINV_KERNELS_BATCH_MATRIX_SOURCE_INL_H_
