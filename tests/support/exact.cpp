#include "support/exact.hpp"

#include <cmath>
#include <stdexcept>
#include <utility>

namespace bezinv::exact {

Poly to_exact(std::span<const double> c) {
  Poly out;
  out.reserve(c.size());
  for (double v : c) out.emplace_back(v);  // mpq_class(double) is exact
  return out;
}

std::vector<double> to_double(const Poly& c) {
  std::vector<double> out;
  out.reserve(c.size());
  for (const mpq_class& v : c) out.push_back(nearest_double(v));
  return out;
}

double nearest_double(const mpq_class& x) {
  // mpq_get_d truncates towards zero; the nearest double is that one or its neighbour away from 0.
  const double d = x.get_d();
  if (!std::isfinite(d)) return d;
  const double away = std::nextafter(d, x < 0 ? -INFINITY : INFINITY);
  if (!std::isfinite(away)) return d;
  return abs(mpq_class(away) - x) < abs(mpq_class(d) - x) ? away : d;
}

mpq_class abs(const mpq_class& x) { return x < 0 ? mpq_class(-x) : x; }

mpq_class max_abs(const Matrix& m) {
  mpq_class best = 0;
  for (const mpq_class& v : m.a)
    if (abs(v) > best) best = abs(v);
  return best;
}

mpz_class binomial(int n, int k) {
  if (k < 0 || k > n) return 0;
  mpz_class r;
  mpz_bin_uiui(r.get_mpz_t(), static_cast<unsigned long>(n), static_cast<unsigned long>(k));
  return r;
}

namespace {

// mpq_class(num, den) is not canonical until told so; arithmetic needs canonical operands.
mpq_class ratio(const mpz_class& num, const mpz_class& den) {
  mpq_class r(num, den);
  r.canonicalize();
  return r;
}

mpq_class power(const mpq_class& x, int e) {
  mpq_class r = 1;
  for (int i = 0; i < e; ++i) r *= x;
  return r;
}

}  // namespace

std::vector<mpq_class> bernstein_basis(int n, const mpq_class& t) {
  // beta_i^{(n)}(t) = C(n,i) (1-t)^{n-i} t^i
  std::vector<mpq_class> out(static_cast<std::size_t>(n) + 1);
  const mpq_class s = 1 - t;
  for (int i = 0; i <= n; ++i) out[i] = mpq_class(binomial(n, i)) * power(s, n - i) * power(t, i);
  return out;
}

mpq_class bernstein_value(const Poly& p, const mpq_class& t) {
  const int n = static_cast<int>(p.size()) - 1;
  const std::vector<mpq_class> beta = bernstein_basis(n, t);
  mpq_class sum = 0;
  for (int i = 0; i <= n; ++i) sum += p[i] * beta[i];
  return sum;
}

Poly power_from_bernstein(const Poly& p) {
  // C(n,i) t^i (1-t)^{n-i} = C(n,i) sum_j C(n-i,j) (-1)^j t^{i+j}
  const int n = static_cast<int>(p.size()) - 1;
  Poly a(static_cast<std::size_t>(n) + 1, mpq_class(0));
  for (int i = 0; i <= n; ++i)
    for (int j = 0; j <= n - i; ++j) {
      mpq_class term = p[i] * mpq_class(binomial(n, i) * binomial(n - i, j));
      if (j % 2) term = -term;
      a[i + j] += term;
    }
  return a;
}

Poly bernstein_from_power(const Poly& a, int n) {
  // t^k = sum_{i=k}^{n} C(i,k) / C(n,k) beta_i^{(n)}(t)
  if (n < static_cast<int>(a.size()) - 1) throw std::invalid_argument("bernstein_from_power: degree too low");
  Poly c(static_cast<std::size_t>(n) + 1, mpq_class(0));
  for (int k = 0; k < static_cast<int>(a.size()); ++k)
    for (int i = k; i <= n; ++i) c[i] += a[k] * ratio(binomial(i, k), binomial(n, k));
  return c;
}

mpq_class power_leading_coefficient(const Poly& p) { return power_from_bernstein(p).back(); }

Poly derivative(const Poly& p) {
  const int n = static_cast<int>(p.size()) - 1;
  if (n == 0) return Poly{mpq_class(0)};
  const Poly a = power_from_bernstein(p);
  Poly da(static_cast<std::size_t>(n));
  for (int k = 1; k <= n; ++k) da[k - 1] = a[k] * k;
  return bernstein_from_power(da, n - 1);
}

Poly elevate(const Poly& p, int degree) { return bernstein_from_power(power_from_bernstein(p), degree); }

Poly product(const Poly& a, const Poly& b) {
  const Poly pa = power_from_bernstein(a), pb = power_from_bernstein(b);
  Poly c(pa.size() + pb.size() - 1, mpq_class(0));
  for (std::size_t i = 0; i < pa.size(); ++i)
    for (std::size_t j = 0; j < pb.size(); ++j) c[i + j] += pa[i] * pb[j];
  return bernstein_from_power(c, static_cast<int>(c.size()) - 1);
}

Matrix bezout_recurrence(const Poly& p, const Poly& q) {
  // Paper Sect. 2.1, verbatim with 1-based B and 0-based p, q:
  //   B[i,1]   = (n/i) (p_i q_0 - p_0 q_i)                                 i = 1..n
  //   B[n,j+1] = (n/(n-j)) (p_n q_j - p_j q_n)                             j = 1..n-1
  //   B[i,j+1] = n^2/(i(n-j)) (p_i q_j - p_j q_i) + j(n-i)/(i(n-j)) B[i+1,j]   i, j = 1..n-1
  const int n = static_cast<int>(p.size()) - 1;
  Matrix b(n, n);
  auto B = [&](int i, int j) -> mpq_class& { return b(i - 1, j - 1); };
  for (int i = 1; i <= n; ++i) B(i, 1) = ratio(n, i) * (p[i] * q[0] - p[0] * q[i]);
  for (int j = 1; j <= n - 1; ++j) B(n, j + 1) = ratio(n, n - j) * (p[n] * q[j] - p[j] * q[n]);
  for (int j = 1; j <= n - 1; ++j)
    for (int i = 1; i <= n - 1; ++i)
      B(i, j + 1) = ratio(n * n, i * (n - j)) * (p[i] * q[j] - p[j] * q[i]) +
                    ratio(j * (n - i), i * (n - j)) * B(i + 1, j);
  return b;
}

Matrix solve(Matrix a, Matrix r) {
  const int n = a.rows;
  if (a.cols != n || r.rows != n) throw std::invalid_argument("solve: shapes");
  for (int c = 0; c < n; ++c) {
    int pivot = c;
    while (pivot < n && a(pivot, c) == 0) ++pivot;
    if (pivot == n) throw std::runtime_error("solve: singular matrix");
    if (pivot != c) {
      for (int j = 0; j < n; ++j) std::swap(a(c, j), a(pivot, j));
      for (int j = 0; j < r.cols; ++j) std::swap(r(c, j), r(pivot, j));
    }
    for (int i = c + 1; i < n; ++i) {
      if (a(i, c) == 0) continue;
      const mpq_class f = a(i, c) / a(c, c);
      for (int j = c; j < n; ++j) a(i, j) -= f * a(c, j);
      for (int j = 0; j < r.cols; ++j) r(i, j) -= f * r(c, j);
    }
  }
  Matrix x(n, r.cols);
  for (int i = n - 1; i >= 0; --i)
    for (int j = 0; j < r.cols; ++j) {
      mpq_class s = r(i, j);
      for (int k = i + 1; k < n; ++k) s -= a(i, k) * x(k, j);
      x(i, j) = s / a(i, i);
    }
  return x;
}

namespace {

Matrix transpose(const Matrix& m) {
  Matrix t(m.cols, m.rows);
  for (int i = 0; i < m.rows; ++i)
    for (int j = 0; j < m.cols; ++j) t(j, i) = m(i, j);
  return t;
}

}  // namespace

Matrix bezout_from_definition(const Poly& p, const Poly& q) {
  const int n = static_cast<int>(p.size()) - 1;
  // Integer nodes keep the basis matrices integral; t_k != s_l for every pair.
  std::vector<mpq_class> t(n), s(n);
  for (int k = 0; k < n; ++k) {
    t[k] = k;
    s[k] = -1 - k;
  }
  Matrix bt(n, n), bs(n, n), l(n, n);
  std::vector<mpq_class> pt(n), qt(n), ps(n), qs(n);
  for (int k = 0; k < n; ++k) {
    const std::vector<mpq_class> bk = bernstein_basis(n - 1, t[k]), sk = bernstein_basis(n - 1, s[k]);
    for (int i = 0; i < n; ++i) {
      bt(k, i) = bk[i];
      bs(k, i) = sk[i];
    }
    pt[k] = bernstein_value(p, t[k]);
    qt[k] = bernstein_value(q, t[k]);
    ps[k] = bernstein_value(p, s[k]);
    qs[k] = bernstein_value(q, s[k]);
  }
  for (int k = 0; k < n; ++k)
    for (int m = 0; m < n; ++m) l(k, m) = (pt[k] * qs[m] - ps[m] * qt[k]) / (t[k] - s[m]);
  // L = Bt B Bs^T:  X = Bt^{-1} L = B Bs^T,  then Bs B^T = X^T.
  const Matrix x = solve(bt, l);
  return transpose(solve(bs, transpose(x)));
}

Matrix sylvester(const Poly& p, const Poly& q) {
  const int m = static_cast<int>(p.size()) - 1, k = static_cast<int>(q.size()) - 1;
  const int size = m + k;
  Matrix s(size, size);
  auto unit = [](int degree, int j) {
    Poly e(static_cast<std::size_t>(degree) + 1, mpq_class(0));
    e[j] = 1;
    return e;
  };
  for (int j = 0; j < k; ++j) {
    const Poly col = product(unit(k - 1, j), p);
    for (int i = 0; i < size; ++i) s(i, j) = col[i];
  }
  for (int j = 0; j < m; ++j) {
    const Poly col = product(unit(m - 1, j), q);
    for (int i = 0; i < size; ++i) s(i, k + j) = col[i];
  }
  return s;
}

std::array<mpq_class, 2> RationalCurve::point(const mpq_class& t) const {
  return {bernstein_value(x_num, t) / bernstein_value(x_den, t), bernstein_value(y_num, t) / bernstein_value(y_den, t)};
}

std::array<mpq_class, 2> RationalCurve::tangent(const mpq_class& t) const {
  // (u/w)' = (u' w - u w') / w^2
  auto quotient_rule = [&](const Poly& u, const Poly& w) {
    const mpq_class uv = bernstein_value(u, t), wv = bernstein_value(w, t);
    const mpq_class du = bernstein_value(derivative(u), t), dw = bernstein_value(derivative(w), t);
    return mpq_class((du * wv - uv * dw) / (wv * wv));
  };
  return {quotient_rule(x_num, x_den), quotient_rule(y_num, y_den)};
}

}  // namespace bezinv::exact
