// The lane-batched nearest-point Newton kernels, every available implementation, degrees 1..24,
// batch sizes around the vector widths: Implementation::rational_newton (de Casteljau's jets, the
// scalar refinement's steps) and the off-curve path's Implementation::nearest_newton (Horner's
// jets, RationalCurve::horner), in turn. Expected parameters come from
// construction: points made exactly (GMP) at a known t, on the curve, along its normal, or past an
// end along its tangent. tests/engine/refine_test.cpp checks the de Casteljau jets against the
// engine's scalar refinement bit for bit; the Horner jets give every implementation the same bits.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <random>
#include <string>
#include <vector>

#include "support/bits.hpp"
#include "bezinv/kernels/batch.hpp"
#include "support/exact.hpp"
#include "support/measure.hpp"
#include "support/sanitizers.hpp"

namespace bezinv::kernels {
namespace {

using test_support::sci;

using test_support::kNaN;
// The engine's settings (engine/include/bezinv/tolerances.hpp).
constexpr NewtonSettings kSettings{60, 0.125, 1e-6, 40, 1e-12};
constexpr NearestNewtonSettings kNearestSettings{60, 0.125, 1e-6, 40, 1e-9};

// Which kernel a test runs: rational_newton or nearest_newton.
enum class Variant { casteljau, nearest };
constexpr Variant kVariants[] = {Variant::casteljau, Variant::nearest};
std::string name(Variant variant) { return variant == Variant::casteljau ? "" : " nearest_newton"; }

// A random rational Bezier curve: control points in [-1, 1]^2, weights in [0.5, 2], one denominator
// (or with `separate`, x and y each their own).
struct TestCurve {
  std::vector<double> x_num, x_den, y_num, y_den;
  exact::RationalCurve exact;
  std::vector<double> horner;  // batch.hpp's layout, filled by completed()
  RationalCurve view(bool by_horner = false) const {
    return {static_cast<int>(x_num.size()) - 1, x_num.data(), x_den.data(), y_num.data(), y_den.data(),
            by_horner ? horner.data() : nullptr};
  }
};

// Per polynomial, the Bernstein coefficients of its value, first and second derivative (degree n,
// n - 1, n - 2: forward differences times n, n (n - 1)), each times its binomial C(m, i).
std::vector<double> horner_layout(int n, const std::vector<const std::vector<double>*>& polynomials) {
  const auto binomial = [](int m, int i) {
    double b = 1;
    for (int k = 1; k <= i; ++k) b = b * (m - i + k) / k;
    return b;
  };
  std::vector<double> out;
  for (const std::vector<double>* c : polynomials) {
    const std::vector<double>& p = *c;
    for (int i = 0; i <= n; ++i) out.push_back(p[i] * binomial(n, i));
    for (int i = 0; i < n; ++i) out.push_back(n * (p[i + 1] - p[i]) * binomial(n - 1, i));
    for (int i = 0; i + 1 < n; ++i) out.push_back(n * (n - 1.0) * (p[i + 2] - 2 * p[i + 1] + p[i]) * binomial(n - 2, i));
  }
  return out;
}

// c with what its polynomials determine: the Horner layout and the exact curve.
TestCurve completed(TestCurve c) {
  c.horner = horner_layout(static_cast<int>(c.x_num.size()) - 1, {&c.x_num, &c.x_den, &c.y_num, &c.y_den});
  c.exact = {exact::to_exact(c.x_num), exact::to_exact(c.x_den), exact::to_exact(c.y_num), exact::to_exact(c.y_den)};
  return c;
}

TestCurve random_curve(int n, std::mt19937_64& rng, bool separate = false) {
  std::uniform_real_distribution<double> coordinate(-1.0, 1.0), weight(0.5, 2.0);
  TestCurve c;
  for (int i = 0; i <= n; ++i) {
    const double w = weight(rng), wy = separate ? weight(rng) : w;
    c.x_num.push_back(w * coordinate(rng));
    c.y_num.push_back(wy * coordinate(rng));
    c.x_den.push_back(w);
    c.y_den.push_back(wy);
  }
  return completed(c);
}

struct Exact {
  double x, y, dx, dy;  // P(t) and P'(t), each the double nearest to the exact value
};
Exact at(const TestCurve& c, double t) {
  const auto p = c.exact.point(t);
  const auto d = c.exact.tangent(t);
  return {exact::nearest_double(p[0]), exact::nearest_double(p[1]), exact::nearest_double(d[0]),
          exact::nearest_double(d[1])};
}

struct Lanes {
  std::vector<double> u, v, t, distance;
  void add(double u0, double v0, double t0) {
    u.push_back(u0);
    v.push_back(v0);
    t.push_back(t0);
    distance.push_back(-1.0);  // overwritten by every lane
  }
  void run(const Implementation& implementation, const TestCurve& c, Variant variant) {
    if (variant == Variant::nearest)
      implementation.nearest_newton(c.view(true), kNearestSettings, t.size(), u.data(), v.data(), t.data(),
                                    distance.data());
    else
      implementation.rational_newton(c.view(), kSettings, t.size(), u.data(), v.data(), t.data(), distance.data());
  }
};

// On-curve points P(t_true), made exactly and rounded: Newton from t_true + offset (offsets from
// the quadratic region to 0.02, where the first steps need the line search) ends at t_true, with
// distance at rounding level. Bound: the rounded point moves the nearest parameter by
// ~eps / |P'|, and speeds here are >= ~0.05, so 1e-13 has room; measured worst 5e-15.
TEST(RationalNewton, OnCurvePointsFromNearbyStarts) {
  for (const Variant variant : kVariants)
  for (const Implementation* implementation : available_implementations()) {
    std::mt19937_64 rng(20261128);
    double worst_t = 0, worst_distance = 0;
    for (int n = 1; n <= 24; ++n) {
      const TestCurve c = random_curve(n, rng);
      std::uniform_real_distribution<double> parameter(0.05, 0.95);
      Lanes lanes;
      std::vector<double> truth;
      for (int k = 0; k < 19; ++k) {  // 19: not a multiple of any vector width
        const double t_true = parameter(rng);
        if (test_support::thinned_out(static_cast<std::size_t>(k / 2))) continue;  // pairs: both signs; the draws stay
        const Exact p = at(c, t_true);
        const double offset = (k % 2 ? 1 : -1) * std::pow(10.0, -2.0 - (k % 8));
        lanes.add(p.x, p.y, t_true + offset);
        truth.push_back(t_true);
      }
      lanes.run(*implementation, c, variant);
      for (std::size_t l = 0; l < truth.size(); ++l) {
        SCOPED_TRACE(std::string(implementation->name) + name(variant) + " n=" + std::to_string(n) +
                   " lane " + std::to_string(l));
        ASSERT_FALSE(std::isnan(lanes.distance[l]));
        EXPECT_NEAR(lanes.t[l], truth[l], 1e-13);
        EXPECT_LE(lanes.distance[l], 1e-14);
        worst_t = std::max(worst_t, std::abs(lanes.t[l] - truth[l]));
        worst_distance = std::max(worst_distance, lanes.distance[l]);
      }
    }
    std::printf("%s%s: worst |t - t_true| %s, worst distance %s\n", std::string(implementation->name).c_str(),
                name(variant).c_str(), sci(worst_t).c_str(), sci(worst_distance).c_str());
  }
}

// Curves with weights 1e-4 to 1e2 apart, x and y each their own denominator: near a light end the
// curve moves fast (|P'| ~3e3 where the diagonal is ~1) and bends faster (|P''| ~1e8 |P'|), so a
// Newton step of 1e-10 leaves t ~1e-15 off, and a step of 4 eps in t moves P by ~3e-12. Points
// made exactly at a known t near that end (the first, a curve the stress tool drew), started 1e-9
// to 1e-15 from it on either side, as the formula's or B's t starts them: each kernel must end
// where the point's own rounding puts it, |t - t_true| <= 8 eps max(1, |P|) / |P'| + 8 eps t.
TEST(RationalNewton, FastCurvesNearAHeavyWeightEndWhereThePointsRoundingPutsThem) {
  std::vector<TestCurve> curves;
  {
    TestCurve c;
    c.x_num = {1.5235207977554004e-05, 28.289328656690962, 0.00012186585351739298};
    c.x_den = {0.0002863833741572606, 49.46298107028977, 0.00016343760945792746};
    c.y_num = {0.6694301138497353, 5.8761194841126345e-06, 93.99434020080926};
    c.y_den = {0.7671702712751561, 0.00012677404638355, 106.67998163362664};
    curves.push_back(completed(c));
  }
  std::mt19937_64 rng(20261206);
  std::uniform_real_distribution<double> coordinate(-1.0, 1.0), exponent(-4.0, 2.0);
  for (int n = 2; n <= 5; ++n)
    for (int k = 0; k < 3; ++k) {
      TestCurve c;
      for (int i = 0; i <= n; ++i) {
        // The ends light, the inner weights heavy: the curve hurries away from its ends.
        const double w = std::pow(10.0, (i == 0 || i == n) ? -4.0 + 0.5 * exponent(rng) / 3 : exponent(rng) + 1);
        const double wy = std::pow(10.0, (i == 0 || i == n) ? -4.0 : exponent(rng) + 1);
        c.x_num.push_back(w * coordinate(rng)), c.x_den.push_back(w);
        c.y_num.push_back(wy * coordinate(rng)), c.y_den.push_back(wy);
      }
      curves.push_back(completed(c));
    }
  std::uniform_real_distribution<double> near_end(-6.0, -4.0);
  for (const Variant variant : kVariants)
    for (const Implementation* implementation : available_implementations()) {
      double worst = 0;  // |t - t_true| over its bound
      for (std::size_t ci = 0; ci < curves.size(); ++ci) {
        const TestCurve& c = curves[ci];
        std::mt19937_64 draws(ci);
        Lanes lanes;
        std::vector<double> truth, bound;
        for (int k = 0; k < 28; ++k) {
          const double from_end = std::pow(10.0, near_end(draws));
          const double t_true = k % 4 < 2 ? from_end : 1.0 - from_end;
          const Exact p = at(c, t_true);
          const double speed = std::hypot(p.dx, p.dy), eps = std::numeric_limits<double>::epsilon();
          const double offset = (k % 2 ? 1 : -1) * std::pow(10.0, -9.0 - (k / 4) % 7);
          lanes.add(p.x, p.y, std::clamp(t_true + offset, 0.0, 1.0));
          truth.push_back(t_true);
          bound.push_back(8 * eps * std::max({1.0, std::abs(p.x), std::abs(p.y)}) / speed + 8 * eps * t_true);
        }
        lanes.run(*implementation, c, variant);
        for (std::size_t l = 0; l < truth.size(); ++l) {
          SCOPED_TRACE(std::string(implementation->name) + name(variant) + " curve " + std::to_string(ci) +
                       " lane " + std::to_string(l) + " t_true " + sci(truth[l]));
          ASSERT_FALSE(std::isnan(lanes.distance[l]));
          EXPECT_LE(std::abs(lanes.t[l] - truth[l]), bound[l]) << "t " << sci(lanes.t[l]);
          worst = std::max(worst, std::abs(lanes.t[l] - truth[l]) / bound[l]);
        }
      }
      std::printf("%s%s: worst |t - t_true| / bound %s\n", std::string(implementation->name).c_str(),
                  name(variant).c_str(), sci(worst).c_str());
    }
}

// Points off the curve along its normal at t_star: P(t_star) + delta N, with delta below half the
// radius of curvature, so t_star is the nearest parameter nearby and the distance is |delta|.
TEST(RationalNewton, OffCurvePointsAlongTheNormal) {
  for (const Variant variant : kVariants)
  for (const Implementation* implementation : available_implementations()) {
    std::mt19937_64 rng(7);
    int checked = 0;
    for (int n = 2; n <= 24; ++n) {
      const TestCurve c = random_curve(n, rng, /*separate=*/n % 2 == 1);
      std::uniform_real_distribution<double> parameter(0.1, 0.9);
      Lanes lanes;
      std::vector<double> truth, offset;
      for (int k = 0; k < 12; ++k) {
        const double t_star = parameter(rng);
        if (test_support::thinned_out(static_cast<std::size_t>(k / 2))) continue;  // pairs: both signs; the draws stay
        const Exact p = at(c, t_star);
        const double speed = std::hypot(p.dx, p.dy);
        const double delta = (k % 2 ? 1e-3 : -1e-4) * (1 + k);
        // Curvature from a central difference of the unit tangent (only to choose delta safely).
        const Exact a = at(c, t_star - 1e-5), b = at(c, t_star + 1e-5);
        const double turn = std::abs(std::atan2(a.dx * b.dy - a.dy * b.dx, a.dx * b.dx + a.dy * b.dy));
        const double curvature = turn / (2e-5 * speed);
        if (!(std::abs(delta) * curvature < 0.5)) continue;
        lanes.add(p.x - delta * p.dy / speed, p.y + delta * p.dx / speed, t_star + 1e-4);
        truth.push_back(t_star);
        offset.push_back(std::abs(delta));
      }
      lanes.run(*implementation, c, variant);
      for (std::size_t l = 0; l < truth.size(); ++l) {
        SCOPED_TRACE(std::string(implementation->name) + name(variant) + " n=" + std::to_string(n) +
                   " lane " + std::to_string(l));
        ASSERT_FALSE(std::isnan(lanes.distance[l]));
        // Off the curve f(t) = 0 still pins t to ~eps / (|P'|^2 (1 - delta kappa)); the point's own
        // rounding (~1e-16) moves t_star by as much.
        EXPECT_NEAR(lanes.t[l], truth[l], 1e-12);
        EXPECT_NEAR(lanes.distance[l], offset[l], 1e-14);
        ++checked;
      }
    }
    EXPECT_GE(checked, 150 / test_support::kSanitizerThinning);  // the filter must leave most of the 276 points
  }
}

// A batch where half the lanes settle at once (points on the curve, started at their t) and half
// are far from their roots (points off the curve, started 0.2 away): rational_newton runs such
// groups in two rounds, the lanes still iterating after the first regrouped (rational_newton-inl.hpp,
// rational_newton_groups). Every lane must end exactly as it does alone, in a batch of one (one
// round), whatever its place among the others; and batches longer than a round's 64 lanes too.
// nearest_newton likewise, whose last group runs one vector wide where one vector holds it
// (nearest_newton-inl.hpp, groups): a lane alone is always in such a group.
TEST(RationalNewton, ALaneEndsAsAloneWhateverItsGroup) {
  for (const Variant variant : {Variant::casteljau, Variant::nearest})
  for (const Implementation* implementation : available_implementations()) {
    std::mt19937_64 rng(31);
    std::uniform_real_distribution<double> parameter(0.05, 0.95), side(-0.05, 0.05);
    for (int n = 2; n <= 12; n += test_support::kSanitizerThinning) {
      const TestCurve c = random_curve(n, rng, /*separate=*/n % 3 == 0);
      for (const std::size_t count : {64u, 37u, 130u}) {
        SCOPED_TRACE(std::string(implementation->name) + name(variant) + " n=" + std::to_string(n) + " count " +
                     std::to_string(count));
        Lanes batch;
        for (std::size_t l = 0; l < count; ++l) {
          const double t_star = parameter(rng);
          const Exact p = at(c, t_star);
          if (l % 2 == 0) {
            batch.add(p.x, p.y, t_star);
          } else {
            const double start = t_star < 0.5 ? t_star + 0.2 : t_star - 0.2;
            batch.add(p.x + side(rng), p.y + side(rng), l % 10 == 1 ? 1.5 : start);  // 1.5: left to the caller
          }
        }
        Lanes alone = batch;
        batch.run(*implementation, c, variant);
        for (std::size_t l = 0; l < count; ++l) {
          Lanes one;
          one.add(alone.u[l], alone.v[l], alone.t[l]);
          one.run(*implementation, c, variant);
          EXPECT_TRUE(test_support::same_bits(batch.t[l], one.t[0])) << "lane " << l << ": " << sci(batch.t[l])
                                                                     << " alone " << sci(one.t[0]);
          EXPECT_TRUE(test_support::same_bits(batch.distance[l], one.distance[0]))
              << "lane " << l << ": " << sci(batch.distance[l]) << " alone " << sci(one.distance[0]);
        }
      }
    }
  }
}

// One denominator passed as one array (y_den the very pointer x_den, as the engine passes it): the
// kernel evaluates it once, with the bits it has from two equal arrays. Points on and off the
// curve, so that the halving steps' distances are compared too.
TEST(RationalNewton, OneDenominatorArrayGivesTheBitsOfTwo) {
  for (const Implementation* implementation : available_implementations()) {
    std::mt19937_64 rng(67);
    std::uniform_real_distribution<double> parameter(0.0, 1.0), side(-0.05, 0.05);
    for (int n = 1; n <= 12; ++n) {
      const TestCurve c = random_curve(n, rng);  // one denominator, held twice
      ASSERT_EQ(c.x_den, c.y_den);
      RationalCurve shared = c.view();
      shared.y_den = shared.x_den;
      Lanes two, one;
      for (int l = 0; l < 37; ++l) {
        const Exact p = at(c, parameter(rng));
        const double u = p.x + (l % 3 ? 0.0 : side(rng)), v = p.y + (l % 3 ? 0.0 : side(rng));
        two.add(u, v, parameter(rng));
      }
      one = two;
      two.run(*implementation, c, Variant::casteljau);
      implementation->rational_newton(shared, kSettings, one.t.size(), one.u.data(), one.v.data(), one.t.data(),
                                      one.distance.data());
      for (std::size_t l = 0; l < two.t.size(); ++l) {
        EXPECT_TRUE(test_support::same_bits(one.t[l], two.t[l])) << implementation->name << " n=" << n << " lane " << l;
        EXPECT_TRUE(test_support::same_bits(one.distance[l], two.distance[l]))
            << implementation->name << " n=" << n << " lane " << l;
      }
    }
  }
}

// settings.leave_distance: a lane whose distance at its start is beyond it stops there, its t as it
// came and its distance +inf, counted in the return; every other lane ends with exactly the bits
// it has without the setting, whatever the batch (130 lanes: two rounds of 64 and a rest). Points
// on the curve started within 1e-13 of their t (start distances below ~1e-12, measured exactly),
// and points 1e-9 to 1e-2 off it (start distances far above the 1e-10 of the setting); starts off
// [0, 1] come back NaN as always.
TEST(RationalNewton, LeavesTheLanesOffTheCurveAtTheirStartToTheCaller) {
  std::mt19937_64 rng(53);
  std::uniform_real_distribution<double> parameter(0.05, 0.95), angle(0.0, 6.283185307179586);
  for (int n = 2; n <= 12; n += test_support::kSanitizerThinning) {
    const TestCurve c = random_curve(n, rng, /*separate=*/n % 4 == 3);
    Lanes made;
    std::vector<int> kind;  // 0 on the curve, 1 off it, 2 a start off [0, 1]
    for (std::size_t l = 0; l < 130; ++l) {
      const double t_star = parameter(rng);
      const Exact p = at(c, t_star);
      if (l % 9 == 4) {
        made.add(p.x, p.y, 1.25), kind.push_back(2);
      } else if (l % 3 == 0) {
        made.add(p.x, p.y, t_star + 1e-13 * (l % 2 ? 1 : -1)), kind.push_back(0);
      } else {
        const double off = std::pow(10.0, -9.0 + static_cast<double>(l % 8)), a = angle(rng);
        made.add(p.x + off * std::cos(a), p.y + off * std::sin(a), t_star), kind.push_back(1);
      }
    }
    for (const Implementation* implementation : available_implementations()) {
      SCOPED_TRACE(std::string(implementation->name) + " n=" + std::to_string(n));
      Lanes plain = made;
      Lanes leaving = plain;
      const std::vector<double> starts = plain.t;
      const std::size_t none = implementation->rational_newton(c.view(), kSettings, plain.t.size(), plain.u.data(),
                                                               plain.v.data(), plain.t.data(), plain.distance.data());
      EXPECT_EQ(none, 0u);
      NewtonSettings settings = kSettings;
      settings.leave_distance = 1e-10;
      const std::size_t left = implementation->rational_newton(c.view(), settings, leaving.t.size(), leaving.u.data(),
                                                               leaving.v.data(), leaving.t.data(),
                                                               leaving.distance.data());
      std::size_t infinite = 0, off_curve = 0;
      for (std::size_t l = 0; l < kind.size(); ++l) {
        infinite += leaving.distance[l] == std::numeric_limits<double>::infinity();
        if (kind[l] == 1) {
          ++off_curve;
          EXPECT_EQ(leaving.distance[l], std::numeric_limits<double>::infinity()) << "lane " << l;
        } else if (kind[l] == 2) {
          EXPECT_TRUE(std::isnan(leaving.distance[l])) << "lane " << l;
        } else {
          EXPECT_TRUE(test_support::same_bits(leaving.distance[l], plain.distance[l])) << "lane " << l;
          EXPECT_LE(leaving.distance[l], 1e-14) << "lane " << l;
        }
        if (kind[l] != 0) {
          EXPECT_EQ(leaving.t[l], starts[l]) << "lane " << l;  // where it started
        } else {
          EXPECT_TRUE(test_support::same_bits(leaving.t[l], plain.t[l])) << "lane " << l;
        }
      }
      EXPECT_EQ(left, infinite);
      EXPECT_EQ(left, off_curve);
    }
  }
}

// A point past the end t = 1 along the tangent there: the nearest point of the segment is the end
// itself, and the iteration must stop there exactly (clamped), at distance |delta|.
TEST(RationalNewton, ClampsAtTheEndsOfTheSegment) {
  for (const Variant variant : kVariants)
  for (const Implementation* implementation : available_implementations()) {
    std::mt19937_64 rng(11);
    for (int n = 2; n <= 12; ++n) {
      const TestCurve c = random_curve(n, rng);
      Lanes lanes;
      for (double end : {0.0, 1.0}) {
        const Exact p = at(c, end);
        const double speed = std::hypot(p.dx, p.dy), sign = end == 1.0 ? 1.0 : -1.0, delta = 1e-3;
        lanes.add(p.x + sign * delta * p.dx / speed, p.y + sign * delta * p.dy / speed, end == 1.0 ? 1.0 - 1e-3 : 1e-3);
      }
      lanes.run(*implementation, c, variant);
      SCOPED_TRACE(std::string(implementation->name) + name(variant) + " n=" + std::to_string(n));
      EXPECT_EQ(lanes.t[0], 0.0);
      EXPECT_EQ(lanes.t[1], 1.0);
      EXPECT_NEAR(lanes.distance[0], 1e-3, 1e-14);
      EXPECT_NEAR(lanes.distance[1], 1e-3, 1e-14);
    }
  }
}

// Starts the kernel does not take (NaN, outside [0, 1], infinite) come back as given, with distance
// NaN; lanes around them are settled as usual; count 0 touches nothing.
TEST(RationalNewton, LeavesUnusableStartsToTheCaller) {
  for (const Variant variant : kVariants)
  for (const Implementation* implementation : available_implementations()) {
    std::mt19937_64 rng(3);
    const TestCurve c = random_curve(5, rng);
    Lanes lanes;
    const double starts[] = {0.3, kNaN, -0.25, 0.6, 1.5, std::numeric_limits<double>::infinity(), 0.8};
    std::vector<double> truth;
    for (double s : starts) {
      const double t_true = std::isfinite(s) && s >= 0 && s <= 1 ? s + 1e-7 : 0.5;
      const Exact p = at(c, t_true);
      lanes.add(p.x, p.y, s);
      truth.push_back(t_true);
    }
    lanes.run(*implementation, c, variant);
    SCOPED_TRACE(std::string(implementation->name) + name(variant));
    for (std::size_t l = 0; l < truth.size(); ++l) {
      const bool usable = std::isfinite(starts[l]) && starts[l] >= 0 && starts[l] <= 1;
      if (usable) {
        EXPECT_NEAR(lanes.t[l], truth[l], 1e-13) << l;
        EXPECT_LE(lanes.distance[l], 1e-14) << l;
      } else {
        EXPECT_TRUE(std::isnan(lanes.distance[l])) << l;
        EXPECT_TRUE(std::isnan(starts[l]) ? std::isnan(lanes.t[l]) : lanes.t[l] == starts[l]) << l;
      }
    }
    Lanes none;
    none.run(*implementation, c, variant);  // count 0
    double t = 0.5, distance = 7.0;
    if (variant == Variant::nearest)
      implementation->nearest_newton(c.view(true), kNearestSettings, 0, &t, &t, &t, &distance);
    else
      implementation->rational_newton(c.view(), kSettings, 0, &t, &t, &t, &distance);
    EXPECT_EQ(t, 0.5);
    EXPECT_EQ(distance, 7.0);
  }
}

// With Horner's jets (nearest_newton) no implementation has the scalar code's bits to match, but
// all of them give the same bits (the same fused multiply-adds on every target, the same
// operations in the same order per lane), whatever the lane's group: off-curve points from starts
// a sampling search would give, one denominator and two.
TEST(RationalNewton, HornerJetsGiveEveryImplementationTheSameBits) {
  for (const Variant variant : {Variant::nearest})
  for (const bool separate : {false, true}) {
  std::mt19937_64 rng(23);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  int compared = 0;
  for (int n = 1; n <= 24; ++n) {
    const TestCurve c = random_curve(n, rng, separate);
    Lanes given;
    for (int k = 0; k < 37; ++k) {
      const Exact p = at(c, unit(rng));
      const double off = 0.05 * (unit(rng) - 0.5);
      given.add(p.x + off, p.y - off, unit(rng));
    }
    std::vector<double> t0, distance0;
    for (const Implementation* implementation : available_implementations()) {
      Lanes lanes = given;
      lanes.run(*implementation, c, variant);
      if (t0.empty()) {
        t0 = lanes.t, distance0 = lanes.distance;
        continue;
      }
      SCOPED_TRACE(std::string(implementation->name) + name(variant) + (separate ? " separate" : "") +
                   " n=" + std::to_string(n));
      for (std::size_t l = 0; l < t0.size(); ++l) {
        EXPECT_TRUE(test_support::same_bits(lanes.t[l], t0[l])) << l;
        EXPECT_TRUE(test_support::same_bits(lanes.distance[l], distance0[l])) << l;
        ++compared;
      }
    }
  }
  if (available_implementations().size() > 1) {
    EXPECT_GT(compared, 0);
  }
  }
}

}  // namespace
}  // namespace bezinv::kernels
