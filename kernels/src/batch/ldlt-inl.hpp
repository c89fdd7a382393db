// B = L D L^T without pivoting, every lane alike: the factorization of the seed kernels
// (null_vector_seed, bezout_null_vector_seed). n^3 / 6 multiply-adds against the pivoted LU's
// n^3 / 3, and no per-lane row swaps. Solved by triangular_substitution-inl.hpp.
// Without pivoting a small pivot d_k makes the backward error large; the seed accepts that: its
// callers check what they make of z by other means (docs/kernels.md, "The seed").
// Re-included once per instruction set by hwy/foreach_target.h (see null_vector_seed.cpp).
#if defined(BEZINV_KERNELS_BATCH_LDLT_INL_H_) == defined(HWY_TARGET_TOGGLE)
#ifdef BEZINV_KERNELS_BATCH_LDLT_INL_H_
#undef BEZINV_KERNELS_BATCH_LDLT_INL_H_
#else
#define BEZINV_KERNELS_BATCH_LDLT_INL_H_
#endif

#include <hwy/highway.h>

#include <cstddef>

#include "batch/constants.hpp"
#include "batch/wide-inl.hpp"

HWY_BEFORE_NAMESPACE();
namespace bezinv::kernels::HWY_NAMESPACE {
namespace hn = wide;

// Unit L below the diagonal and D as 1 / d_k in inv_pivot, from B's lower triangle (its upper is
// never read: the factorization keeps its undivided multipliers there).
template <int N, class D>
struct Ldlt {
  static constexpr std::size_t L = hn::MaxLanes(D());
  static constexpr bool kLowerOnly = true;         // reads B's lower triangle only
  static constexpr bool kRowInterchanges = false;
  static constexpr bool kSeparateDiagonal = true;  // the upper factor is L^T (unit diagonal), D apart
  HWY_ALIGN double lu[N * N * L];     // unit L below the diagonal; above it, L D undivided
                                      // (c_jk at (k, j)); the diagonal is not rewritten
  HWY_ALIGN double inv_pivot[N * L];  // 1 / d_k

  double* at(int r, int c) { return lu + (r * N + c) * L; }
  const double* lower(int i, int k) const { return lu + (i * N + k) * L; }  // L(i, k), i > k
  const double* upper(int i, int k) const { return lu + (k * N + i) * L; }  // L^T(i, k) = L(k, i), i < k

  // Crout order: column j of L D is b_ij - sum_{k<j} l_ik c_jk (i >= j), c_jk = l_jk d_k the
  // undivided multiplier, kept in the upper triangle at (k, j) where the solves never look. Each
  // entry takes the updates of the steps k in ascending order, as the right-looking order
  // (a_ij <- a_ij - l_ik c_jk at step k) would: the same operations, so the same bits.
  // Crout, so that a tile of kTileRows rows x 2 columns stays in registers for all its k (one
  // store per entry) and the wide group's G vectors interleave their dependency chains.
  static constexpr int kTileRows = D::kVectors >= 4 ? 2 : 4;  // 4 vectors: 2 rows, or spills

  // B = L D L^T for B = scale times the lower triangle stored in lu (each entry is loaded once,
  // at the start of its tile, and scaled there).
  void factor(D d, hn::Vec<D> scale) {
    int j = 0;
    for (; j + 1 < N; j += 2) column_pair<true>(d, j, scale);
    if (j < N) column_pair<false>(d, j, scale);  // odd N: the last column alone
  }

  // Columns j and j + 1 (kPair; else column j alone): the diagonal rows first (row j gives d_j;
  // row j + 1 gives c_{j+1,j}, then, after step j, d_{j+1}), then the rows below in tiles.
  template <bool kPair>
  HWY_INLINE void column_pair(D d, int j, hn::Vec<D> scale) {
    constexpr int kHead = kPair ? 2 : 1;
    hn::Vec<D> a[kHead][2];
    tile_sums<kHead, kPair, true>(d, j, j, scale, a);
    const auto inv = pivot_inverse(d, j, a[0][0]);
    hn::Vec<D> c_next = hn::Zero(d), inv_next = hn::Zero(d);
    if constexpr (kPair) {
      c_next = a[1][0];
      hn::Store(c_next, d, at(j, j + 1));
      const auto l = hn::Mul(c_next, inv);
      hn::Store(l, d, at(j + 1, j));
      inv_next = pivot_inverse(d, j + 1, hn::NegMulAdd(l, c_next, a[1][1]));
    }
    int i0 = j + kHead;
    for (; i0 + kTileRows <= N; i0 += kTileRows) tile<kTileRows, kPair>(d, i0, j, scale, inv, c_next, inv_next);
    // The last rows one at a time: a tile of every height in between is one more instantiation.
    for (; i0 < N; ++i0) tile<1, kPair>(d, i0, j, scale, inv, c_next, inv_next);
  }

  // Rows i0 .. i0 + R - 1 of columns j (and j + 1): the stored entries times scale, every step
  // k < j applied. kHead: the rows j and j + 1, whose (j, j + 1) is not in the lower triangle (0
  // here, and unused).
  template <int R, bool kPair, bool kHead = false>
  HWY_INLINE void tile_sums(D d, int i0, int j, hn::Vec<D> scale, hn::Vec<D> (&a)[R][2]) {
#pragma GCC unroll 8
    for (int r = 0; r < R; ++r) {
      a[r][0] = hn::Mul(hn::Load(d, at(i0 + r, j)), scale);
      if constexpr (kPair)
        a[r][1] = kHead && r == 0 ? hn::Zero(d) : hn::Mul(hn::Load(d, at(i0 + r, j + 1)), scale);
    }
    for (int k = 0; k < j; ++k) {
      const auto c = hn::Load(d, at(k, j));
      hn::Vec<D> c2;
      if constexpr (kPair) c2 = hn::Load(d, at(k, j + 1));
#pragma GCC unroll 8
      for (int r = 0; r < R; ++r) {
        const auto l = hn::Load(d, at(i0 + r, k));
        a[r][0] = hn::NegMulAdd(l, c, a[r][0]);
        if constexpr (kPair) a[r][1] = hn::NegMulAdd(l, c2, a[r][1]);
      }
    }
  }

  // Rows i0 .. i0 + R - 1, all below the pair's diagonal rows: their sums, then column j's c and
  // l, step j on column j + 1, and its c and l.
  template <int R, bool kPair>
  HWY_INLINE void tile(D d, int i0, int j, hn::Vec<D> scale, hn::Vec<D> inv, hn::Vec<D> c_next,
                       hn::Vec<D> inv_next) {
    hn::Vec<D> a[R][2];
    tile_sums<R, kPair>(d, i0, j, scale, a);
#pragma GCC unroll 8
    for (int r = 0; r < R; ++r) {
      const int i = i0 + r;
      hn::Store(a[r][0], d, at(j, i));
      const auto l = hn::Mul(a[r][0], inv);
      hn::Store(l, d, at(i, j));
      if constexpr (kPair) {
        const auto c = hn::NegMulAdd(l, c_next, a[r][1]);
        hn::Store(c, d, at(j + 1, i));
        hn::Store(hn::Mul(c, inv_next), d, at(i, j + 1));
      }
    }
  }

  // 1 / d_k for the pivot d_k, guarded as PivotedLu's pivots are (below eps ||B|| -> +-eps); also
  // stored in inv_pivot.
  HWY_INLINE hn::Vec<D> pivot_inverse(D d, int k, hn::Vec<D> pivot) {
    const auto tiny = hn::Set(d, batch::kEpsilon);
    pivot = hn::IfThenElse(hn::Le(hn::Abs(pivot), tiny), hn::CopySign(tiny, pivot), pivot);
    const auto inv = hn::Div(hn::Set(d, 1.0), pivot);
    hn::Store(inv, d, inv_pivot + k * L);
    return inv;
  }
};

}  // namespace bezinv::kernels::HWY_NAMESPACE
HWY_AFTER_NAMESPACE();

#endif  // BEZINV_KERNELS_BATCH_LDLT_INL_H_
