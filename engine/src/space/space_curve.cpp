#include "space/space_curve.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <string>

#include "bernstein_arithmetic.hpp"
#include "bezinv/bernstein.hpp"
#include "plan_data.hpp"
#include "bezinv/tolerances.hpp"
#include "quote.hpp"
#include "ratio_range.hpp"

namespace bezinv::detail {
namespace {

// The product of two Bernstein polynomials (degrees m and n, result m + n):
// c_k = sum_{i + j = k} C(m, i) C(n, j) a_i b_j / C(m + n, k), each sum divided once (the
// numerators of the pencil below; bernstein_arithmetic.hpp's product divides term by term).
std::vector<double> product_summed(const std::vector<double>& a, const std::vector<double>& b) {
  const int m = static_cast<int>(a.size()) - 1, n = static_cast<int>(b.size()) - 1;
  std::vector<double> c(m + n + 1, 0.0);
  for (int i = 0; i <= m; ++i)
    for (int j = 0; j <= n; ++j) c[i + j] += binomial(m, i) * binomial(n, j) * a[i] * b[j];
  for (int k = 0; k <= m + n; ++k) c[k] /= binomial(m + n, k);
  return c;
}

// Eigenvectors of the symmetric 3 x 3 matrix m (cyclic Jacobi rotations), as the columns of v,
// ordered by decreasing eigenvalue.
void symmetric_eigenvectors(std::array<std::array<double, 3>, 3> m, std::array<std::array<double, 3>, 3>& v) {
  v = {{{1, 0, 0}, {0, 1, 0}, {0, 0, 1}}};
  for (int sweep = 0; sweep < 50; ++sweep) {
    const double off = std::abs(m[0][1]) + std::abs(m[0][2]) + std::abs(m[1][2]);
    const double size = std::abs(m[0][0]) + std::abs(m[1][1]) + std::abs(m[2][2]);
    if (!(off > 1e-300) || off <= 1e-18 * size) break;
    for (int p = 0; p < 2; ++p)
      for (int q = p + 1; q < 3; ++q) {
        if (m[p][q] == 0.0) continue;
        const double theta = 0.5 * std::atan2(2 * m[p][q], m[q][q] - m[p][p]);
        const double c = std::cos(theta), s = std::sin(theta);
        for (int k = 0; k < 3; ++k) {  // m <- m J (columns p, q)
          const double mkp = m[k][p], mkq = m[k][q];
          m[k][p] = c * mkp - s * mkq;
          m[k][q] = s * mkp + c * mkq;
        }
        for (int k = 0; k < 3; ++k) {  // m <- J^T m (rows p, q)
          const double mpk = m[p][k], mqk = m[q][k];
          m[p][k] = c * mpk - s * mqk;
          m[q][k] = s * mpk + c * mqk;
        }
        for (int k = 0; k < 3; ++k) {
          const double vkp = v[k][p], vkq = v[k][q];
          v[k][p] = c * vkp - s * vkq;
          v[k][q] = s * vkp + c * vkq;
        }
      }
  }
  // Order the columns by eigenvalue (selection sort of three).
  std::array<int, 3> order{0, 1, 2};
  std::sort(order.begin(), order.end(), [&](int i, int j) { return m[i][i] > m[j][j]; });
  const auto copy = v;
  for (int c = 0; c < 3; ++c)
    for (int k = 0; k < 3; ++k) v[k][c] = copy[k][order[c]];
}

// The number of samples the nearest-point search starts from.
int sample_count(int degree) { return 16 * (degree + 1) + 1; }

}  // namespace

SpacePolynomial::SpacePolynomial(std::vector<double> coefficients) : c(std::move(coefficients)) {
  const int n = static_cast<int>(c.size()) - 1;
  binomial_c.resize(c.size());
  for (int i = 0; i <= n; ++i) binomial_c[i] = c[i] * binomial(n, i);
}

double SpacePolynomial::horner(bool forward, double s) const {
  const int n = degree();
  double v = forward ? binomial_c[n] : binomial_c[0];
  if (forward)
    for (int i = n - 1; i >= 0; --i) v = v * s + binomial_c[i];
  else
    for (int i = 1; i <= n; ++i) v = v * s + binomial_c[i];
  return v;
}

double SpacePolynomial::operator()(double t) const {
  const int n = degree();
  if (n <= 0) return c.empty() ? 0.0 : c[0];
  if (!(t >= 0.0 && t <= 1.0)) return bernstein_value(c, t);
  const bool forward = t <= 0.5;
  const double u = forward ? 1 - t : t;
  double power = 1;
  for (int i = 0; i < n; ++i) power *= u;
  return horner(forward, forward ? t / u : (1 - t) / u) * power;
}

SpaceData make_space_data(const Curve& curve) {
  SpaceData space;
  space.curve = curve;
  const int n = curve.degree();
  space.degree = n;
  const std::array<const std::vector<double>*, 3> nums{&curve.x_num, &curve.y_num, &curve.z_num},
      dens{&curve.x_den, &curve.y_den, &curve.z_den};

  // The bounding box of the control points, in halves (as the plane plan: a box as wide as the
  // doubles go keeps a finite centre and scale).
  std::array<double, 3> lo, hi;
  lo.fill(std::numeric_limits<double>::infinity());
  hi.fill(-std::numeric_limits<double>::infinity());
  for (int i = 0; i <= n; ++i)
    for (int k = 0; k < 3; ++k) {
      const double x = (*nums[k])[i] / (*dens[k])[i];
      lo[k] = std::min(lo[k], x);
      hi[k] = std::max(hi[k], x);
    }
  // Where the ratios do not bound the curve (a zero or negative denominator coefficient), the
  // extent of the segment itself, from pieces on which they do (as the plane plan).
  if (!ratios_bound(curve.x_num, curve.x_den) || !ratios_bound(curve.y_num, curve.y_den) ||
      !ratios_bound(curve.z_num, curve.z_den))
    for (int k = 0; k < 3; ++k) {
      const RatioRange range = ratio_range(*nums[k], *dens[k]);
      lo[k] = range.lo;
      hi[k] = range.hi;
    }
  // hypot: the squares of a box wider than ~1e154 overflow, which left the curve unscaled.
  const double half_diagonal = std::hypot(0.5 * hi[0] - 0.5 * lo[0], 0.5 * hi[1] - 0.5 * lo[1], 0.5 * hi[2] - 0.5 * lo[2]);
  space.diagonal = 2 * half_diagonal;
  for (int k = 0; k < 3; ++k) space.centre[k] = 0.5 * lo[k] + 0.5 * hi[k];
  const double magnitude = std::max({std::abs(lo[0]), std::abs(hi[0]), std::abs(lo[1]), std::abs(hi[1]),
                                     std::abs(lo[2]), std::abs(hi[2])});
  if (half_diagonal > 0 && std::isfinite(half_diagonal)) {
    const int e = normalizing_exponent(half_diagonal, magnitude);
    space.scale = std::ldexp(1.0, e);
    space.inverse_scale = std::ldexp(1.0, -e);
  }
  space.normalized_resolution = kResolutionUlps * ulp(magnitude) * space.inverse_scale;

  // The principal axes of the control points (normalized units, about the box's centre).
  std::vector<std::array<double, 3>> offsets;
  double farthest = 0;
  for (int i = 0; i <= n; ++i) {
    std::array<double, 3> d;
    for (int k = 0; k < 3; ++k)
      d[k] = (*nums[k])[i] / (*dens[k])[i] * space.inverse_scale - space.centre[k] * space.inverse_scale;
    // A ratio at infinity (a zero denominator coefficient) has no place among the points.
    if (!std::isfinite(d[0]) || !std::isfinite(d[1]) || !std::isfinite(d[2])) continue;
    offsets.push_back(d);
    for (double e : d) farthest = std::max(farthest, std::abs(e));
  }
  // Rescaled where their squares would underflow or overflow (offset_rescaling: a curve far
  // narrower than its coordinates resolve is normalized to a tiny width, normalizing_exponent).
  if (const int shift = offset_rescaling(farthest); shift != 0)
    for (auto& d : offsets)
      for (double& e : d) e = std::ldexp(e, shift);
  std::array<std::array<double, 3>, 3> covariance{}, axes{};
  for (const auto& d : offsets)
    for (int r = 0; r < 3; ++r)
      for (int c = 0; c < 3; ++c) covariance[r][c] += d[r] * d[c];
  symmetric_eigenvectors(covariance, axes);
  for (int c = 0; c < 2; ++c) {
    // A fixed sign (the largest component positive), so that the same curve gets the same plane.
    int largest = 0;
    for (int k = 1; k < 3; ++k)
      if (std::abs(axes[k][c]) > std::abs(axes[largest][c])) largest = k;
    const double sign = axes[largest][c] < 0 ? -1.0 : 1.0;
    for (int k = 0; k < 3; ++k) (c == 0 ? space.a : space.b)[k] = sign * axes[k][c];
  }
  if (!curve.common_denominator()) {
    // Separate denominators: a combination of x, y, z is over their product (degree up to 3n),
    // a coordinate is over its own (degree n). So a coordinate plane, unless the curve is much
    // narrower there than on its principal plane (a projection that crowds the curve's branches
    // together or collapses a line to a point): both spreads on the coordinate plane (its
    // covariance's eigenvalues) at least kCoordinatePlaneSpread of the principal plane's, to the
    // covariance's rounding (a line's smaller spread is zero to it); of those, the widest.
    double principal[2] = {0, 0};  // a^T C a, b^T C b
    for (int r = 0; r < 3; ++r)
      for (int c = 0; c < 3; ++c) {
        principal[0] += space.a[r] * covariance[r][c] * space.a[c];
        principal[1] += space.b[r] * covariance[r][c] * space.b[c];
      }
    const double slack = 1e-12 * principal[0];
    double best = -std::numeric_limits<double>::infinity();
    for (int i = 0; i < 2; ++i)
      for (int j = i + 1; j < 3; ++j) {
        const double mean = 0.5 * (covariance[i][i] + covariance[j][j]),
                     half = 0.5 * (covariance[i][i] - covariance[j][j]);
        const double larger = mean + std::hypot(half, covariance[i][j]), smaller = mean - std::hypot(half, covariance[i][j]);
        if (larger >= kCoordinatePlaneSpread * principal[0] - slack &&
            smaller >= kCoordinatePlaneSpread * principal[1] - slack && smaller > best)
          best = smaller, space.axes = {i, j};
      }
    if (space.axes[0] >= 0) {
      space.a = space.b = {0.0, 0.0, 0.0};
      space.a[space.axes[0]] = space.b[space.axes[1]] = 1.0;
    }
  }

  // The normalized curve: (x_k - c_k) / scale = (N_k - c_k D_k) / (scale D_k), each pair divided by
  // its largest denominator coefficient.
  for (int k = 0; k < 3; ++k) {
    double largest = 0;
    for (double w : *dens[k]) largest = std::max(largest, std::abs(w));
    std::vector<double> num(n + 1), den(n + 1);
    for (int i = 0; i <= n; ++i) {
      den[i] = (*dens[k])[i] / largest;
      num[i] = (*nums[k])[i] / largest * space.inverse_scale - space.centre[k] * space.inverse_scale * den[i];
    }
    const std::vector<double> d_num = derivative(num, false), d_den = derivative(den, false);
    space.dd_num[k] = SpacePolynomial(derivative(d_num, false));
    space.dd_den[k] = SpacePolynomial(derivative(d_den, false));
    space.d_num[k] = SpacePolynomial(d_num);
    space.d_den[k] = SpacePolynomial(d_den);
    space.num[k] = SpacePolynomial(num);
    space.den[k] = SpacePolynomial(den);
  }
  for (int r = 0; r < 3; ++r) {
    const auto& nums_r = r == 0 ? space.num : r == 1 ? space.d_num : space.dd_num;
    const auto& dens_r = r == 0 ? space.den : r == 1 ? space.d_den : space.dd_den;
    const int m = nums_r[0].degree();
    space.interleaved[r].assign(8 * static_cast<std::size_t>(m + 1), 0.0);
    for (int i = 0; i <= m; ++i)
      for (int k = 0; k < 3; ++k) {
        space.interleaved[r][8 * i + k] = nums_r[k].binomial_c[i];
        space.interleaved[r][8 * i + 3 + k] = dens_r[k].binomial_c[i];
      }
  }
  {
    const bool common = curve.common_denominator();
    const int width = common ? 8 : 16, slopes = common ? 4 : 8;  // where the derivatives start
    space.first_order_width = width;
    space.first_order_forward.assign(static_cast<std::size_t>(width) * (n + 1), 0.0);
    space.first_order_backward.assign(static_cast<std::size_t>(width) * (n + 1), 0.0);
    for (int i = 0; i <= n; ++i)
      for (int j = 0; j < (common ? 4 : 6); ++j) {
        const SpacePolynomial& value = j < 3 ? space.num[j] : space.den[common ? 0 : j - 3];
        const SpacePolynomial& slope = j < 3 ? space.d_num[j] : space.d_den[common ? 0 : j - 3];
        space.first_order_forward[width * i + j] = space.first_order_backward[width * i + j] = value.binomial_c[i];
        if (i < n) space.first_order_forward[width * i + slopes + j] = slope.binomial_c[i];
        if (i > 0) space.first_order_backward[width * i + slopes + j] = slope.binomial_c[i - 1];
      }
  }
  const int samples = sample_count(n);
  space.samples.resize(3 * static_cast<std::size_t>(samples));
  for (int j = 0; j < samples; ++j) {
    const double t = static_cast<double>(j) / (samples - 1);
    for (int k = 0; k < 3; ++k) space.samples[3 * j + k] = space.num[k](t) / space.den[k](t);
  }

  // The principal projection's degree with separate denominators: the product of the distinct ones.
  if (!curve.common_denominator() && space.axes[0] < 0) {
    int distinct = 1 + (curve.y_den != curve.x_den) + (curve.z_den != curve.x_den && curve.z_den != curve.y_den);
    if (distinct * n > kMaxDegree)
      throw CurveError("curve " + quoted_excerpt(curve.id) + ": a space curve with " + std::to_string(distinct) +
                       " different denominators of degree " + std::to_string(n) +
                       " is inverted through a plane curve of degree " + std::to_string(distinct * n) +
                       ", above the maximum " + std::to_string(kMaxDegree));
  }
  return space;
}

Curve projected_curve(const SpaceData& space) {
  const Curve& curve = space.curve;
  const int n = curve.degree();
  const std::array<const std::vector<double>*, 3> nums{&curve.x_num, &curve.y_num, &curve.z_num},
      dens{&curve.x_den, &curve.y_den, &curve.z_den};
  Curve flat;
  flat.id = curve.id;
  flat.kind = curve.kind;
  if (curve.common_denominator()) {
    // u = a . (P - c) = (a . (N - c W)) / W: one denominator, the curve's.
    flat.x_num.resize(n + 1);
    flat.y_num.resize(n + 1);
    for (int i = 0; i <= n; ++i) {
      double u = 0, v = 0;
      for (int k = 0; k < 3; ++k) {
        const double homogeneous = (*nums[k])[i] - space.centre[k] * curve.x_den[i];
        u += space.a[k] * homogeneous;
        v += space.b[k] * homogeneous;
      }
      flat.x_num[i] = u;
      flat.y_num[i] = v;
    }
    flat.x_den = curve.x_den;
    flat.y_den = curve.x_den;
    return flat;
  }
  if (space.axes[0] >= 0) {
    // A coordinate plane: u = x_i - c_i = (N_i - c_i D_i) / D_i, each over its own denominator.
    flat.kind = CurveKind::rational;
    for (int c = 0; c < 2; ++c) {
      const int k = space.axes[c];
      std::vector<double> homogeneous(n + 1);
      for (int i = 0; i <= n; ++i) homogeneous[i] = (*nums[k])[i] - space.centre[k] * (*dens[k])[i];
      (c == 0 ? flat.x_num : flat.y_num) = homogeneous;
      (c == 0 ? flat.x_den : flat.y_den) = *dens[k];
    }
    return flat;
  }
  // The principal plane: over the product D of the distinct denominators, each term times D / D_k.
  std::vector<const std::vector<double>*> distinct;
  for (const auto* d : dens)
    if (std::none_of(distinct.begin(), distinct.end(), [&](const auto* e) { return *e == *d; })) distinct.push_back(d);
  std::vector<double> D = *distinct[0];
  for (std::size_t j = 1; j < distinct.size(); ++j) D = product_summed(D, *distinct[j]);
  std::vector<double> U(D.size(), 0.0), V(D.size(), 0.0);
  for (int k = 0; k < 3; ++k) {
    std::vector<double> homogeneous(n + 1);
    for (int i = 0; i <= n; ++i) homogeneous[i] = (*nums[k])[i] - space.centre[k] * (*dens[k])[i];
    for (const auto* d : distinct)  // times the other distinct denominators
      if (*d != *dens[k]) homogeneous = product_summed(homogeneous, *d);
    U = combine(U, scaled(homogeneous, space.a[k]), 1.0);
    V = combine(V, scaled(homogeneous, space.b[k]), 1.0);
  }
  flat.kind = CurveKind::rational;
  flat.x_num = U;
  flat.y_num = V;
  flat.x_den = D;
  flat.y_den = D;
  return flat;
}

namespace {

// The six polynomials num x, y, z, den x, y, z of derivative order r at t in [0, 1], side by side
// (SpaceData::interleaved): Horner's rule in s = t / (1 - t) (or (1 - t) / t past 1/2), times u^m.
// W polynomials of degree m side by side (c: entry i * W + j is coefficient i of polynomial j) by
// Horner's rule in s: from the top coefficient down (forward) or from coefficient 0 up.
template <int W>
void horner_side_by_side(const std::vector<double>& c, int m, bool forward, double s, double (&v)[W]) {
  if (forward) {
    for (int j = 0; j < W; ++j) v[j] = c[W * m + j];
    for (int i = m - 1; i >= 0; --i)
      for (int j = 0; j < W; ++j) v[j] = v[j] * s + c[W * i + j];
  } else {
    for (int j = 0; j < W; ++j) v[j] = c[j];
    for (int i = 1; i <= m; ++i)
      for (int j = 0; j < W; ++j) v[j] = v[j] * s + c[W * i + j];
  }
}

void interleaved_values(const SpaceData& space, int r, bool forward, double s, double power, double* out) {
  const std::vector<double>& c = space.interleaved[r];
  double v[8];
  horner_side_by_side<8>(c, static_cast<int>(c.size() / 8) - 1, forward, s, v);
  for (int j = 0; j < 6; ++j) out[j] = v[j] * power;
}

// Where Horner's rule in s is taken at t in [0, 1] for a curve of degree n: s = t / (1 - t) forward
// (t <= 1/2), else (1 - t) / t, and the factors u^n, u^(n-1), u^(n-2) of derivative orders 0, 1, 2
// (u = 1 - t forward, else t; a power below 0 is of a zero polynomial: 1 does).
struct HornerPoint {
  bool forward;
  double s;
  double powers[3];
};
HornerPoint horner_point(int n, double t) {
  HornerPoint h;
  h.forward = t <= 0.5;
  const double u = h.forward ? 1 - t : t;
  h.s = h.forward ? t / u : (1 - t) / u;
  double power = 1;
  for (int i = 0; i < n - 2; ++i) power *= u;
  h.powers[0] = n >= 2 ? power * u * u : n == 1 ? u : 1.0;
  h.powers[1] = n >= 2 ? power * u : 1.0;
  h.powers[2] = power;
  return h;
}

// P and P' on [0, 1] from one Horner loop (SpaceData::first_order_forward; width 8 with one
// denominator, 16 with separate ones): the same doubles as space_jet's general evaluation, which
// takes a loop per derivative order.
template <int W>
SpaceJet first_order_jet(const SpaceData& space, double t) {
  constexpr int slopes = W / 2;  // where the derivatives start
  const HornerPoint h = horner_point(space.degree, t);
  const double power_0 = h.powers[0], power_1 = h.powers[1];
  double v[W];
  horner_side_by_side<W>(h.forward ? space.first_order_forward : space.first_order_backward, space.degree, h.forward,
                         h.s, v);
  SpaceJet j{};
  for (int k = 0; k < 3; ++k) {
    const int d = W == 8 ? 3 : 3 + k;  // the denominator's index
    const double D = v[d] * power_0, D1 = v[slopes + d] * power_1;
    const double inverse = 1 / D;
    const double x = (v[k] * power_0) * inverse;
    j.p[k] = x;
    j.dp[k] = (v[slopes + k] * power_1 - D1 * x) * inverse;
  }
  return j;
}

}  // namespace

SpaceJet space_jet(const SpaceData& space, double t, int orders) {
  if (orders <= 2 && t >= 0.0 && t <= 1.0) {
    SpaceJet j = space.first_order_width == 8 ? first_order_jet<8>(space, t) : first_order_jet<16>(space, t);
    if (orders == 1) j.dp = {};
    return j;
  }
  double value[3][6] = {};  // [derivative order][num x, y, z, den x, y, z] (orders not asked for: 0)
  if (t >= 0.0 && t <= 1.0) {
    const HornerPoint h = horner_point(space.degree, t);
    for (int r = 0; r < orders; ++r) interleaved_values(space, r, h.forward, h.s, h.powers[r], value[r]);
  } else {  // the extension: de Casteljau (SpacePolynomial's own evaluation)
    for (int k = 0; k < 3; ++k) {
      value[0][k] = space.num[k](t), value[0][3 + k] = space.den[k](t);
      value[1][k] = space.d_num[k](t), value[1][3 + k] = space.d_den[k](t);
      value[2][k] = space.dd_num[k](t), value[2][3 + k] = space.dd_den[k](t);
    }
  }
  SpaceJet j;
  for (int k = 0; k < 3; ++k) {
    const double N = value[0][k], D = value[0][3 + k], N1 = value[1][k], D1 = value[1][3 + k], N2 = value[2][k],
                 D2 = value[2][3 + k];
    const double inverse = 1 / D;  // one division for the three quotients
    const double x = N * inverse, x1 = (N1 - D1 * x) * inverse;
    j.p[k] = x;
    j.dp[k] = x1;
    j.ddp[k] = (N2 - 2 * D1 * x1 - D2 * x) * inverse;
  }
  return j;
}

double space_distance(const SpaceJet& jet, const std::array<double, 3>& point) {
  const double dx = jet.p[0] - point[0], dy = jet.p[1] - point[1], dz = jet.p[2] - point[2];
  const double d = std::sqrt(dx * dx + dy * dy + dz * dz);
  // (hypot is several times slower; it is needed only where the squares overflow: a far point)
  return std::isfinite(d) ? d : std::hypot(dx, dy, dz);
}

double space_distance(const SpaceData& space, const std::array<double, 3>& point, double t) {
  return space_distance(space_jet(space, t, 1), point);
}

SpaceRefined space_refine(const SpaceData& space, const std::array<double, 3>& point, double t0, bool on_segment) {
  constexpr double eps = std::numeric_limits<double>::epsilon();
  double t = on_segment ? std::clamp(t0, 0.0, 1.0) : t0;
  auto distance_of = [&](const SpaceJet& jet) { return space_distance(jet, point); };
  // The common case first, without second derivatives: a point on the curve, whose plane answer
  // is its parameter to rounding already -- the Gauss-Newton step (P'' times the tiny |P - P0|
  // left out) is below rounding.
  SpaceJet j = space_jet(space, t, 2);
  SpaceRefined best{t, distance_of(j)};
  if (!std::isfinite(best.distance)) return best;
  {
    double g = 0, speed2 = 0;
    for (int k = 0; k < 3; ++k) g += (j.p[k] - point[k]) * j.dp[k], speed2 += j.dp[k] * j.dp[k];
    if (speed2 > 0 && std::abs(g / speed2) <= 2 * eps * std::max(1.0, std::abs(t)) + 2 * eps / std::sqrt(speed2))
      return best;
  }
  j = space_jet(space, t);
  for (int iteration = 0; iteration < 60; ++iteration) {
    double g = 0, speed2 = 0, curvature = 0;
    for (int k = 0; k < 3; ++k) {
      const double e = j.p[k] - point[k];
      g += e * j.dp[k];
      speed2 += j.dp[k] * j.dp[k];
      curvature += e * j.ddp[k];
    }
    double h = speed2 + curvature;
    if (!(h > 0)) h = speed2;  // locally concave: Gauss-Newton still descends
    if (!(h > 0) || !std::isfinite(g)) break;
    double step = -g / h;
    // A step below rounding -- of t itself, and of the point's coordinates (~1 in normalized
    // units) over the speed -- leaves t where it is.
    if (std::abs(step) <= 2 * eps * std::max(1.0, std::abs(t)) + 2 * eps / std::sqrt(speed2)) break;
    // A step is taken where it reduces the distance, or (near the minimum, where the distance is
    // flat to rounding and cannot tell two parameters apart) where it keeps the distance to rounding
    // and reduces |(P - P0) . P'|, the derivative Newton's method drives to zero.
    bool reduced = false;
    for (int halving = 0; halving < 40 && !reduced; ++halving, step *= 0.5) {
      const double next = on_segment ? std::clamp(t + step, 0.0, 1.0) : t + step;
      if (next == t) break;
      const SpaceJet candidate = space_jet(space, next);
      const double d = distance_of(candidate);
      double g_next = 0;
      for (int k = 0; k < 3; ++k) g_next += (candidate.p[k] - point[k]) * candidate.dp[k];
      const bool flat = d <= best.distance * (1 + 8 * eps) + 8 * eps && std::abs(g_next) < std::abs(g);
      if (d < best.distance || flat) {
        best = {next, d};
        t = next;
        j = candidate;
        reduced = true;
      }
    }
    if (!reduced) break;  // no step reduces the distance: a minimum to rounding
  }
  return best;
}

SpaceRefined space_nearest(const SpaceData& space, const std::array<double, 3>& point) {
  const int samples = static_cast<int>(space.samples.size() / 3);
  std::vector<double> d2(samples);
  for (int j = 0; j < samples; ++j) {
    double s = 0;
    for (int k = 0; k < 3; ++k) {
      const double e = space.samples[3 * j + k] - point[k];
      s += e * e;
    }
    d2[j] = s;
  }
  SpaceRefined best{PointResult::nan, std::numeric_limits<double>::infinity()};
  for (int j = 0; j < samples; ++j) {
    const bool minimum = (j == 0 || d2[j] <= d2[j - 1]) && (j == samples - 1 || d2[j] <= d2[j + 1]);
    if (!minimum) continue;
    const SpaceRefined r = space_refine(space, point, static_cast<double>(j) / (samples - 1), true);
    if (r.distance < best.distance || (r.distance == best.distance && r.t < best.t)) best = r;
  }
  return best;
}

void space_answer(const SpaceData& space, const std::array<double, 3>& point, double tolerance,
                  const InvertOptions& options, PointResult& r) {
  if (r.status == Status::invalid_input || r.status == Status::failed) return;
  auto accept = [&](const SpaceRefined& a) {
    r.t = a.t;
    r.residual = a.distance * space.scale;
  };
  if (!options.refine) {
    // The algebraic t as it is: its distance in space decides, as the plane's decides there.
    const double d = space_distance(space, point, r.t);
    r.residual = d * space.scale;
    if (r.status == Status::double_point) {
      const double d2 = space_distance(space, point, r.t2);
      if (d <= tolerance && d2 <= tolerance) return;
      r.status = d <= tolerance || d2 <= tolerance ? Status::ok : Status::off_curve;
      if (d2 <= tolerance && !(d <= tolerance)) r.t = r.t2, r.residual = d2 * space.scale;
      r.t2 = PointResult::nan;
      return;
    }
    if (!(d <= tolerance)) {
      r.status = Status::off_curve;
    } else if (r.status == Status::off_curve) {
      // Within the tolerance in space though off the curve in the plane: the two measure the
      // distance in different units, and they disagree by rounding on a curve a few ulps wide.
      r.status = r.t >= 0.0 && r.t <= 1.0 ? Status::ok : Status::outside_segment;
    }
    return;
  }
  if (r.status == Status::ok || r.status == Status::outside_segment) {
    const SpaceRefined a = space_refine(space, point, r.t, r.status == Status::ok);
    if (a.distance <= tolerance) return accept(a);
  } else if (r.status == Status::double_point) {
    const SpaceRefined a = space_refine(space, point, r.t, true), b = space_refine(space, point, r.t2, true);
    const bool a_in = a.distance <= tolerance, b_in = b.distance <= tolerance;
    if (a_in && b_in && std::abs(a.t - b.t) > kDistinctParameterGap) {
      const SpaceRefined& lo = a.t < b.t ? a : b;
      accept(lo);
      r.t2 = (a.t < b.t ? b : a).t;
      return;
    }
    if (a_in || b_in) {  // one branch in space: the projection crossed itself there, the curve does not
      r.status = Status::ok;
      r.t2 = PointResult::nan;
      return accept(a_in && (!b_in || a.distance <= b.distance) ? a : b);
    }
  }
  // Off the curve in space (the plane's parameters were spurious, or the plane said so).
  const SpaceRefined nearest = space_nearest(space, point);
  r.t2 = PointResult::nan;
  r.path = Path::nearest;
  if (!std::isfinite(nearest.distance)) {
    r.status = Status::failed;
    r.t = r.residual = PointResult::nan;
    r.reason = "no finite parameter found";
    return;
  }
  accept(nearest);
  r.status = nearest.distance <= tolerance ? Status::ok : Status::off_curve;
}

}  // namespace bezinv::detail
