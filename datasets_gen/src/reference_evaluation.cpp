#include "bezinv/datasets/reference_evaluation.hpp"

#include <algorithm>
#include <cmath>
#include <vector>

namespace bezinv::datasets {
namespace {

// Error-free transformations in long double (Knuth's TwoSum, Dekker's TwoProduct with the split
// factor 2^32 + 1 for a 64-bit significand): a + b = s + e and a * b = p + e exactly.
void two_sum(Real a, Real b, Real& s, Real& e) {
  s = a + b;
  const Real z = s - a;
  e = (a - (s - z)) + (b - z);
}
void split(Real a, Real& hi, Real& lo) {
  constexpr Real kSplitter = 4294967297.0L;  // 2^32 + 1
  const Real c = kSplitter * a;
  hi = c - (c - a);
  lo = a - hi;
}
void two_product(Real a, Real b, Real& p, Real& e) {
  p = a * b;
  Real ah, al, bh, bl;
  split(a, ah, al);
  split(b, bh, bl);
  e = al * bl - (((p - ah * bh) - al * bh) - ah * bl);
}

// Compensated de Casteljau (Graillat, Langlois & Louvet 2009): as accurate as de Casteljau in twice
// the working precision, i.e. about 2^-64 + cond * 2^-128 relative. Outside [0,1] the condition
// number grows like (|1-t| + |t|)^n (1e4 at t = 1.3, n = 20), which plain long double would pass
// on to the "true" point at the level of a few double ulps. 1 - t = c + rho exactly (TwoSum), and
// rho * b_i joins the error term.
Real compensated_de_casteljau(std::span<const double> p, Real t) {
  const int n = static_cast<int>(p.size()) - 1;
  Real c, rho;
  two_sum(1.0L, -t, c, rho);
  std::array<Real, kMaxDegree + 1> b{}, err{};
  for (int i = 0; i <= n; ++i) b[i] = p[i];
  for (int level = 1; level <= n; ++level)
    for (int i = 0; i <= n - level; ++i) {
      Real p1, e1, p2, e2, sum, e3;
      const Real b_old = b[i];
      two_product(c, b[i], p1, e1);
      two_product(t, b[i + 1], p2, e2);
      two_sum(p1, p2, sum, e3);
      b[i] = sum;
      err[i] = c * err[i] + t * err[i + 1] + (e1 + e2 + e3 + rho * b_old);
    }
  return b[0] + err[0];
}

// p, p', p'' at t from the Bernstein coefficients; the differences are taken in long double.
struct Jet1 { Real value, first, second; };
Jet1 jet(std::span<const double> p, Real t) {
  const int n = static_cast<int>(p.size()) - 1;
  const Real c = 1 - t, s = t;
  // c^k and s^k by running products (std::pow on long double, twice per term, was most of the
  // stress tool's generation time).
  std::array<Real, kMaxDegree + 1> cp{}, sp{};
  cp[0] = sp[0] = 1;
  for (int k = 1; k <= n; ++k) cp[k] = cp[k - 1] * c, sp[k] = sp[k - 1] * s;
  auto sum = [&](int degree, auto&& coefficient) {
    Real total = 0, binomial = 1;  // C(degree, i), by C(d, i) = C(d, i-1) (d - i + 1) / i (exact)
    for (int i = 0; i <= degree; ++i) {
      if (i > 0) binomial = binomial * (degree - i + 1) / i;
      total += binomial * cp[degree - i] * sp[i] * coefficient(i);
    }
    return total;
  };
  Jet1 j{};
  j.value = compensated_de_casteljau(p, t);
  if (n >= 1)
    j.first = n * sum(n - 1, [&](int i) { return static_cast<Real>(p[i + 1]) - p[i]; });
  if (n >= 2)
    j.second = static_cast<Real>(n) * (n - 1) *
               sum(n - 2, [&](int i) { return static_cast<Real>(p[i + 2]) - 2 * static_cast<Real>(p[i + 1]) + p[i]; });
  return j;
}

// C(n, i) for n <= kMaxDegree, exact (integers below 2^64), made once: the generators evaluate
// curves millions of times, and a division per term was a third of the time.
const std::array<std::array<Real, kMaxDegree + 1>, kMaxDegree + 1>& binomials() {
  static const auto table = [] {
    std::array<std::array<Real, kMaxDegree + 1>, kMaxDegree + 1> c{};
    for (int n = 0; n <= kMaxDegree; ++n) {
      c[n][0] = 1;
      for (int i = 1; i <= n; ++i) c[n][i] = c[n][i - 1] * (n - i + 1) / i;
    }
    return c;
  }();
  return table;
}

}  // namespace

HomogeneousValue homogeneous_value(std::span<const double> coefficients, Real c, Real s) {
  const int n = static_cast<int>(coefficients.size()) - 1;
  // c^{n-i} s^i by running products, so t = inf (c = -s) needs no special case.
  std::array<Real, kMaxDegree + 1> cp{}, sp{};
  cp[0] = 1;
  sp[0] = 1;
  for (int i = 1; i <= n; ++i) { cp[i] = cp[i - 1] * c; sp[i] = sp[i - 1] * s; }
  HomogeneousValue h;
  const Real* binomial = binomials()[n].data();
  for (int i = 0; i <= n; ++i) {
    const Real term = binomial[i] * cp[n - i] * sp[i] * coefficients[i];
    h.value += term;
    h.magnitude += std::abs(term);
  }
  return h;
}

std::optional<RealPoint> reference_point(const Curve& curve, Real c, Real s, Real min_relative_denominator) {
  // homogeneous_value of the four polynomials, the basis C(n, i) c^{n-i} s^i formed once for all
  // four (the same products, so the same values).
  const int n = curve.degree();
  std::array<Real, kMaxDegree + 1> cp{}, sp{};
  cp[0] = 1;
  sp[0] = 1;
  for (int i = 1; i <= n; ++i) { cp[i] = cp[i - 1] * c; sp[i] = sp[i - 1] * s; }
  const Real* binomial = binomials()[n].data();
  HomogeneousValue X, W, Y, V;
  for (int i = 0; i <= n; ++i) {
    const Real basis = binomial[i] * cp[n - i] * sp[i];
    const Real x = basis * curve.x_num[i], w = basis * curve.x_den[i], y = basis * curve.y_num[i], v = basis * curve.y_den[i];
    X.value += x, X.magnitude += std::abs(x);
    W.value += w, W.magnitude += std::abs(w);
    Y.value += y, Y.magnitude += std::abs(y);
    V.value += v, V.magnitude += std::abs(v);
  }
  if (!(std::abs(W.value) > min_relative_denominator * W.magnitude) ||
      !(std::abs(V.value) > min_relative_denominator * V.magnitude))
    return std::nullopt;
  return RealPoint{X.value / W.value, Y.value / V.value};
}

RealPoint reference_point(const Curve& curve, Real t) {
  return {compensated_de_casteljau(curve.x_num, t) / compensated_de_casteljau(curve.x_den, t),
          compensated_de_casteljau(curve.y_num, t) / compensated_de_casteljau(curve.y_den, t)};
}

ReferenceJet reference_jet(const Curve& curve, Real t) {
  auto component = [&](std::span<const double> num, std::span<const double> den, Real& v, Real& d1, Real& d2) {
    const Jet1 N = jet(num, t), D = jet(den, t);
    v = N.value / D.value;
    d1 = (N.first - D.first * v) / D.value;
    d2 = (N.second - 2 * D.first * d1 - D.second * v) / D.value;
  };
  ReferenceJet j;
  component(curve.x_num, curve.x_den, j.p.x, j.d1.x, j.d2.x);
  component(curve.y_num, curve.y_den, j.p.y, j.d1.y, j.d2.y);
  return j;
}

Real denominator_conditioning(const Curve& curve, Real t) {
  const auto W = homogeneous_value(curve.x_den, 1 - t, t), V = homogeneous_value(curve.y_den, 1 - t, t);
  return std::min(std::abs(W.value) / W.magnitude, std::abs(V.value) / V.magnitude);
}

Real evaluation_scale(const Curve& curve, Real t) {
  const Real c = 1 - t, s = t;
  auto coordinate = [&](std::span<const double> num, std::span<const double> den) {
    const auto N = homogeneous_value(num, c, s), D = homogeneous_value(den, c, s);
    return (N.magnitude + std::abs(N.value / D.value) * D.magnitude) / std::abs(D.value);
  };
  return std::max(coordinate(curve.x_num, curve.x_den), coordinate(curve.y_num, curve.y_den));
}

double control_diagonal(const Curve& curve) {
  std::vector<RealPoint> points;
  for (std::size_t i = 0; i < curve.x_num.size(); ++i)
    if (curve.x_den[i] != 0.0 && curve.y_den[i] != 0.0)
      points.push_back({static_cast<Real>(curve.x_num[i]) / curve.x_den[i],
                        static_cast<Real>(curve.y_num[i]) / curve.y_den[i]});
  points.push_back(reference_point(curve, 0.0L));
  points.push_back(reference_point(curve, 1.0L));
  Real lo_x = points[0].x, hi_x = lo_x, lo_y = points[0].y, hi_y = lo_y;
  for (const auto& p : points) {
    lo_x = std::min(lo_x, p.x); hi_x = std::max(hi_x, p.x);
    lo_y = std::min(lo_y, p.y); hi_y = std::max(hi_y, p.y);
  }
  return static_cast<double>(std::hypot(hi_x - lo_x, hi_y - lo_y));
}

Point rounded(RealPoint p) { return {static_cast<double>(p.x), static_cast<double>(p.y)}; }

// sqrt of the sum of squares rather than hypot (several times slower in long double): the dense
// sampling calls this millions of times, and long double's exponent range cannot overflow here.
Real distance(RealPoint a, RealPoint b) {
  const Real dx = a.x - b.x, dy = a.y - b.y;
  return std::sqrt(dx * dx + dy * dy);
}
Real distance(RealPoint a, Point b) { return distance(a, RealPoint{b.x, b.y}); }

}  // namespace bezinv::datasets
