#include "bezinv/bernstein.hpp"

#include <array>
#include <cassert>
#include <cmath>

namespace bezinv {
namespace {
// de Casteljau needs a scratch copy of the coefficients; the Sylvester path works at degree
// up to 2 * kMaxDegree - 1, so this bounds every polynomial bezinv evaluates.
constexpr int kMaxCoefficients = 128;
}  // namespace

namespace {
// Pascal's triangle in 128-bit integers is exact for n <= 127 (C(127,63) < 2^127); each entry is
// then rounded once to double, so binomial() is correctly rounded (exact while C(n,k) < 2^53).
constexpr int kBinomialTableRows = 128;
struct BinomialTable {
  std::array<double, kBinomialTableRows*(kBinomialTableRows + 1) / 2> value;
  BinomialTable() {
    std::array<unsigned __int128, kBinomialTableRows> row{};
    row[0] = 1;
    for (int n = 0; n < kBinomialTableRows; ++n) {
      if (n > 0)
        for (int k = n; k >= 1; --k) row[k] += row[k - 1];
      for (int k = 0; k <= n; ++k) value[n * (n + 1) / 2 + k] = static_cast<double>(row[k]);
    }
  }
};
}  // namespace

double binomial(int n, int k) {
  if (k < 0 || k > n) return 0.0;
  if (n < kBinomialTableRows) {
    static const BinomialTable table;
    return table.value[n * (n + 1) / 2 + k];
  }
  if (k > n - k) k = n - k;
  double r = 1.0;
  for (int i = 1; i <= k; ++i) r = r * (n - k + i) / i;
  return r;
}

void bernstein_basis(int n, double t, std::span<double> out) {
  assert(static_cast<int>(out.size()) >= n + 1);
  // Build degree j from degree j-1: beta_i^{(j)} = (1-t) beta_i^{(j-1)} + t beta_{i-1}^{(j-1)}.
  // Only products and sums of the two affine factors, so no binomials and no cancellation on [0,1].
  const double s = 1.0 - t;
  out[0] = 1.0;
  for (int j = 1; j <= n; ++j) {
    out[j] = t * out[j - 1];
    for (int i = j - 1; i >= 1; --i) out[i] = s * out[i] + t * out[i - 1];
    out[0] = s * out[0];
  }
}

double bernstein_value(std::span<const double> c, double t) {
  const int n = static_cast<int>(c.size()) - 1;
  assert(n >= 0 && n < kMaxCoefficients);
  std::array<double, kMaxCoefficients> b;
  for (int i = 0; i <= n; ++i) b[i] = c[i];
  const double s = 1.0 - t;
  for (int r = 1; r <= n; ++r)
    for (int i = 0; i <= n - r; ++i) b[i] = s * b[i] + t * b[i + 1];
  return b[0];
}

BernsteinJet bernstein_jet(std::span<const double> c, double t) {
  const int n = static_cast<int>(c.size()) - 1;
  assert(n >= 0 && n < kMaxCoefficients);
  if (n == 0) return {c[0], 0.0, 0.0};
  std::array<double, kMaxCoefficients> b{};  // zeroed: GCC cannot see that only b[0..n] is read
  for (int i = 0; i <= n; ++i) b[i] = c[i];
  const double s = 1.0 - t;
  // Run de Casteljau until three points remain, then bernstein_jet_from_last_points.
  for (int r = 1; r <= n - 2; ++r)
    for (int i = 0; i <= n - r; ++i) b[i] = s * b[i] + t * b[i + 1];
  return bernstein_jet_from_last_points(n, t, b[0], b[1], b[2]);
}

double power_leading_coefficient(std::span<const double> c) {
  const int n = static_cast<int>(c.size()) - 1;
  double sum = 0.0;
  for (int i = 0; i <= n; ++i) sum += ((n - i) % 2 ? -1.0 : 1.0) * binomial(n, i) * c[i];
  return sum;
}

double power_leading_bound(std::span<const double> c) {
  const int n = static_cast<int>(c.size()) - 1;
  double sum = 0.0;
  for (int i = 0; i <= n; ++i) sum += binomial(n, i) * std::abs(c[i]);
  return sum;
}

void elevate_degree(std::span<const double> p, std::span<double> q) {
  const int n = static_cast<int>(p.size()) - 1;
  assert(static_cast<int>(q.size()) == n + 2);
  q[0] = p[0];
  q[n + 1] = p[n];
  for (int i = 1; i <= n; ++i) {
    const double a = static_cast<double>(i) / (n + 1);
    q[i] = a * p[i - 1] + (1.0 - a) * p[i];
  }
}

void reduce_degree(std::span<const double> p, std::span<double> r) {
  const int n = static_cast<int>(p.size()) - 1;
  assert(n >= 1 && static_cast<int>(r.size()) == n);
  // Inverting p_i = (i/n) r_{i-1} + (1 - i/n) r_i. Forwards: r_i = (n p_i - i r_{i-1}) / (n - i),
  // whose amplification i/(n-i) is small for i < n/2; backwards: r_{i-1} = (n p_i - (n-i) r_i) / i,
  // small for i > n/2. Each half is taken from the direction that keeps it small (Farin, Ch. 6).
  const int half = (n - 1) / 2;  // forward fills 0..half, backward fills half+1..n-1
  r[0] = p[0];
  for (int i = 1; i <= half; ++i) r[i] = (n * p[i] - i * r[i - 1]) / (n - i);
  if (n - 1 > half) {
    r[n - 1] = p[n];
    for (int i = n - 1; i >= half + 2; --i) r[i - 1] = (n * p[i] - (n - i) * r[i]) / i;
  }
}

}  // namespace bezinv
