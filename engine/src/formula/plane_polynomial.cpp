#include "bezinv/plane_polynomial.hpp"

#include <cassert>
#include <cstddef>
#include <stdexcept>
#include <utility>

namespace bezinv {

std::array<double, 2> PlaneFrame::to_frame(double x, double y) const {
  const double dx = x - centre[0], dy = y - centre[1];
  return {(cos_rotation * dx - sin_rotation * dy) / scale_u, (sin_rotation * dx + cos_rotation * dy) / scale_v};
}

std::array<double, 2> PlaneFrame::from_frame(double u, double v) const {
  // R is a rotation: its inverse is its transpose.
  const double a = scale_u * u, b = scale_v * v;
  return {centre[0] + cos_rotation * a + sin_rotation * b, centre[1] - sin_rotation * a + cos_rotation * b};
}

std::array<double, 3> PlaneFrame::from_frame_homogeneous(double u, double v, double w) const {
  const double a = scale_u * u, b = scale_v * v;
  return {centre[0] * w + cos_rotation * a + sin_rotation * b, centre[1] * w - sin_rotation * a + cos_rotation * b, w};
}

PlanePolynomial::PlanePolynomial(int degree, PlaneFrame frame, std::vector<double> coefficients)
    : degree_(degree), frame_(frame), coefficients_(std::move(coefficients)) {
  if (degree < 0 || coefficients_.size() != static_cast<std::size_t>(size(degree)))
    throw std::invalid_argument("PlanePolynomial: degree and number of coefficients disagree");
}

namespace {

// The homogenized Chebyshev terms T_k(a, w) = w^k T_k(a / w), k = 0..d, into t (room for d + 1):
// T_{k+1} = 2 a T_k - w^2 T_{k-1}.
void chebyshev_terms(int d, double a, double w, double* t) {
  t[0] = 1.0;
  if (d >= 1) t[1] = a;
  const double w2 = w * w;
  for (int k = 1; k < d; ++k) t[k + 1] = 2.0 * a * t[k] - w2 * t[k - 1];
}

// Up to this degree the terms are kept on the stack (every formula bezinv computes): evaluating
// a formula allocates nothing.
constexpr int kStackDegree = 64;

// T_i(u, w), T_j(v, w) and w^k, k = 0..d: the tables every term T_i(u) T_j(v) w^(d - i - j) is
// a product from (on the stack up to kStackDegree).
class TermTables {
 public:
  TermTables(int d, double u, double v, double w) {
    if (d > kStackDegree) heap_.resize(3 * static_cast<std::size_t>(d + 1));
    tu = d > kStackDegree ? heap_.data() : stack_.data();
    tv = tu + d + 1;
    wp = tv + d + 1;
    chebyshev_terms(d, u, w, tu);
    chebyshev_terms(d, v, w, tv);
    wp[0] = 1.0;
    for (int k = 0; k < d; ++k) wp[k + 1] = wp[k] * w;
  }
  double* tu;
  double* tv;
  double* wp;

 private:
  std::array<double, 3 * (kStackDegree + 1)> stack_;
  std::vector<double> heap_;
};

}  // namespace

void PlanePolynomial::homogeneous_terms(int degree, double u, double v, double w, std::span<double> out) {
  assert(out.size() >= static_cast<std::size_t>(size(degree)));
  const TermTables t(degree, u, v, w);
  for (int k = 0; k <= degree; ++k)
    for (int j = 0; j <= k; ++j)
      out[static_cast<std::size_t>(index(k - j, j))] = t.tu[k - j] * t.tv[j] * t.wp[degree - k];
}

double PlanePolynomial::homogeneous(double u, double v, double w) const {
  const TermTables t(degree_, u, v, w);
  // sum_k w^(d-k) sum_j c_(k-j, j) T_(k-j)(u) T_j(v), in index() order.
  double sum = 0.0;
  std::size_t e = 0;
  for (int k = 0; k <= degree_; ++k) {
    double row = 0.0;
    for (int j = 0; j <= k; ++j) row += coefficients_[e++] * t.tu[k - j] * t.tv[j];
    sum += row * t.wp[degree_ - k];
  }
  return sum;
}

double PlanePolynomial::at_frame(double u, double v) const { return homogeneous(u, v, 1.0); }

double PlanePolynomial::operator()(double x, double y) const {
  const auto [u, v] = frame_.to_frame(x, y);
  return at_frame(u, v);
}

namespace {

// A dense polynomial in x and y of total degree <= d: a[index(i, j)] multiplies x^i y^j.
using Dense = std::vector<long double>;

// p times (a x + b y + c), p of total degree < d (both stored with p's size).
Dense times_linear(const Dense& p, int d, long double a, long double b, long double c) {
  Dense out(p.size(), 0.0L);
  for (int k = 0; k < d; ++k)
    for (int j = 0; j <= k; ++j) {
      const long double e = p[static_cast<std::size_t>(PlanePolynomial::index(k - j, j))];
      if (e == 0.0L) continue;
      out[static_cast<std::size_t>(PlanePolynomial::index(k - j + 1, j))] += a * e;
      out[static_cast<std::size_t>(PlanePolynomial::index(k - j, j + 1))] += b * e;
      out[static_cast<std::size_t>(PlanePolynomial::index(k - j, j))] += c * e;
    }
  return out;
}

// p q, both of total degree <= d, the product's terms above d dropped (they are zero when the
// degrees add up to at most d, as for T_i(u) T_j(v) with i + j <= d).
void add_product(const Dense& p, const Dense& q, int d, long double scale, Dense& out) {
  for (int k1 = 0; k1 <= d; ++k1)
    for (int j1 = 0; j1 <= k1; ++j1) {
      const long double a = p[static_cast<std::size_t>(PlanePolynomial::index(k1 - j1, j1))];
      if (a == 0.0L) continue;
      for (int k2 = 0; k1 + k2 <= d; ++k2)
        for (int j2 = 0; j2 <= k2; ++j2) {
          const long double b = q[static_cast<std::size_t>(PlanePolynomial::index(k2 - j2, j2))];
          if (b != 0.0L)
            out[static_cast<std::size_t>(PlanePolynomial::index(k1 - j1 + k2 - j2, j1 + j2))] += scale * a * b;
        }
    }
}

}  // namespace

std::vector<double> PlanePolynomial::monomials() const {
  const int d = degree_;
  const auto n = static_cast<std::size_t>(size(d));
  // u = a_u x + b_u y + c_u and v alike, from to_frame.
  const long double su = 1.0L / static_cast<long double>(frame_.scale_u);
  const long double sv = 1.0L / static_cast<long double>(frame_.scale_v);
  const long double co = frame_.cos_rotation, si = frame_.sin_rotation;
  const long double cx = frame_.centre[0], cy = frame_.centre[1];
  const long double au = co * su, bu = -si * su, cu = -(co * cx - si * cy) * su;
  const long double av = si * sv, bv = co * sv, cv = -(si * cx + co * cy) * sv;
  // T_k(u) and T_k(v) as polynomials in x and y, by T_{k+1} = 2 u T_k - T_{k-1}.
  std::vector<Dense> tu(d + 1, Dense(n, 0.0L)), tv(d + 1, Dense(n, 0.0L));
  tu[0][0] = tv[0][0] = 1.0L;
  for (int k = 0; k < d; ++k) {
    const long double twice = k == 0 ? 1.0L : 2.0L;  // T_1 = u
    tu[k + 1] = times_linear(tu[k], k + 1, twice * au, twice * bu, twice * cu);
    tv[k + 1] = times_linear(tv[k], k + 1, twice * av, twice * bv, twice * cv);
    if (k >= 1)
      for (std::size_t e = 0; e < n; ++e) {
        tu[k + 1][e] -= tu[k - 1][e];
        tv[k + 1][e] -= tv[k - 1][e];
      }
  }
  // sum_i T_i(u) (sum_j c_ij T_j(v)): d + 1 products instead of one per term.
  Dense out(n, 0.0L);
  for (int i = 0; i <= d; ++i) {
    Dense inner(n, 0.0L);
    for (int j = 0; i + j <= d; ++j) {
      const long double c = coefficients_[static_cast<std::size_t>(index(i, j))];
      for (std::size_t e = 0; e < n; ++e) inner[e] += c * tv[j][e];
    }
    add_product(tu[i], inner, d, 1.0L, out);
  }
  return {out.begin(), out.end()};
}

}  // namespace bezinv
