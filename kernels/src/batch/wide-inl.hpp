// G SIMD vectors used as one ("wide" vectors), for kernels whose work per group of lanes is one
// long dependency chain: with G independent vectors in flight the core overlaps their latencies
// (the LU null-vector kernel at small n waits on its square roots and divisions, not on its
// arithmetic). The operations are Highway's, applied vector by vector, so every lane computes
// exactly what it would with G = 1. Re-included once per instruction set (see sizes-inl.hpp).
#if defined(BEZINV_KERNELS_BATCH_WIDE_INL_H_) == defined(HWY_TARGET_TOGGLE)
#ifdef BEZINV_KERNELS_BATCH_WIDE_INL_H_
#undef BEZINV_KERNELS_BATCH_WIDE_INL_H_
#else
#define BEZINV_KERNELS_BATCH_WIDE_INL_H_
#endif

#include <hwy/highway.h>

#include <cstddef>

HWY_BEFORE_NAMESPACE();
namespace bezinv::kernels::HWY_NAMESPACE::wide {
namespace hn = hwy::HWY_NAMESPACE;

// The descriptor: G vectors of the native descriptor D, laid out one after the other in memory.
// Vec<Tag<G>> and Mask<Tag<G>> are its vector and mask types, so that code written against
// Highway's names (Vec<D>, MaxLanes(D()), Load(d, p), ...) runs on it unchanged.
template <int G>
struct Tag {
  using D = hn::ScalableTag<double>;
  static constexpr int kVectors = G;
};
template <class T>
constexpr std::size_t MaxLanes(T) { return T::kVectors * hn::MaxLanes(typename T::D()); }

template <class T>
struct Vec {
  using Tag = T;
  hn::Vec<typename T::D> v[T::kVectors];
};
template <class V>
using DFromV = typename V::Tag;
template <class T>
struct Mask {
  hn::Mask<typename T::D> m[T::kVectors];
};

#define BEZINV_WIDE_EACH(result, expression) \
  result r;                                  \
  for (int g = 0; g < T::kVectors; ++g) r.expression;  \
  return r

template <class T> HWY_INLINE Vec<T> Zero(T) { BEZINV_WIDE_EACH(Vec<T>, v[g] = hn::Zero(typename T::D())); }
template <class T> HWY_INLINE Vec<T> Set(T, double x) { BEZINV_WIDE_EACH(Vec<T>, v[g] = hn::Set(typename T::D(), x)); }
template <class T>
HWY_INLINE Vec<T> Load(T, const double* HWY_RESTRICT p) {
  constexpr std::size_t L = hn::MaxLanes(typename T::D());
  BEZINV_WIDE_EACH(Vec<T>, v[g] = hn::Load(typename T::D(), p + g * L));
}
template <class T>
HWY_INLINE Vec<T> LoadU(T, const double* HWY_RESTRICT p) {
  constexpr std::size_t L = hn::MaxLanes(typename T::D());
  BEZINV_WIDE_EACH(Vec<T>, v[g] = hn::LoadU(typename T::D(), p + g * L));
}
template <class T>
HWY_INLINE void Store(const Vec<T>& a, T, double* HWY_RESTRICT p) {
  constexpr std::size_t L = hn::MaxLanes(typename T::D());
  for (int g = 0; g < T::kVectors; ++g) hn::Store(a.v[g], typename T::D(), p + g * L);
}

template <class T>
HWY_INLINE void StoreU(const Vec<T>& a, T, double* HWY_RESTRICT p) {
  constexpr std::size_t L = hn::MaxLanes(typename T::D());
  for (int g = 0; g < T::kVectors; ++g) hn::StoreU(a.v[g], typename T::D(), p + g * L);
}

template <class T> HWY_INLINE Vec<T> Add(const Vec<T>& a, const Vec<T>& b) { BEZINV_WIDE_EACH(Vec<T>, v[g] = hn::Add(a.v[g], b.v[g])); }
template <class T> HWY_INLINE Vec<T> Sub(const Vec<T>& a, const Vec<T>& b) { BEZINV_WIDE_EACH(Vec<T>, v[g] = hn::Sub(a.v[g], b.v[g])); }
template <class T> HWY_INLINE Vec<T> Mul(const Vec<T>& a, const Vec<T>& b) { BEZINV_WIDE_EACH(Vec<T>, v[g] = hn::Mul(a.v[g], b.v[g])); }
template <class T> HWY_INLINE Vec<T> Div(const Vec<T>& a, const Vec<T>& b) { BEZINV_WIDE_EACH(Vec<T>, v[g] = hn::Div(a.v[g], b.v[g])); }
template <class T> HWY_INLINE Vec<T> Max(const Vec<T>& a, const Vec<T>& b) { BEZINV_WIDE_EACH(Vec<T>, v[g] = hn::Max(a.v[g], b.v[g])); }
template <class T> HWY_INLINE Vec<T> Min(const Vec<T>& a, const Vec<T>& b) { BEZINV_WIDE_EACH(Vec<T>, v[g] = hn::Min(a.v[g], b.v[g])); }
template <class T> HWY_INLINE Vec<T> CopySign(const Vec<T>& a, const Vec<T>& b) { BEZINV_WIDE_EACH(Vec<T>, v[g] = hn::CopySign(a.v[g], b.v[g])); }
template <class T> HWY_INLINE Vec<T> Abs(const Vec<T>& a) { BEZINV_WIDE_EACH(Vec<T>, v[g] = hn::Abs(a.v[g])); }
template <class T> HWY_INLINE Vec<T> Sqrt(const Vec<T>& a) { BEZINV_WIDE_EACH(Vec<T>, v[g] = hn::Sqrt(a.v[g])); }
// The fused operations a * b + c, a * b - c, c - a * b.
#define BEZINV_WIDE_FUSED(Op)                                                    \
  template <class T>                                                             \
  HWY_INLINE Vec<T> Op(const Vec<T>& a, const Vec<T>& b, const Vec<T>& c) {      \
    BEZINV_WIDE_EACH(Vec<T>, v[g] = hn::Op(a.v[g], b.v[g], c.v[g]));            \
  }
BEZINV_WIDE_FUSED(MulAdd)
BEZINV_WIDE_FUSED(MulSub)
BEZINV_WIDE_FUSED(NegMulAdd)
#undef BEZINV_WIDE_FUSED
template <class T>
HWY_INLINE Vec<T> IfThenElse(const Mask<T>& m, const Vec<T>& a, const Vec<T>& b) {
  BEZINV_WIDE_EACH(Vec<T>, v[g] = hn::IfThenElse(m.m[g], a.v[g], b.v[g]));
}
template <class T> HWY_INLINE Mask<T> Eq(const Vec<T>& a, const Vec<T>& b) { BEZINV_WIDE_EACH(Mask<T>, m[g] = hn::Eq(a.v[g], b.v[g])); }
template <class T> HWY_INLINE Mask<T> Gt(const Vec<T>& a, const Vec<T>& b) { BEZINV_WIDE_EACH(Mask<T>, m[g] = hn::Gt(a.v[g], b.v[g])); }
template <class T> HWY_INLINE Mask<T> Le(const Vec<T>& a, const Vec<T>& b) { BEZINV_WIDE_EACH(Mask<T>, m[g] = hn::Le(a.v[g], b.v[g])); }
template <class T> HWY_INLINE Vec<T> Neg(const Vec<T>& a) { BEZINV_WIDE_EACH(Vec<T>, v[g] = hn::Neg(a.v[g])); }
template <class T> HWY_INLINE Mask<T> Ge(const Vec<T>& a, const Vec<T>& b) { BEZINV_WIDE_EACH(Mask<T>, m[g] = hn::Ge(a.v[g], b.v[g])); }
template <class T> HWY_INLINE Mask<T> Lt(const Vec<T>& a, const Vec<T>& b) { BEZINV_WIDE_EACH(Mask<T>, m[g] = hn::Lt(a.v[g], b.v[g])); }
template <class T> HWY_INLINE Mask<T> Ne(const Vec<T>& a, const Vec<T>& b) { BEZINV_WIDE_EACH(Mask<T>, m[g] = hn::Ne(a.v[g], b.v[g])); }
template <class T> HWY_INLINE Mask<T> IsNaN(const Vec<T>& a) { BEZINV_WIDE_EACH(Mask<T>, m[g] = hn::IsNaN(a.v[g])); }
template <class T> HWY_INLINE Mask<T> IsFinite(const Vec<T>& a) { BEZINV_WIDE_EACH(Mask<T>, m[g] = hn::IsFinite(a.v[g])); }
template <class T> HWY_INLINE Mask<T> And(const Mask<T>& a, const Mask<T>& b) { BEZINV_WIDE_EACH(Mask<T>, m[g] = hn::And(a.m[g], b.m[g])); }
template <class T> HWY_INLINE Mask<T> Or(const Mask<T>& a, const Mask<T>& b) { BEZINV_WIDE_EACH(Mask<T>, m[g] = hn::Or(a.m[g], b.m[g])); }
template <class T> HWY_INLINE Mask<T> AndNot(const Mask<T>& a, const Mask<T>& b) { BEZINV_WIDE_EACH(Mask<T>, m[g] = hn::AndNot(a.m[g], b.m[g])); }
template <class T> HWY_INLINE Mask<T> Not(const Mask<T>& a) { BEZINV_WIDE_EACH(Mask<T>, m[g] = hn::Not(a.m[g])); }
// The first n lanes of the wide vector.
template <class T> HWY_INLINE Mask<T> FirstN(T, std::size_t n) { BEZINV_WIDE_EACH(Mask<T>, m[g] = hn::FirstN(typename T::D(), n > g * hn::MaxLanes(typename T::D()) ? n - g * hn::MaxLanes(typename T::D()) : 0)); }
template <class T>
HWY_INLINE bool AllFalse(T, const Mask<T>& m) {
  for (int g = 0; g < T::kVectors; ++g)
    if (!hn::AllFalse(typename T::D(), m.m[g])) return false;
  return true;
}

template <class T>
HWY_INLINE std::size_t CountTrue(T, const Mask<T>& m) {
  std::size_t count = 0;
  for (int g = 0; g < T::kVectors; ++g) count += hn::CountTrue(typename T::D(), m.m[g]);
  return count;
}

#undef BEZINV_WIDE_EACH

// One group of a batch: p[first .. first + lanes) (lanes <= MaxLanes), then `padding` in the
// lanes past them (the last group of a batch that is not a multiple of the group's width).
template <class T>
HWY_INLINE Vec<T> LoadGroup(T d, const double* HWY_RESTRICT p, std::size_t first, std::size_t lanes, double padding) {
  constexpr std::size_t L = MaxLanes(T());
  if (lanes == L) return LoadU(d, p + first);
  HWY_ALIGN double buffer[L];
  for (std::size_t l = 0; l < L; ++l) buffer[l] = l < lanes ? p[first + l] : padding;
  return Load(d, buffer);
}
// The group's first `lanes` lanes to p[first .. first + lanes).
template <class T>
HWY_INLINE void StoreGroup(const Vec<T>& a, T d, double* HWY_RESTRICT p, std::size_t first, std::size_t lanes) {
  constexpr std::size_t L = MaxLanes(T());
  if (lanes == L) return StoreU(a, d, p + first);
  HWY_ALIGN double buffer[L];
  Store(a, d, buffer);
  for (std::size_t l = 0; l < lanes; ++l) p[first + l] = buffer[l];
}

// group(Tag<G>(), first, lanes) for the consecutive groups of a batch of `count` lanes, G vectors
// a group, but a last group that one vector holds as Tag<1>: a wider one would compute its other
// vectors for padding lanes only, nearly what the first costs.
template <int G, class Group>
HWY_INLINE void ForEachGroup(std::size_t count, Group&& group) {
  constexpr std::size_t LW = MaxLanes(Tag<G>()), L1 = MaxLanes(Tag<1>());
  std::size_t first = 0;
  for (; first + L1 < count; first += LW) group(Tag<G>(), first, count - first < LW ? count - first : LW);
  if (first < count) group(Tag<1>(), first, count - first);
}

}  // namespace bezinv::kernels::HWY_NAMESPACE::wide
HWY_AFTER_NAMESPACE();

#endif  // BEZINV_KERNELS_BATCH_WIDE_INL_H_
