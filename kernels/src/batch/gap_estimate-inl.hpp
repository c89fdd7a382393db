// The gap of null_vector: an estimate of sigma_{n-1} (the singular value next to the null
// vector's) of the factored, normalised matrix, by inverse iteration deflated against the null
// vector z and a Rayleigh-Ritz step on its last two iterates. Re-included once per instruction set
// by hwy/foreach_target.h (see null_vector.cpp).
#if defined(BEZINV_KERNELS_BATCH_GAP_ESTIMATE_INL_H_) == defined(HWY_TARGET_TOGGLE)
#ifdef BEZINV_KERNELS_BATCH_GAP_ESTIMATE_INL_H_
#undef BEZINV_KERNELS_BATCH_GAP_ESTIMATE_INL_H_
#else
#define BEZINV_KERNELS_BATCH_GAP_ESTIMATE_INL_H_
#endif

#include <hwy/highway.h>

#include <cstddef>

#include "batch/constants.hpp"
#include "batch/lane_vectors-inl.hpp"
#include "batch/triangular_substitution-inl.hpp"
#include "batch/wide-inl.hpp"

HWY_BEFORE_NAMESPACE();
namespace bezinv::kernels::HWY_NAMESPACE {
namespace hn = wide;

// The largest |Ritz value| of A (B's inverse deflated against z, symmetric like B) on the plane of
// the last two deflated iterates u = w_{K-2}, v = w_{K-1}, given w = w_K, A u = g1 v and
// A v = g2 w. The power iteration's growth g2 converges at the rate sigma_{n-1}/sigma_{n-2}, slowly
// when those two are close; the plane holds both directions and its Ritz value resolves them
// (Rayleigh-Ritz on the Krylov space span{u, A u}; Golub & Van Loan, Sect. 10.1). A Ritz value of
// a symmetric operator never exceeds its norm 1 / sigma_{n-1}, so sigma_{n-1} is still estimated
// from above.
// With q = (u - c v) / s the unit vector of the plane orthogonal to v (c = u.v, s^2 = 1 - c^2), the
// 2 x 2 matrix [v q]^T A [v q] needs only the dot products c, d = u.w and e = v.w:
//   T11 = g2 e,  T22 = c g2 (c e - d) / s^2,  T12 = (g1 - c g2 e) / s,  T21 = g2 (d - c e) / s,
// symmetrised (A is symmetric up to the rounding of the LU). When the iterates are nearly parallel
// (s^2 < 1e-6) the iteration has converged and the cancellation in c e - d would dominate: 0 then,
// so that the caller keeps g2.
template <int N, class D>
HWY_INLINE hn::Vec<D> ritz_growth(D d, const double* HWY_RESTRICT u, const double* HWY_RESTRICT v,
                                  const double* HWY_RESTRICT w, hn::Vec<D> g1, hn::Vec<D> g2) {
  const auto c = dot<N>(d, u, v), dd = dot<N>(d, u, w), e = dot<N>(d, v, w);
  const auto s2 = hn::NegMulAdd(c, c, hn::Set(d, 1.0));
  const auto planar = hn::Ge(s2, hn::Set(d, 1e-6));
  const auto safe_s2 = hn::IfThenElse(planar, s2, hn::Set(d, 1.0));
  const auto inv_s = hn::Div(hn::Set(d, 1.0), hn::Sqrt(safe_s2));
  const auto ce_minus_d = hn::MulSub(c, e, dd);
  const auto t11 = hn::Mul(g2, e);
  const auto t22 = hn::Div(hn::Mul(hn::Mul(c, g2), ce_minus_d), safe_s2);
  const auto t12 = hn::Mul(hn::NegMulAdd(hn::Mul(c, g2), e, g1), inv_s);
  const auto t21 = hn::Mul(hn::Neg(hn::Mul(g2, ce_minus_d)), inv_s);
  const auto off = hn::Mul(hn::Set(d, 0.5), hn::Add(t12, t21));
  const auto mean = hn::Mul(hn::Set(d, 0.5), hn::Add(t11, t22));
  const auto half_gap = hn::Mul(hn::Set(d, 0.5), hn::Sub(t11, t22));
  const auto radius = hn::Sqrt(hn::MulAdd(half_gap, half_gap, hn::Mul(off, off)));
  const auto largest = hn::Add(hn::Abs(mean), radius);
  // Not finite (NaN input, overflow): 0, so that the caller keeps g2 (NaN or not).
  return hn::IfThenElse(hn::And(planar, hn::IsFinite(largest)), largest, hn::Zero(d));
}

// 1 / sigma_{n-1} of the normalised matrix (estimated from below: sigma_{n-1} from above), by
// deflated_iterations(N) solves of `factors` orthogonal to the unit null vector z, and the
// deflated iterate in w: unit length, orthogonal to z, an approximation of the singular vector of
// sigma_{n-1}. NaN where the iteration overflowed (so that the caller's defect flags the lane).
template <int N, class Factors, class D>
HWY_INLINE hn::Vec<D> inverse_sigma_next(D d, const Factors& factors, const double* HWY_RESTRICT z,
                                         double* HWY_RESTRICT w) {
  static_assert(N >= 2, "no sigma_{n-1} at n = 1");
  constexpr std::size_t L = hn::MaxLanes(D());
  // w orthogonal to z, after every solve (the solve re-amplifies the rounding-level z component
  // by 1/eps).
  auto project = [&] {
    const auto along = dot<N>(d, w, z);
    for (int i = 0; i < N; ++i)
      hn::Store(hn::NegMulAdd(along, hn::Load(d, z + i * L), hn::Load(d, w + i * L)), d, w + i * L);
  };
  // The start: a fixed vector of mixed signs and sizes, with a generic component along every
  // direction orthogonal to z.
  for (int i = 0; i < N; ++i) hn::Store(hn::Set(d, (i % 2 ? -1.0 : 1.0) * (1.0 + 0.37 * i)), d, w + i * L);
  project();
  normalize<N>(d, w);
  // The last three iterates w_{K-2}, w_{K-1}, w_K and the last two growths g_{K-1}, g_K, with
  // A w_{k-1} = g_k w_k for A the inverse deflated against z.
  // (Zeroed only because GCC cannot see that the loop below always sets them before the Ritz
  // step reads them: -Wmaybe-uninitialized.)
  HWY_ALIGN double older[N * L] = {}, old[N * L] = {};
  auto growth = hn::Zero(d), old_growth = hn::Zero(d);
  constexpr int kIterations = batch::deflated_iterations(N);
  for (int iteration = 0; iteration < kIterations; ++iteration) {
    if (iteration + 2 == kIterations) copy<N>(d, w, older);  // w_{K-2}
    if (iteration + 1 == kIterations) copy<N>(d, w, old);    // w_{K-1}
    solve<N>(d, factors, w);
    // Twice: the solve makes the z component ~1/eps times larger than the rest, and one
    // projection leaves rounding of that size; the second removes it to rounding of the rest.
    project();
    project();
    old_growth = growth;
    growth = normalize<N>(d, w);  // ~ 1 / sigma_{n-1} of the normalised matrix
  }
  // Not Max: x86's max returns its second operand when either is NaN, and a NaN growth (an
  // overflow) must stay NaN.
  const auto ritz = ritz_growth<N>(d, older, old, w, old_growth, growth);
  return hn::IfThenElse(hn::Gt(ritz, growth), ritz, growth);
}

}  // namespace bezinv::kernels::HWY_NAMESPACE
HWY_AFTER_NAMESPACE();

#endif  // BEZINV_KERNELS_BATCH_GAP_ESTIMATE_INL_H_
