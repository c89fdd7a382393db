#include "bezinv/datasets/high_precision_nearest.hpp"

#include <mpfr.h>

#include <algorithm>
#include <cmath>
#include <vector>

namespace bezinv::datasets {
namespace {

// An MPFR number of kReferenceBits bits that frees itself. Every operation rounds to nearest.
class Big {
 public:
  Big() { mpfr_init2(v_, kReferenceBits); mpfr_set_zero(v_, 1); }
  explicit Big(double x) { mpfr_init2(v_, kReferenceBits); mpfr_set_d(v_, x, MPFR_RNDN); }
  Big(const Big& other) { mpfr_init2(v_, kReferenceBits); mpfr_set(v_, other.v_, MPFR_RNDN); }
  Big& operator=(const Big& other) { mpfr_set(v_, other.v_, MPFR_RNDN); return *this; }
  ~Big() { mpfr_clear(v_); }
  mpfr_ptr get() { return v_; }
  mpfr_srcptr get() const { return v_; }
  double to_double() const { return mpfr_get_d(v_, MPFR_RNDN); }

  friend Big operator+(const Big& a, const Big& b) { Big r; mpfr_add(r.v_, a.v_, b.v_, MPFR_RNDN); return r; }
  friend Big operator-(const Big& a, const Big& b) { Big r; mpfr_sub(r.v_, a.v_, b.v_, MPFR_RNDN); return r; }
  friend Big operator*(const Big& a, const Big& b) { Big r; mpfr_mul(r.v_, a.v_, b.v_, MPFR_RNDN); return r; }
  friend Big operator/(const Big& a, const Big& b) { Big r; mpfr_div(r.v_, a.v_, b.v_, MPFR_RNDN); return r; }
  friend Big operator*(double a, const Big& b) { Big r; mpfr_mul_d(r.v_, b.v_, a, MPFR_RNDN); return r; }

 private:
  mpfr_t v_;
};

// A polynomial in the Bernstein basis and its first two derivatives at t, from de Casteljau's
// triangle: with b^k_i the level-k points, p = b^n_0, p' = n (b^{n-1}_1 - b^{n-1}_0),
// p'' = n (n - 1) (b^{n-2}_2 - 2 b^{n-2}_1 + b^{n-2}_0).
struct Jet {
  Big value, first, second;
};

Jet bernstein_jet(const std::vector<double>& coefficients, const Big& t) {
  const int n = static_cast<int>(coefficients.size()) - 1;
  std::vector<Big> b;
  b.reserve(coefficients.size());
  for (double c : coefficients) b.emplace_back(c);
  const Big one(1.0), s = one - t;
  Big product;
  Jet jet;
  for (int level = n; level >= 1; --level) {  // `level` points remain after this step
    if (level == 2) jet.second = static_cast<double>(n) * (n - 1) * ((b[2] - 2.0 * b[1]) + b[0]);
    if (level == 1) jet.first = static_cast<double>(n) * (b[1] - b[0]);
    // b_i <- s b_i + t b_{i+1} in place: the operators' temporaries (an allocation each) were most
    // of the truth's time.
    for (int i = 0; i < level; ++i) {
      mpfr_mul(product.get(), t.get(), b[i + 1].get(), MPFR_RNDN);
      mpfr_fma(b[i].get(), s.get(), b[i].get(), product.get(), MPFR_RNDN);
    }
  }
  if (n == 1) jet.second = Big();
  if (n == 0) jet.first = jet.second = Big();
  jet.value = b[0];
  return jet;
}

// A quotient N / D and its derivatives: x' = (N' - D' x) / D, x'' = (N'' - 2 D' x' - D'' x) / D.
Jet quotient_jet(const std::vector<double>& numerator, const std::vector<double>& denominator, const Big& t) {
  const Jet N = bernstein_jet(numerator, t), D = bernstein_jet(denominator, t);
  Jet x;
  x.value = N.value / D.value;
  x.first = (N.first - D.first * x.value) / D.value;
  x.second = ((N.second - 2.0 * (D.first * x.first)) - D.second * x.value) / D.value;
  return x;
}

struct Stationarity {
  Big f, derivative, distance2, speed2;
};

// f = (x - x0) x' + (y - y0) y', f' = x'^2 + y'^2 + (x - x0) x'' + (y - y0) y'' (and z's terms for a
// space curve).
Stationarity stationarity(const Curve& curve, Point point, double z0, const Big& t) {
  const Jet x = quotient_jet(curve.x_num, curve.x_den, t), y = quotient_jet(curve.y_num, curve.y_den, t);
  const Big dx = x.value - Big(point.x), dy = y.value - Big(point.y);
  Stationarity s;
  s.speed2 = x.first * x.first + y.first * y.first;
  s.f = dx * x.first + dy * y.first;
  s.derivative = (s.speed2 + dx * x.second) + dy * y.second;
  s.distance2 = dx * dx + dy * dy;
  if (curve.dimension() == 3) {
    const Jet z = quotient_jet(curve.z_num, curve.z_den, t);
    const Big dz = z.value - Big(z0);
    s.speed2 = s.speed2 + z.first * z.first;
    s.f = s.f + dz * z.first;
    s.derivative = (s.derivative + z.first * z.first) + dz * z.second;
    s.distance2 = s.distance2 + dz * dz;
  }
  return s;
}

double sqrt_to_double(const Big& x) {
  Big r;
  mpfr_sqrt(r.get(), x.get(), MPFR_RNDN);
  return r.to_double();
}

}  // namespace

HighPrecisionNearest high_precision_nearest(const Curve& curve, Point point, double t_start, bool segment_only,
                                            double z) {
  Big t(t_start);
  bool converged = false;
  // Quadratic convergence from ~1e-6 reaches the working precision in about 4 steps; 60 allow slow
  // (near degenerate) minima to creep in. The precision attainable in t is 2^-bits relative to t,
  // or to the point's size over the speed (a curve 1e12 from the origin is known to 2^-128 1e12 in
  // x, so to that over |P'| in t): converged 2^20 above the larger.
  const double coordinates = std::max({std::abs(point.x), std::abs(point.y), std::abs(z), 1.0});
  for (int iteration = 0; iteration < 60 && !converged; ++iteration) {
    const Stationarity s = stationarity(curve, point, z, t);
    const double speed = std::sqrt(s.speed2.to_double());
    const Big tolerance(std::ldexp(std::max(std::abs(t.to_double()), coordinates / speed), -(kReferenceBits - 20)));
    if (mpfr_sgn(s.derivative.get()) <= 0) break;  // not a minimum's basin: keep what we have
    const Big step = s.f / s.derivative;
    const Big next = t - step;
    // The nearest point of the segment at an end: the minimum of the distance lies beyond it.
    if (segment_only && (next.to_double() < 0.0 || next.to_double() > 1.0)) {
      t = Big(next.to_double() < 0.0 ? 0.0 : 1.0);
      converged = true;
      break;
    }
    t = next;
    Big size;
    mpfr_abs(size.get(), step.get(), MPFR_RNDN);
    converged = mpfr_lessequal_p(size.get(), tolerance.get()) != 0;
  }
  HighPrecisionNearest result;
  result.t = t.to_double();
  result.t_low = (t - Big(result.t)).to_double();
  const Stationarity s = stationarity(curve, point, z, t);
  result.distance = sqrt_to_double(s.distance2);
  result.speed = sqrt_to_double(s.speed2);
  result.converged = converged;
  return result;
}

double high_precision_stationarity(const Curve& curve, Point point, double t_hi, double t_lo, double z) {
  return stationarity(curve, point, z, Big(t_hi) + Big(t_lo)).f.to_double();
}

}  // namespace bezinv::datasets
