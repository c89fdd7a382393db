#include "bezinv/singular_points.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>
#include <string>

#include "bernstein_arithmetic.hpp"
#include "bezinv/bernstein.hpp"
#include "formula/homogeneous_curve.hpp"
#include "plan_data.hpp"

namespace bezinv {

const char* to_string(BasePointKind kind) {
  switch (kind) {
    case BasePointKind::double_point: return "double_point";
    case BasePointKind::isolated_point: return "isolated_point";
    case BasePointKind::cusp: return "cusp";
    case BasePointKind::multiple_point: return "multiple_point";
    case BasePointKind::simple: return "simple";
  }
  return "?";
}

namespace {

using detail::BernsteinPoly;
using Complex = std::complex<double>;

// Roots of M(P(t)) that are one point of the curve (frame units, the curve's box is ~[-1, 1]^2),
// parameters that are one (a cusp's double root splits by ~sqrt(eps)), and a point that is real.
constexpr double kSamePoint = 1e-6;
constexpr double kSameParameter = 1e-5;
constexpr double kRealPoint = 1e-6;

// m(t) = M(P(t)) W(t)^d in the Bernstein basis of degree n d: the Chebyshev terms homogenized,
// T_{k+1}(U, W) = 2 U T_k - W^2 T_{k-1}, multiplied out exactly in the Bernstein basis.
BernsteinPoly composed(const PlanePolynomial& m, const detail::HomogeneousCurve& curve) {
  using detail::combine;
  using detail::product;
  using detail::scaled;
  const int d = m.degree();
  const BernsteinPoly one{1.0}, w2 = product(curve.w, curve.w);
  std::vector<BernsteinPoly> tu{one, curve.u}, tv{one, curve.v}, wp{one, curve.w};
  for (int k = 1; k < d; ++k) {
    tu.push_back(combine(scaled(product(curve.u, tu[k]), 2.0), product(w2, tu[k - 1]), -1.0));
    tv.push_back(combine(scaled(product(curve.v, tv[k]), 2.0), product(w2, tv[k - 1]), -1.0));
    wp.push_back(product(wp[k], curve.w));
  }
  BernsteinPoly sum(static_cast<std::size_t>(curve.degree() * d + 1), 0.0);
  const auto c = m.coefficients();
  for (int i = 0; i <= d; ++i)
    for (int j = 0; i + j <= d; ++j) {
      const double cij = c[static_cast<std::size_t>(PlanePolynomial::index(i, j))];
      if (cij != 0.0) sum = combine(sum, product(product(tu[i], tv[j]), wp[d - i - j]), cij);
    }
  return sum;
}

// de Casteljau at a complex parameter (extrapolating outside [0, 1]).
Complex value(const BernsteinPoly& p, Complex t) {
  std::vector<Complex> b(p.begin(), p.end());
  for (std::size_t r = 1; r < b.size(); ++r)
    for (std::size_t i = 0; i + r < b.size(); ++i) b[i] = (1.0 - t) * b[i] + t * b[i + 1];
  return b.empty() ? Complex{} : b[0];
}

// The roots of p (Bernstein, degree L) over C, t = infinity included as +inf. With s = t / (1 - t),
// p(t) = (1 - t)^L q(s), q(s) = sum_i C(L, i) p_i s^i (the scaled Bernstein basis, well conditioned
// for roots near the segment): q's roots by the Aberth-Ehrlich iteration (all roots at once, each
// corrected by Newton's step deflated by the others; cubic convergence to simple roots, linear to
// a cusp's double root), then t = s / (1 + s). A root of q at s = -1 is t = infinity; a missing
// leading coefficient of q (p_L = p(1) = 0) is a root at t = 1, taken out first.
std::vector<Complex> roots(BernsteinPoly p) {
  std::vector<Complex> out;
  const double size = detail::max_abs(p);
  if (!(size > 0.0)) return out;
  while (p.size() > 1 && std::abs(p.back()) <= 1e-13 * size) {
    out.emplace_back(1.0, 0.0);
    // p = (1 - t) r: r_i = p_i L / (L - i) for i < L.
    const int L = static_cast<int>(p.size()) - 1;
    BernsteinPoly r(static_cast<std::size_t>(L));
    for (int i = 0; i < L; ++i) r[static_cast<std::size_t>(i)] = p[static_cast<std::size_t>(i)] * L / (L - i);
    p = std::move(r);
  }
  const int L = static_cast<int>(p.size()) - 1;
  if (L == 0) return out;
  std::vector<double> q(static_cast<std::size_t>(L + 1));
  for (int i = 0; i <= L; ++i) q[static_cast<std::size_t>(i)] = binomial(L, i) * p[static_cast<std::size_t>(i)];
  // q and q' at s by Horner's rule.
  auto evaluate = [&](Complex s, Complex& value, Complex& slope) {
    value = q[static_cast<std::size_t>(L)];
    slope = 0.0;
    for (int i = L - 1; i >= 0; --i) {
      slope = slope * s + value;
      value = value * s + q[static_cast<std::size_t>(i)];
    }
  };
  // Start on a circle of the roots' geometric mean radius |q_0 / q_L|^(1/L), at angles that avoid
  // the real axis (conjugate pairs must be able to separate).
  const double radius = std::pow(std::abs(q[0]) / std::abs(q[static_cast<std::size_t>(L)]) + 1e-300, 1.0 / L);
  std::vector<Complex> z(static_cast<std::size_t>(L));
  for (int k = 0; k < L; ++k)
    z[static_cast<std::size_t>(k)] = std::polar(std::isfinite(radius) && radius > 0 ? radius : 1.0,
                                                2.0 * std::numbers::pi * (k + 0.25) / L + 0.4);
  for (int iteration = 0; iteration < 500; ++iteration) {
    double largest_step = 0.0;
    for (int k = 0; k < L; ++k) {
      Complex value, slope;
      Complex& zk = z[static_cast<std::size_t>(k)];
      evaluate(zk, value, slope);
      if (value == Complex{}) continue;
      const Complex ratio = value / slope;
      Complex repulsion{};
      for (int j = 0; j < L; ++j)
        if (j != k) repulsion += 1.0 / (zk - z[static_cast<std::size_t>(j)]);
      const Complex step = ratio / (1.0 - ratio * repulsion);
      if (!std::isfinite(step.real()) || !std::isfinite(step.imag())) continue;
      zk -= step;
      largest_step = std::max(largest_step, std::abs(step) / std::max(1.0, std::abs(zk)));
    }
    if (largest_step <= 1e-15) break;
  }
  for (const Complex s : z) {
    if (std::abs(1.0 + s) <= 1e-7 * std::max(1.0, std::abs(s)))
      out.emplace_back(std::numeric_limits<double>::infinity(), 0.0);  // t = s / (1 + s) = infinity
    else
      out.push_back(s / (1.0 + s));
  }
  return out;
}

// f(h) = 0 within the rounding of its terms (h a homogeneous point of largest component 1).
bool vanishes(const PlanePolynomial& f, const std::array<double, 3>& h) {
  std::vector<double> terms(static_cast<std::size_t>(PlanePolynomial::size(f.degree())));
  PlanePolynomial::homogeneous_terms(f.degree(), h[0], h[1], h[2], terms);
  double value = 0.0, size = 0.0;
  for (std::size_t k = 0; k < terms.size(); ++k) {
    value += f.coefficients()[k] * terms[k];
    size += std::abs(f.coefficients()[k] * terms[k]);
  }
  return std::abs(value) <= 1e-8 * size;
}

struct Root {
  Complex t;
  std::array<double, 2> point;  // frame coordinates
};

}  // namespace

BasePoints base_points(const InversionPlan& plan, const InversionFormula& formula) {
  const detail::PlanData& data = detail::plan_data(plan);
  const detail::FrameCurve framed = detail::formula_curve(data);
  const detail::HomogeneousCurve& curve = framed.curve;
  const int degree = curve.degree() * formula.degree();
  if (degree > kMaxBasePointDegree)
    throw FormulaError("base points not computed: M(P(t)) has degree " + std::to_string(degree) + ", past " +
                       std::to_string(kMaxBasePointDegree));
  BasePoints result;
  std::vector<Root> real;
  bool infinity_seen = false;
  for (const Complex t : roots(composed(formula.denominator(), curve))) {
    Complex u, v, w;
    if (std::isinf(t.real())) {
      // One parameter, however many roots m has there: M(P(infinity)) = 0 for every formula, and
      // a base point there (a conic's centre P(infinity)) doubles the root without a second branch.
      if (infinity_seen) continue;
      infinity_seen = true;
      // M(P(infinity)) = 0 for every formula (N(P(t)) - t M(P(t)) has no t^(n d + 1) term): a base
      // point there only if N vanishes too.
      const auto h = curve.at_infinity();
      if (!vanishes(formula.numerator(), h)) continue;
      u = h[0], v = h[1], w = h[2];
    } else {
      u = value(curve.u, t), v = value(curve.v, t), w = value(curve.w, t);
    }
    const double size = std::max({std::abs(u), std::abs(v), std::abs(w)});
    if (std::abs(w) <= 1e-12 * size) {  // a point at infinity
      result.at_infinity = true;
      continue;
    }
    const Complex pu = u / w, pv = v / w;
    const double scale = std::max({1.0, std::abs(pu), std::abs(pv)});
    if (std::abs(pu.imag()) > kRealPoint * scale || std::abs(pv.imag()) > kRealPoint * scale) {
      ++result.complex_points;
      continue;
    }
    real.push_back({t, {pu.real(), pv.real()}});
  }
  // Roots at one point are one point of the curve.
  std::vector<bool> taken(real.size(), false);
  for (std::size_t a = 0; a < real.size(); ++a) {
    if (taken[a]) continue;
    std::vector<Complex> parameters{real[a].t};
    for (std::size_t b = a + 1; b < real.size(); ++b)
      if (!taken[b] && std::hypot(real[a].point[0] - real[b].point[0], real[a].point[1] - real[b].point[1]) <=
                           kSamePoint * std::max({1.0, std::abs(real[a].point[0]), std::abs(real[a].point[1])})) {
        taken[b] = true;
        parameters.push_back(real[b].t);
      }
    BasePoint point;
    const PlaneFrame& frame = framed.frame;
    point.point = frame.from_frame(real[a].point[0], real[a].point[1]);
    auto same = [](Complex x, Complex y) {
      return std::abs(x - y) <= kSameParameter * std::max(1.0, std::abs(x));
    };
    if (parameters.size() == 1) {
      point.kind = BasePointKind::simple;
      parameters[0] = parameters[0].real();
    } else if (parameters.size() == 2 && same(parameters[0], parameters[1])) {
      point.kind = BasePointKind::cusp;
      parameters = {Complex((parameters[0].real() + parameters[1].real()) / 2.0, 0.0)};
    } else if (parameters.size() == 2) {
      const bool conjugate = std::abs(parameters[0].imag()) > kSameParameter * std::max(1.0, std::abs(parameters[0]));
      point.kind = conjugate ? BasePointKind::isolated_point : BasePointKind::double_point;
      if (!conjugate)
        for (Complex& t : parameters) t = t.real();
    } else {
      point.kind = BasePointKind::multiple_point;
    }
    // Real parameters increasing (infinity last); a conjugate pair with the positive imaginary part first.
    std::sort(parameters.begin(), parameters.end(), [](Complex x, Complex y) {
      return x.real() != y.real() ? x.real() < y.real() : x.imag() > y.imag();
    });
    point.parameters = std::move(parameters);
    result.points.push_back(std::move(point));
  }
  std::sort(result.points.begin(), result.points.end(), [](const BasePoint& x, const BasePoint& y) {
    return x.parameters[0].real() < y.parameters[0].real();
  });
  return result;
}

}  // namespace bezinv
