// The lane-batched check in space (Implementation::space_check), every available implementation,
// degrees 1..32, one denominator and three, batch sizes around the vector widths. Expected
// distances come from construction: points made exactly (GMP) at a known t, on the curve or moved
// off it along a normal, and the distance to them measured exactly. tests/engine/space_curve_test.cpp checks the kernel against
// the engine's scalar check bit for bit.
#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <cstdio>
#include <limits>
#include <random>
#include <string>
#include <vector>

#include "bezinv/kernels/batch.hpp"
#include "support/bits.hpp"
#include "support/exact.hpp"
#include "support/measure.hpp"

namespace bezinv::kernels {
namespace {

using test_support::kNaN;
using test_support::same_bits;
using test_support::sci;

// A random space curve in the kernel's layout (SpaceCurve), with one denominator or three: the
// value entries e_ij (x, y, z and the denominators: control points in [-1, 1]^3 times weights in
// [0.5, 2], times C(n, i)), and the derivatives' entries computed exactly from them and rounded.
// The curve under test is the one the value entries define, exactly:
// V_j(t) = sum_i e_ij (1 - t)^(n - i) t^i.
struct SpaceCheckCurve {
  int n = 0, denominators = 1;
  std::vector<double> forward, backward;
  // Bernstein coefficients e_ij / C(n, i), exact, of x, y, z and of the denominators of x, y, z
  // (the same three with one denominator), and their derivatives (degree n - 1).
  std::array<exact::Poly, 6> value, slope;
  SpaceCurve view() const { return {n, denominators, forward.data(), backward.data()}; }

  // P(t) and P'(t), exactly.
  std::array<mpq_class, 3> point(const mpq_class& t) const {
    std::array<mpq_class, 3> p;
    for (int k = 0; k < 3; ++k) p[k] = exact::bernstein_value(value[k], t) / exact::bernstein_value(value[3 + k], t);
    return p;
  }
  std::array<mpq_class, 3> tangent(const mpq_class& t) const {
    std::array<mpq_class, 3> d;
    for (int k = 0; k < 3; ++k) {
      const mpq_class w = exact::bernstein_value(value[3 + k], t), dw = exact::bernstein_value(slope[3 + k], t);
      d[k] = (exact::bernstein_value(slope[k], t) * w - exact::bernstein_value(value[k], t) * dw) / (w * w);
    }
    return d;
  }
};

SpaceCheckCurve random_space_check_curve(int n, std::mt19937_64& rng, int denominators = 1) {
  std::uniform_real_distribution<double> coordinate(-1.0, 1.0), weight(0.5, 2.0);
  SpaceCheckCurve c;
  c.n = n;
  c.denominators = denominators;
  const int width = denominators == 1 ? 8 : 16, polynomials = denominators == 1 ? 4 : 6, slopes = width / 2;
  c.forward.assign(static_cast<std::size_t>(width) * (n + 1), 0.0);
  c.backward = c.forward;
  for (int i = 0; i <= n; ++i) {
    double w[3];
    for (double& v : w) v = weight(rng);
    if (denominators == 1) w[1] = w[2] = w[0];
    const double binomial = exact::binomial(n, i).get_d();
    for (int j = 0; j < polynomials; ++j) {
      const double entry = (j < 3 ? w[j] * coordinate(rng) : w[j - 3]) * binomial;
      c.forward[width * i + j] = c.backward[width * i + j] = entry;
      c.value[j].push_back(mpq_class(entry) / exact::binomial(n, i));
    }
  }
  for (int j = 0; j < polynomials; ++j) {
    c.slope[j] = exact::derivative(c.value[j]);
    for (int i = 0; i < n; ++i) {
      const double entry = exact::nearest_double(c.slope[j][i] * exact::binomial(n - 1, i));
      c.forward[width * i + slopes + j] = entry;
      c.backward[width * (i + 1) + slopes + j] = entry;
    }
  }
  if (denominators == 1) c.value[4] = c.value[5] = c.value[3], c.slope[4] = c.slope[5] = c.slope[3];
  return c;
}

struct SpaceCheckLanes {
  std::vector<double> t, x, y, z, distance;
  void add(double t0, const std::array<double, 3>& p) {
    t.push_back(t0), x.push_back(p[0]), y.push_back(p[1]), z.push_back(p[2]);
    distance.push_back(-1.0);  // overwritten by every lane
  }
  void run(const Implementation& implementation, const SpaceCheckCurve& c) {
    implementation.space_check(c.view(), t.size(), t.data(), x.data(), y.data(), z.data(), distance.data());
  }
};

std::array<double, 3> rounded_point(const std::array<mpq_class, 3>& p) {
  return {exact::nearest_double(p[0]), exact::nearest_double(p[1]), exact::nearest_double(p[2])};
}

// |P(t) - Q| exactly, then rounded (via the exact square).
double exact_space_distance(const std::array<mpq_class, 3>& p, const std::array<double, 3>& q) {
  mpq_class s = 0;
  for (int k = 0; k < 3; ++k) {
    const mpq_class e = p[k] - mpq_class(q[k]);
    s += e * e;
  }
  return std::sqrt(s.get_d());
}

// On-curve points P(t), made exactly and rounded, with their own t: settled, at the distance of
// the rounding (half an ulp per coordinate of a point in [-1, 1]^3, ~2e-16, plus the kernel's
// evaluation error, which grows with the degree). The first-order test can refuse a lane whose
// rounding error exceeds its bound (2 eps / |P'|): most lanes settle; measured 100% here.
TEST(SpaceCheck, OnCurvePointsAreSettledWithTheirDistance) {
  const auto implementations = available_implementations();
  std::vector<std::size_t> settled(implementations.size());
  std::vector<double> worst(implementations.size());
  std::size_t lanes_total = 0;
  std::mt19937_64 rng(20261204);
  for (int denominators : {1, 3})
    for (int n = kSpaceCheckMinDegree; n <= kSpaceCheckMaxDegree; n += denominators == 1 ? 1 : 3) {
      const SpaceCheckCurve c = random_space_check_curve(n, rng, denominators);
      SpaceCheckLanes lanes;
      std::vector<double> ts = {0.0, 0.5, 1.0, 0.25, 0.75};
      for (int k = 0; k < 11; ++k) ts.push_back(std::uniform_real_distribution<double>(0.0, 1.0)(rng));
      for (double t : ts) lanes.add(t, rounded_point(c.point(mpq_class(t))));
      lanes_total += ts.size();
      for (std::size_t m = 0; m < implementations.size(); ++m) {
        lanes.run(*implementations[m], c);
        for (std::size_t l = 0; l < ts.size(); ++l) {
          SCOPED_TRACE(std::string(implementations[m]->name) + " n=" + std::to_string(n) + " lane " + std::to_string(l));
          if (std::isnan(lanes.distance[l])) continue;
          ++settled[m];
          EXPECT_LE(lanes.distance[l], 1e-14);
          worst[m] = std::max(worst[m], lanes.distance[l]);
        }
      }
    }
  for (std::size_t m = 0; m < implementations.size(); ++m) {
    std::printf("%s: %zu of %zu on-curve lanes settled, worst distance %s\n",
                std::string(implementations[m]->name).c_str(), settled[m], lanes_total, sci(worst[m]).c_str());
    EXPECT_GE(settled[m], lanes_total * 9 / 10) << implementations[m]->name;
  }
}

// Points moved off the curve along a normal, P(t) + delta N with N . P'(t) = 0 (N = P' x a for a
// random a, exactly): t is the foot, so the lane settles, and its distance is the exact distance
// from P(t) to the rounded point to rounding.
TEST(SpaceCheck, PointsAlongANormalGetTheirDistance) {
  const auto implementations = available_implementations();
  std::vector<std::size_t> settled(implementations.size());
  std::vector<double> worst(implementations.size());
  std::size_t lanes_total = 0;
  std::mt19937_64 rng(42);
  for (int denominators : {1, 3})
    for (int n = kSpaceCheckMinDegree; n <= kSpaceCheckMaxDegree; n += denominators == 1 ? 1 : 3) {
      const SpaceCheckCurve c = random_space_check_curve(n, rng, denominators);
      SpaceCheckLanes lanes;
      std::vector<double> truth;
      for (int k = 0; k < 8; ++k) {
        const double t = std::uniform_real_distribution<double>(0.0, 1.0)(rng);
        const double delta = std::pow(10.0, -1.0 - 3.0 * k / 8);  // 1e-1 .. 1e-4
        const auto p = c.point(mpq_class(t));
        const auto d = c.tangent(mpq_class(t));
        std::array<mpq_class, 3> a;
        for (auto& e : a) e = std::uniform_real_distribution<double>(-1.0, 1.0)(rng);
        const std::array<mpq_class, 3> normal = {d[1] * a[2] - d[2] * a[1], d[2] * a[0] - d[0] * a[2],
                                                 d[0] * a[1] - d[1] * a[0]};
        const double length =
            std::sqrt(mpq_class(normal[0] * normal[0] + normal[1] * normal[1] + normal[2] * normal[2]).get_d());
        std::array<mpq_class, 3> q;
        for (int j = 0; j < 3; ++j) q[j] = p[j] + mpq_class(delta / length) * normal[j];
        const auto point = rounded_point(q);
        lanes.add(t, point);
        truth.push_back(exact_space_distance(p, point));
      }
      lanes_total += truth.size();
      for (std::size_t m = 0; m < implementations.size(); ++m) {
        lanes.run(*implementations[m], c);
        for (std::size_t l = 0; l < truth.size(); ++l) {
          SCOPED_TRACE(std::string(implementations[m]->name) + " n=" + std::to_string(n) + " lane " + std::to_string(l));
          if (std::isnan(lanes.distance[l])) continue;
          ++settled[m];
          const double error = std::abs(lanes.distance[l] - truth[l]);
          EXPECT_LE(error, 1e-14) << lanes.distance[l] << " " << truth[l];
          worst[m] = std::max(worst[m], error);
        }
      }
    }
  for (std::size_t m = 0; m < implementations.size(); ++m) {
    std::printf("%s: %zu of %zu normal lanes settled, worst |distance error| %s\n",
                std::string(implementations[m]->name).c_str(), settled[m], lanes_total, sci(worst[m]).c_str());
    EXPECT_GE(settled[m], lanes_total * 9 / 10) << implementations[m]->name;
  }
}

// A t away from the foot (the on-curve point of t + h given t), a t outside [0, 1] or NaN, a point
// with a coordinate that is not finite or so far that its distance overflows: never settled.
TEST(SpaceCheck, LanesItCannotSettleAreNaN) {
  for (const Implementation* implementation : available_implementations()) {
    std::mt19937_64 rng(3);
    for (int n : {1, 2, 3, 7, 20, 32}) {
      SCOPED_TRACE(std::string(implementation->name) + " n=" + std::to_string(n));
      const SpaceCheckCurve c = random_space_check_curve(n, rng, n % 2 == 0 ? 3 : 1);
      SpaceCheckLanes lanes;
      for (double h : {1e-9, -1e-9, 1e-6, 1e-3})
        lanes.add(0.4, rounded_point(c.point(mpq_class(0.4 + h))));
      const auto on = rounded_point(c.point(mpq_class(0.5)));
      lanes.add(-1e-3, on);
      lanes.add(1 + 1e-3, on);
      lanes.add(kNaN, on);
      lanes.add(0.5, {kNaN, on[1], on[2]});
      lanes.add(0.5, {on[0], std::numeric_limits<double>::infinity(), on[2]});
      lanes.add(0.5, {on[0], on[1], 1e300});
      lanes.run(*implementation, c);
      for (std::size_t l = 0; l < lanes.t.size(); ++l) EXPECT_TRUE(std::isnan(lanes.distance[l])) << l;
    }
  }
}

// Every lane's answer is its own: the same bits whatever the batch size (the tails of vectors) and
// whatever the implementation (the kernel's promise: the engine's scalar operations, in order).
TEST(SpaceCheck, SameBitsAtEveryBatchSizeAndOnEveryImplementation) {
  std::mt19937_64 rng(11);
  for (int n : {1, 2, 3, 5, 8, 15, 32}) {
    const SpaceCheckCurve c = random_space_check_curve(n, rng, n % 2 == 0 ? 3 : 1);
    SpaceCheckLanes all;
    for (int l = 0; l < 19; ++l) {
      const double t = std::uniform_real_distribution<double>(0.0, 1.0)(rng);
      auto p = rounded_point(c.point(mpq_class(t)));
      if (l % 3 == 1) p[2] += 1e-3;  // some off the curve (settled where t is still the foot, or NaN)
      all.add(t, p);
    }
    std::vector<double> reference;
    for (const Implementation* implementation : available_implementations()) {
      SCOPED_TRACE(std::string(implementation->name) + " n=" + std::to_string(n));
      all.run(*implementation, c);
      if (reference.empty()) reference = all.distance;
      EXPECT_TRUE(test_support::same_bits(all.distance, reference));
      for (std::size_t count = 0; count <= all.t.size(); ++count) {
        std::vector<double> distance(count + 1, 7.0);
        implementation->space_check(c.view(), count, all.t.data(), all.x.data(), all.y.data(), all.z.data(),
                                    distance.data());
        for (std::size_t l = 0; l < count; ++l) EXPECT_TRUE(same_bits(distance[l], reference[l])) << count << " " << l;
        EXPECT_EQ(distance[count], 7.0) << count;  // nothing written past `count`
      }
    }
  }
}

}  // namespace
}  // namespace bezinv::kernels
