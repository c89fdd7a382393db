#include "bezinv/matrix_weighted.hpp"

#include <algorithm>
#include <cmath>
#include <optional>
#include <sstream>
#include <string>

#include "bernstein_arithmetic.hpp"
#include "bezinv/bernstein.hpp"

namespace bezinv {
namespace {

using detail::BernsteinPoly;
using detail::combine;
using detail::product;

std::string quoted_id(const std::string& id) { return "curve \"" + id + "\""; }

Vector3 unit(int dimension, Vector3 v, const std::string& what) {
  if (dimension == 2) v[2] = 0.0;
  const double length = std::sqrt(v[0] * v[0] + v[1] * v[1] + v[2] * v[2]);
  if (!(length > 0.0) || !std::isfinite(length)) throw CurveError(what + ": a zero or non-finite vector");
  for (double& e : v) e /= length;
  return v;
}

void check_omega_mu(double omega, double mu, const std::string& what) {
  if (!(omega > 0.0) || !std::isfinite(omega)) throw CurveError(what + ": omega must be > 0");
  if (!(mu > -1.0) || !std::isfinite(mu)) throw CurveError(what + ": mu must be > -1");
}

// The polynomial entry (r, c) of M(t) = sum_i M_i B_{i,n}(t).
BernsteinPoly entry(const MatrixWeightedCurve& curve, int r, int c) {
  BernsteinPoly p(curve.matrices.size());
  for (std::size_t i = 0; i < p.size(); ++i) p[i] = curve.matrices[i][static_cast<std::size_t>(3 * r + c)];
  return p;
}

// The first parameter of [0, 1] where det M(t) vanishes or changes sign, if any: sampled, then
// bisected. (No threshold relative to the coefficients' size: matrices from eqs. (2) and (3) with
// mu near -1 have a tiny but positive determinant, which is not singular.)
std::optional<double> singular_parameter(const BernsteinPoly& det) {
  // Coefficients of one strict sign: so is the polynomial on [0, 1] (a convex combination of them),
  // the case of every matrix from eqs. (2) and (3).
  if (std::all_of(det.begin(), det.end(), [](double w) { return w > 0.0; }) ||
      std::all_of(det.begin(), det.end(), [](double w) { return w < 0.0; }))
    return std::nullopt;
  constexpr int kSamples = 4096;
  const double first = bernstein_value(det, 0.0);
  if (first == 0.0 || !std::isfinite(first)) return 0.0;
  double previous_t = 0.0;
  for (int k = 1; k <= kSamples; ++k) {
    const double t = static_cast<double>(k) / kSamples, value = bernstein_value(det, t);
    if (value == 0.0 || !std::isfinite(value)) return t;
    if ((value > 0) != (first > 0)) {
      double lo = previous_t, hi = t;
      for (int i = 0; i < 60; ++i) {
        const double mid = (lo + hi) / 2;
        ((bernstein_value(det, mid) > 0) == (first > 0) ? lo : hi) = mid;
      }
      return (lo + hi) / 2;
    }
    previous_t = t;
  }
  return std::nullopt;
}

}  // namespace

Matrix3 normal_weight(int dimension, Vector3 normal, double omega, double mu, const std::string& what) {
  check_omega_mu(omega, mu, what);
  const Vector3 n = unit(dimension, normal, what);
  Matrix3 m{};
  for (int r = 0; r < dimension; ++r)
    for (int c = 0; c < dimension; ++c) m[3 * r + c] = omega * ((r == c ? 1.0 : 0.0) + mu * n[r] * n[c]);
  return m;
}

Matrix3 tangent_weight(int dimension, Vector3 tangent, double omega, double mu, const std::string& what) {
  check_omega_mu(omega, mu, what);
  const Vector3 t = unit(dimension, tangent, what);
  Matrix3 m{};
  for (int r = 0; r < dimension; ++r)
    for (int c = 0; c < dimension; ++c) {
      const double identity = r == c ? 1.0 : 0.0;
      m[3 * r + c] = omega * (identity + mu * (identity - t[r] * t[c]));
    }
  return m;
}

ConvertedCurve convert(const MatrixWeightedCurve& curve) {
  const int d = curve.dimension;
  // The adjugate M*(t) (degree (d - 1) n): its (r, c) entry is the cofactor of (c, r).
  std::array<std::array<BernsteinPoly, 3>, 3> adjugate;
  if (d == 2) {
    adjugate[0][0] = entry(curve, 1, 1);
    adjugate[0][1] = detail::scaled(entry(curve, 0, 1), -1.0);
    adjugate[1][0] = detail::scaled(entry(curve, 1, 0), -1.0);
    adjugate[1][1] = entry(curve, 0, 0);
  } else {
    for (int r = 0; r < 3; ++r)
      for (int c = 0; c < 3; ++c) {
        // Cofactor of (c, r): the 2 x 2 minor without row c and column r, signed.
        const int r0 = (c + 1) % 3, r1 = (c + 2) % 3, c0 = (r + 1) % 3, c1 = (r + 2) % 3;
        adjugate[r][c] = combine(product(entry(curve, r0, c0), entry(curve, r1, c1)),
                                 product(entry(curve, r0, c1), entry(curve, r1, c0)), -1.0);
      }
  }
  // det M(t) = sum_l a_{0l}(t) A_{0l}(t) (row 0 against its cofactors: adjugate column 0).
  BernsteinPoly det;
  for (int l = 0; l < d; ++l) {
    const BernsteinPoly term = product(entry(curve, 0, l), adjugate[l][0]);
    det = det.empty() ? term : combine(det, term, 1.0);
  }
  if (const auto t = singular_parameter(det)) {
    std::ostringstream text;
    text.precision(6);
    text << quoted_id(curve.id) << ": the weight matrices' sum M(t) is singular at t = " << *t
         << " (det M(t) = 0 there)";
    throw CurveError(text.str());
  }
  // The numerator M*(t) sum_j (M_j P_j) B_j(t), degree d n.
  std::array<BernsteinPoly, 3> weighted;  // sum_j (M_j P_j)_r B_j
  for (int r = 0; r < d; ++r) {
    weighted[r].resize(curve.points.size());
    for (std::size_t j = 0; j < curve.points.size(); ++j) {
      double sum = 0.0;
      for (int c = 0; c < d; ++c) sum += curve.matrices[j][static_cast<std::size_t>(3 * r + c)] * curve.points[j][c];
      weighted[r][j] = sum;
    }
  }
  ConvertedCurve out;
  out.dimension = d;
  out.weights = det;
  const std::size_t count = det.size();
  out.points.assign(count, Vector3{});
  out.numerators.assign(count, Vector3{});
  for (int r = 0; r < d; ++r) {
    BernsteinPoly numerator;
    for (int c = 0; c < d; ++c) {
      const BernsteinPoly term = product(adjugate[r][c], weighted[c]);
      numerator = numerator.empty() ? term : combine(numerator, term, 1.0);
    }
    for (std::size_t k = 0; k < count; ++k) {
      out.numerators[k][r] = numerator[k];
      out.points[k][r] = det[k] != 0.0 ? numerator[k] / det[k] : numerator[k];
    }
  }
  return out;
}

Vector3 matrix_weighted_point(const MatrixWeightedCurve& curve, double t) {
  const int d = curve.dimension, n = static_cast<int>(curve.points.size()) - 1;
  std::vector<double> b(static_cast<std::size_t>(n + 1));
  bernstein_basis(n, t, b);
  long double m[3][3] = {}, rhs[3] = {};
  for (int i = 0; i <= n; ++i)
    for (int r = 0; r < d; ++r)
      for (int c = 0; c < d; ++c) {
        const long double e = static_cast<long double>(b[i]) * curve.matrices[i][3 * r + c];
        m[r][c] += e;
        rhs[r] += e * curve.points[i][c];
      }
  // Cramer's rule in long double (d <= 3).
  auto det3 = [&](long double a[3][3]) {
    if (d == 2) return a[0][0] * a[1][1] - a[0][1] * a[1][0];
    return a[0][0] * (a[1][1] * a[2][2] - a[1][2] * a[2][1]) - a[0][1] * (a[1][0] * a[2][2] - a[1][2] * a[2][0]) +
           a[0][2] * (a[1][0] * a[2][1] - a[1][1] * a[2][0]);
  };
  const long double det = det3(m);
  Vector3 q{};
  for (int k = 0; k < d; ++k) {
    long double mk[3][3];
    for (int r = 0; r < 3; ++r)
      for (int c = 0; c < 3; ++c) mk[r][c] = c == k ? rhs[r] : m[r][c];
    q[k] = static_cast<double>(det3(mk) / det);
  }
  return q;
}

Curve plane_curve(const ConvertedCurve& converted, std::string id) {
  // The homogeneous coefficients omega_k Q_k and omega_k, as computed: Q_k itself loses digits
  // where omega_k is tiny against its terms (mu near -1).
  std::vector<double> x, y;
  for (const Vector3& q : converted.numerators) x.push_back(q[0]), y.push_back(q[1]);
  return Curve::rational(std::move(id), x, converted.weights, y, converted.weights);
}

Curve lowest_terms_curve(const MatrixWeightedCurve& curve, std::string id) {
  const int d = curve.dimension;
  std::vector<double> scale;
  for (const Matrix3& m : curve.matrices) {
    // s I exactly: equal diagonal, zero elsewhere (in the curve's dimension).
    bool scalar = m[0] > 0;
    for (int r = 0; r < d; ++r)
      for (int c = 0; c < d; ++c) scalar = scalar && m[3 * r + c] == (r == c ? m[0] : 0.0);
    if (!scalar) return rational_curve(convert(curve), std::move(id));
    scale.push_back(m[0]);
  }
  if (d == 3) {
    std::vector<std::array<double, 3>> points;
    for (const Vector3& p : curve.points) points.push_back({p[0], p[1], p[2]});
    return Curve::space_rational_bezier(std::move(id), points, scale);
  }
  std::vector<std::array<double, 2>> points;
  for (const Vector3& p : curve.points) points.push_back({p[0], p[1]});
  return Curve::rational_bezier(std::move(id), points, scale);
}

Curve rational_curve(const ConvertedCurve& converted, std::string id) {
  Curve curve = plane_curve(converted, std::move(id));
  if (converted.dimension == 3) {
    for (const Vector3& q : converted.numerators) curve.z_num.push_back(q[2]);
    curve.z_den = converted.weights;
  }
  return curve;
}

}  // namespace bezinv
