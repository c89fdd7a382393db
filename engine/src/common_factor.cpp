#include "common_factor.hpp"

#include <gmpxx.h>

#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <span>
#include <vector>

namespace bezinv::detail {
namespace {

// ---- modulo the prime 2^61 - 1 (the filter) ---------------------------------------------------------

using u64 = std::uint64_t;
using u128 = unsigned __int128;
constexpr u64 kPrime = (u64{1} << 61) - 1;

u64 reduce(u128 x) {  // 2^61 = 1 (mod kPrime): fold the high bits onto the low ones
  u64 r = static_cast<u64>(x & kPrime) + static_cast<u64>(x >> 61);
  r = (r & kPrime) + (r >> 61);
  return r >= kPrime ? r - kPrime : r;
}
u64 mul(u64 a, u64 b) { return reduce(static_cast<u128>(a) * b); }
u64 add(u64 a, u64 b) { return reduce(static_cast<u128>(a) + b); }
u64 sub(u64 a, u64 b) { return add(a, kPrime - b); }
u64 power(u64 a, u64 e) {
  u64 r = 1;
  for (; e > 0; e >>= 1, a = mul(a, a))
    if (e & 1) r = mul(r, a);
  return r;
}
u64 inverse(u64 a) { return power(a, kPrime - 2); }  // Fermat

// A finite double m 2^e (m a 53-bit integer) modulo the prime; 2 has order 61, so 2^e = 2^(e mod 61).
u64 residue(double x) {
  if (x == 0.0) return 0;
  int e = 0;
  const double m = std::frexp(std::abs(x), &e);
  const u64 mantissa = static_cast<u64>(std::ldexp(m, 53));
  const int shift = ((e - 53) % 61 + 61) % 61;
  const u64 r = mul(mantissa % kPrime, u64{1} << shift);
  return x < 0 ? sub(0, r) : r;
}

using ModPoly = std::vector<u64>;  // power basis, a_0 first

// a_k = C(n,k) sum_{i<=k} (-1)^(k-i) C(k,i) b_i: the power-basis coefficients of sum_i b_i beta_i^(n).
ModPoly power_residues(std::span<const double> bernstein) {
  const int n = static_cast<int>(bernstein.size()) - 1;
  std::vector<std::vector<u64>> c(n + 1, std::vector<u64>(n + 1, 0));  // Pascal's triangle, C(32,16) < 2^61
  for (int i = 0; i <= n; ++i) {
    c[i][0] = c[i][i] = 1;
    for (int k = 1; k < i; ++k) c[i][k] = add(c[i - 1][k - 1], c[i - 1][k]);
  }
  ModPoly a(n + 1, 0);
  for (int k = 0; k <= n; ++k) {
    u64 s = 0;
    for (int i = 0; i <= k; ++i) {
      const u64 term = mul(c[k][i], residue(bernstein[i]));
      s = (k - i) % 2 == 0 ? add(s, term) : sub(s, term);
    }
    a[k] = mul(c[n][k], s);
  }
  return a;
}

void trim(ModPoly& a) {
  while (!a.empty() && a.back() == 0) a.pop_back();
}

// gcd of a and b modulo the prime, by Euclid; empty when both are 0.
ModPoly gcd(ModPoly a, ModPoly b) {
  trim(a);
  trim(b);
  while (!b.empty()) {
    const u64 lead_inverse = inverse(b.back());
    while (a.size() >= b.size()) {  // a <- a mod b
      const u64 f = mul(a.back(), lead_inverse);
      const std::size_t shift = a.size() - b.size();
      for (std::size_t i = 0; i < b.size(); ++i) a[shift + i] = sub(a[shift + i], mul(f, b[i]));
      trim(a);
    }
    std::swap(a, b);
  }
  return a;
}

// Degree of the gcd of the polynomials modulo the prime (-1 when all are 0).
int gcd_degree_modulo_prime(std::initializer_list<std::span<const double>> polynomials) {
  ModPoly g;
  for (const auto& p : polynomials) g = gcd(g, power_residues(p));
  return static_cast<int>(g.size()) - 1;
}

// ---- over Q (GMP) ------------------------------------------------------------------------------------

using Poly = std::vector<mpq_class>;  // power basis, a_0 first

mpz_class exact_binomial(int n, int k) {
  mpz_class c;
  mpz_bin_uiui(c.get_mpz_t(), static_cast<unsigned long>(n), static_cast<unsigned long>(k));
  return c;
}

Poly power_coefficients(std::span<const double> bernstein) {
  const int n = static_cast<int>(bernstein.size()) - 1;
  Poly a(n + 1);
  for (int k = 0; k <= n; ++k) {
    mpq_class s = 0;
    for (int i = 0; i <= k; ++i) {
      const mpq_class term = mpq_class(exact_binomial(k, i)) * mpq_class(bernstein[i]);  // a double is exact in mpq
      if ((k - i) % 2 == 0) s += term; else s -= term;
    }
    a[k] = mpq_class(exact_binomial(n, k)) * s;
  }
  return a;
}

void trim(Poly& a) {
  while (!a.empty() && a.back() == 0) a.pop_back();
}

// a = quotient * b + remainder; b non-zero and trimmed.
void divide(Poly a, const Poly& b, Poly& quotient, Poly& remainder) {
  trim(a);
  quotient.assign(a.size() >= b.size() ? a.size() - b.size() + 1 : 0, mpq_class(0));
  while (a.size() >= b.size()) {
    const mpq_class f = a.back() / b.back();
    const std::size_t shift = a.size() - b.size();
    quotient[shift] = f;
    for (std::size_t i = 0; i < b.size(); ++i) a[shift + i] -= f * b[i];
    a.pop_back();  // cancelled exactly
    trim(a);
  }
  remainder = a;
}

// Monic gcd over Q; empty when both are 0.
Poly gcd(Poly a, Poly b) {
  trim(a);
  trim(b);
  Poly quotient, remainder;
  while (!b.empty()) {
    divide(a, b, quotient, remainder);
    a = std::move(b);
    b = std::move(remainder);
  }
  if (!a.empty()) {
    const mpq_class lead = a.back();
    for (mpq_class& c : a) c /= lead;
  }
  return a;
}

// p / g at Bernstein degree m (deg p/g <= m): b_i = sum_{k<=i} C(i,k) / C(m,k) a_k, rounded once.
std::vector<double> bernstein_quotient(std::span<const double> p, const Poly& g, int m) {
  Poly quotient, remainder;
  divide(power_coefficients(p), g, quotient, remainder);
  std::vector<double> b(m + 1);
  for (int i = 0; i <= m; ++i) {
    mpq_class s = 0;
    for (int k = 0; k <= i && k < static_cast<int>(quotient.size()); ++k)
      s += mpq_class(exact_binomial(i, k)) / mpq_class(exact_binomial(m, k)) * quotient[k];
    b[i] = s.get_d();
  }
  return b;
}

}  // namespace

Curve without_common_factor(const Curve& curve) {
  const int n = curve.degree();
  if (n < 2) return curve;
  Curve out = curve;
  if (curve.common_denominator()) {
    if (gcd_degree_modulo_prime({curve.x_num, curve.y_num, curve.x_den}) < 1) return curve;
    const Poly g = gcd(gcd(power_coefficients(curve.x_num), power_coefficients(curve.y_num)),
                       power_coefficients(curve.x_den));
    const int m = n - (static_cast<int>(g.size()) - 1);
    if (g.size() < 2 || m < 1) return curve;
    out.x_num = bernstein_quotient(curve.x_num, g, m);
    out.y_num = bernstein_quotient(curve.y_num, g, m);
    out.x_den = bernstein_quotient(curve.x_den, g, m);
    out.y_den = out.x_den;
    return out;
  }
  const bool x_factor = gcd_degree_modulo_prime({curve.x_num, curve.x_den}) >= 1;
  const bool y_factor = gcd_degree_modulo_prime({curve.y_num, curve.y_den}) >= 1;
  if (!x_factor && !y_factor) return curve;
  const Poly one{mpq_class(1)};
  const Poly gx = x_factor ? gcd(power_coefficients(curve.x_num), power_coefficients(curve.x_den)) : one;
  const Poly gy = y_factor ? gcd(power_coefficients(curve.y_num), power_coefficients(curve.y_den)) : one;
  // Each coordinate at its own degree, both written at the larger one.
  const int m = n - std::min(static_cast<int>(gx.size()), static_cast<int>(gy.size())) + 1;
  if (gx.size() < 2 && gy.size() < 2) return curve;
  if (m < 1) return curve;
  out.x_num = bernstein_quotient(curve.x_num, gx, m);
  out.x_den = bernstein_quotient(curve.x_den, gx, m);
  out.y_num = bernstein_quotient(curve.y_num, gy, m);
  out.y_den = bernstein_quotient(curve.y_den, gy, m);
  return out;
}

}  // namespace bezinv::detail
