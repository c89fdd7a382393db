// Lane-batched cyclic Jacobi eigendecomposition, one symmetric matrix per SIMD lane.
// Re-included once per instruction set by hwy/foreach_target.h (see symmetric_svd.cpp): the
// include guard below toggles per target, as Highway's own -inl.h files do.
#if defined(BEZINV_KERNELS_BATCH_SYMMETRIC_SVD_INL_H_) == defined(HWY_TARGET_TOGGLE)
#ifdef BEZINV_KERNELS_BATCH_SYMMETRIC_SVD_INL_H_
#undef BEZINV_KERNELS_BATCH_SYMMETRIC_SVD_INL_H_
#else
#define BEZINV_KERNELS_BATCH_SYMMETRIC_SVD_INL_H_
#endif

#include <hwy/highway.h>

#include <algorithm>
#include <cmath>
#include <cstddef>

#include "batch/constants.hpp"
#include "batch/sizes-inl.hpp"

HWY_BEFORE_NAMESPACE();
namespace bezinv::kernels::HWY_NAMESPACE {
namespace hn = hwy::HWY_NAMESPACE;

// One Jacobi rotation J(p, q, theta) applied as A <- J^T A J, Q <- Q J, in every lane at once.
// The angle is the stable one of Rutishauser / Golub & Van Loan (Alg. 8.5.1):
//     tau = (a_qq - a_pp) / (2 a_pq),   t = sign(tau) / (|tau| + sqrt(1 + tau^2)),
//     c = 1 / sqrt(1 + t^2),  s = t c,
// t being the smaller root of t^2 + 2 tau t - 1 = 0, so |theta| <= pi/4 and the off-diagonal norm
// decreases monotonically. Lanes with a_pq == 0 get t = 0 (the identity), chosen by a select since
// the other lanes still rotate. If tau^2 overflows, t rounds to 0: then |a_pq| < 1e-154 |a_qq - a_pp|,
// far below the tolerance.
//
// Lanes in `frozen` (already converged) get t = 0 as well: c = 1 and s = 0 exactly, so every value
// they hold is left bit for bit as it is (only their a_pq, no longer read, is zeroed). A lane's
// result is then the same whichever other matrices share its register: a point gets the same
// answer alone (invert_point) as in any batch.
template <int N, class D, class M>
HWY_INLINE void jacobi_rotate(D d, int p, int q, M frozen, double* HWY_RESTRICT A, double* HWY_RESTRICT Q) {
  constexpr std::size_t L = hn::MaxLanes(D());
  const auto one = hn::Set(d, 1.0);
  double* const pp = A + (p * N + p) * L;
  double* const qq = A + (q * N + q) * L;
  double* const pq = A + (p * N + q) * L;
  double* const qp = A + (q * N + p) * L;
  const auto apq = hn::Load(d, pq);
  const auto app = hn::Load(d, pp);
  const auto aqq = hn::Load(d, qq);
  const auto zero = hn::Or(hn::Eq(apq, hn::Zero(d)), frozen);
  const auto tau = hn::Div(hn::Sub(aqq, app), hn::Add(hn::IfThenElse(zero, one, apq), hn::IfThenElse(zero, one, apq)));
  const auto t_abs = hn::Div(one, hn::Add(hn::Abs(tau), hn::Sqrt(hn::MulAdd(tau, tau, one))));
  const auto t = hn::IfThenZeroElse(zero, hn::CopySign(t_abs, tau));
  const auto c = hn::Div(one, hn::Sqrt(hn::MulAdd(t, t, one)));
  const auto s = hn::Mul(t, c);
  // a'_pp = a_pp - t a_pq, a'_qq = a_qq + t a_pq, a'_pq = 0 (exactly, by the choice of t).
  hn::Store(hn::NegMulAdd(t, apq, app), d, pp);
  hn::Store(hn::MulAdd(t, apq, aqq), d, qq);
  hn::Store(hn::Zero(d), d, pq);
  hn::Store(hn::Zero(d), d, qp);
  for (int r = 0; r < N; ++r) {
    if (r == p || r == q) continue;
    const auto arp = hn::Load(d, A + (r * N + p) * L);
    const auto arq = hn::Load(d, A + (r * N + q) * L);
    const auto new_rp = hn::NegMulAdd(s, arq, hn::Mul(c, arp));  // c a_rp - s a_rq
    const auto new_rq = hn::MulAdd(s, arp, hn::Mul(c, arq));     // s a_rp + c a_rq
    hn::Store(new_rp, d, A + (r * N + p) * L);
    hn::Store(new_rp, d, A + (p * N + r) * L);
    hn::Store(new_rq, d, A + (r * N + q) * L);
    hn::Store(new_rq, d, A + (q * N + r) * L);
  }
  for (int r = 0; r < N; ++r) {
    const auto qrp = hn::Load(d, Q + (r * N + p) * L);
    const auto qrq = hn::Load(d, Q + (r * N + q) * L);
    hn::Store(hn::NegMulAdd(s, qrq, hn::Mul(c, qrp)), d, Q + (r * N + p) * L);
    hn::Store(hn::MulAdd(s, qrp, hn::Mul(c, qrq)), d, Q + (r * N + q) * L);
  }
}

// Lanes [first, first + lanes) of the batch; `lanes` < L only for the last group, whose padding
// lanes are computed (they hold finite values) but never written.
template <int N, class D>
HWY_NOINLINE void symmetric_svd_group(D d, std::size_t stride, std::size_t first, std::size_t lanes,
                                      const double* HWY_RESTRICT B, double* HWY_RESTRICT sigma,
                                      double* HWY_RESTRICT V) {
  constexpr std::size_t L = hn::MaxLanes(D());
  HWY_ALIGN double A[N * N * L];  // full symmetric storage: a rotation touches rows and columns
  HWY_ALIGN double Q[N * N * L];  // accumulated rotations, Q(r, k) = component r of eigenvector k
  auto norm2 = hn::Zero(d);
  for (int r = 0; r < N; ++r) {
    for (int c = 0; c <= r; ++c) {
      const auto b = hn::LoadU(d, B + static_cast<std::size_t>(r * N + c) * stride + first);
      hn::Store(b, d, A + (r * N + c) * L);
      hn::Store(b, d, A + (c * N + r) * L);
      norm2 = hn::MulAdd(b, b, norm2);
      if (c != r) norm2 = hn::MulAdd(b, b, norm2);
    }
  }
  for (int r = 0; r < N; ++r)
    for (int c = 0; c < N; ++c) hn::Store(hn::Set(d, r == c ? 1.0 : 0.0), d, Q + (r * N + c) * L);

  // off(A)^2 <= tol^2 ||A||_F^2, checked once per sweep (||A||_F is invariant under rotations).
  const auto limit2 = hn::Mul(hn::Set(d, batch::kJacobiTolerance * batch::kJacobiTolerance), norm2);
  for (int sweep = 0; sweep < batch::kJacobiMaxSweeps; ++sweep) {
    auto off2 = hn::Zero(d);
    for (int p = 0; p < N; ++p)
      for (int q = p + 1; q < N; ++q) {
        const auto a = hn::Load(d, A + (p * N + q) * L);
        off2 = hn::MulAdd(a, a, off2);
      }
    off2 = hn::Add(off2, off2);
    const auto converged = hn::Le(off2, limit2);
    if (hn::AllTrue(d, converged)) break;
    for (int p = 0; p < N; ++p)
      for (int q = p + 1; q < N; ++q) jacobi_rotate<N>(d, p, q, converged, A, Q);
  }

  // sigma = |lambda| sorted descending per lane, vectors carried along. The order differs per
  // lane, so this part is per lane: a stable insertion sort of n <= 32 indices, then one
  // gather-and-store pass that the output layout needs anyway.
  for (std::size_t l = 0; l < lanes; ++l) {
    int order[N];
    double magnitude[N];
    for (int k = 0; k < N; ++k) {
      order[k] = k;
      magnitude[k] = std::abs(A[(k * N + k) * L + l]);
    }
    for (int k = 1; k < N; ++k) {
      const int moving = order[k];
      int j = k;
      for (; j > 0 && magnitude[order[j - 1]] < magnitude[moving]; --j) order[j] = order[j - 1];
      order[j] = moving;
    }
    for (int k = 0; k < N; ++k) {
      sigma[static_cast<std::size_t>(k) * stride + first + l] = magnitude[order[k]];
      for (int r = 0; r < N; ++r)
        V[static_cast<std::size_t>(k * N + r) * stride + first + l] = Q[(r * N + order[k]) * L + l];
    }
  }
}

template <int N>
void symmetric_svd_fixed(std::size_t count, std::size_t stride, const double* B, double* sigma, double* V) {
  const hn::ScalableTag<double> d;
  constexpr std::size_t L = hn::MaxLanes(hn::ScalableTag<double>());
  for (std::size_t first = 0; first < count; first += L)
    symmetric_svd_group<N>(d, stride, first, std::min(L, count - first), B, sigma, V);
}

// The size is a template parameter so every loop bound is a constant (Ceres small_blas style).
void symmetric_svd_batch(int n, std::size_t count, std::size_t stride, const double* B, double* sigma,
                         double* V) {
  dispatch_size<kSymmetricSvdMinSize, kSymmetricSvdMaxSize>("symmetric_svd", n, [&](auto size) {
    symmetric_svd_fixed<decltype(size)::value>(count, stride, B, sigma, V);
  });
}

}  // namespace bezinv::kernels::HWY_NAMESPACE
HWY_AFTER_NAMESPACE();

#endif  // BEZINV_KERNELS_BATCH_SYMMETRIC_SVD_INL_H_
