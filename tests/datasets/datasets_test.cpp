// The generators do what they claim. Every check here evaluates with exact rationals
// (tests/support/exact.hpp, GMP) or with sampling written in this file, never with the generators'
// own long double evaluation (datasets_gen/src/reference_evaluation.cpp), so a generator bug cannot
// vouch for itself.
#include <gtest/gtest.h>

#include <algorithm>
#include <cstddef>
#include <cmath>
#include <iterator>
#include <numbers>
#include <random>
#include <string>
#include <vector>

#include "support/curve_kinds.hpp"
#include "bezinv/curve.hpp"
#include "bezinv/datasets/curve_sampling.hpp"
#include "bezinv/datasets/degree_elevation.hpp"
#include "bezinv/datasets/improper.hpp"
#include "bezinv/datasets/off_curve_points.hpp"
#include "bezinv/datasets/on_curve_points.hpp"
#include "bezinv/datasets/paper_curves.hpp"
#include "bezinv/datasets/random_curve.hpp"
#include "bezinv/datasets/random_numbers.hpp"
#include "bezinv/datasets/self_intersection.hpp"
#include "bezinv/datasets/translation.hpp"
#include "support/exact.hpp"
#include "support/sanitizers.hpp"

namespace bezinv::datasets {
namespace {

using test_support::kAllKinds;

constexpr ControlPolygon kPolygons[] = {ControlPolygon::unit_square, ControlPolygon::perturbed_arc};

exact::RationalCurve exact_curve(const Curve& c) {
  return {exact::to_exact(c.x_num), exact::to_exact(c.x_den), exact::to_exact(c.y_num), exact::to_exact(c.y_den)};
}

// |a - b| for an exact point a and a double point b, as a double (the difference is exact first).
double gap(const std::array<mpq_class, 2>& a, Point b) {
  const mpq_class dx = a[0] - mpq_class(b.x), dy = a[1] - mpq_class(b.y);
  return std::hypot(dx.get_d(), dy.get_d());
}
double gap(const std::array<mpq_class, 2>& a, const std::array<mpq_class, 2>& b) {
  const mpq_class dx = a[0] - b[0], dy = a[1] - b[1];
  return std::hypot(dx.get_d(), dy.get_d());
}
double norm(const std::array<mpq_class, 2>& a) { return std::hypot(a[0].get_d(), a[1].get_d()); }

std::string label(CurveKind kind, int degree, std::uint64_t seed) {
  return std::string(to_string(kind)) + " degree " + std::to_string(degree) + " seed " + std::to_string(seed);
}

// Long double P(t) by the textbook sum of C(n,i) (1-t)^{n-i} t^i, for dense brute-force sampling
// (exact rationals would take minutes at 20000 samples).
struct Sampled { long double x, y; };
Sampled textbook_point(const Curve& c, long double t) {
  const int n = c.degree();
  long double xn = 0, xd = 0, yn = 0, yd = 0, binom = 1;
  long double one_minus[kMaxDegree + 1], power[kMaxDegree + 1];
  one_minus[0] = power[0] = 1;
  for (int i = 1; i <= n; ++i) { one_minus[i] = one_minus[i - 1] * (1 - t); power[i] = power[i - 1] * t; }
  for (int i = 0; i <= n; ++i) {
    if (i > 0) binom = binom * (n - i + 1) / i;
    const long double b = binom * one_minus[n - i] * power[i];
    xn += b * c.x_num[i]; xd += b * c.x_den[i]; yn += b * c.y_num[i]; yd += b * c.y_den[i];
  }
  return {xn / xd, yn / yd};
}

// `count` + 1 samples at t = lo + (hi - lo) i / count.
std::vector<std::pair<long double, Sampled>> textbook_samples(const Curve& c, long double lo, long double hi, int count) {
  std::vector<std::pair<long double, Sampled>> out;
  for (int i = 0; i <= count; ++i) {
    const long double t = lo + (hi - lo) * i / count;
    out.push_back({t, textbook_point(c, t)});
  }
  return out;
}

double distance_to(const Sampled& p, Point q) {
  return std::hypot(static_cast<double>(p.x - q.x), static_cast<double>(p.y - q.y));
}

TEST(DatasetsRandom, SameSeedSameCurveAndUniformInRange) {
  for (CurveKind kind : kAllKinds)
    for (ControlPolygon polygon : kPolygons) {
      std::mt19937_64 a(42), b(42), c(43);
      const Curve ca = random_curve(kind, 7, a, polygon), cb = random_curve(kind, 7, b, polygon);
      const Curve cc = random_curve(kind, 7, c, polygon);
      EXPECT_EQ(ca.x_num, cb.x_num);
      EXPECT_EQ(ca.y_den, cb.y_den);
      EXPECT_NE(ca.x_num, cc.x_num);
    }
  std::mt19937_64 rng(1);
  double lo = 1, hi = 0;
  for (int i = 0; i < 10000; ++i) {
    const double u = uniform(rng, 0.25, 0.5);
    lo = std::min(lo, u);
    hi = std::max(hi, u);
    const int k = uniform_int(rng, -2, 3);
    ASSERT_TRUE(k >= -2 && k <= 3);
  }
  EXPECT_GE(lo, 0.25);
  EXPECT_LT(hi, 0.5);
  EXPECT_LT(lo, 0.2501);
  EXPECT_GT(hi, 0.4999);
}

TEST(DatasetsRandom, KindsHaveTheirShape) {
  for (CurveKind kind : kAllKinds)
    for (ControlPolygon polygon : kPolygons)
      for (int degree = 1; degree <= 20; ++degree) {
        std::mt19937_64 rng(degree);
        const Curve c = random_curve(kind, degree, rng, polygon);
        SCOPED_TRACE(label(kind, degree, degree) + " " + to_string(polygon));
        ASSERT_EQ(c.degree(), degree);
        EXPECT_EQ(c.kind, kind);
        EXPECT_NO_THROW(validate(c));
        EXPECT_EQ(c.common_denominator(), kind != CurveKind::rational);
        for (int i = 0; i <= degree; ++i) {
          if (kind == CurveKind::bezier) {
            EXPECT_EQ(c.x_den[i], 1.0);
          } else {
            EXPECT_TRUE(c.x_den[i] >= 0.5 && c.x_den[i] <= 2.0) << c.x_den[i];
            EXPECT_TRUE(c.y_den[i] >= 0.5 && c.y_den[i] <= 2.0) << c.y_den[i];
          }
          if (polygon == ControlPolygon::unit_square) {
            const double a = c.x_num[i] / c.x_den[i], b = c.y_num[i] / c.y_den[i];
            EXPECT_TRUE(a >= -1e-15 && a <= 1 + 1e-15 && b >= -1e-15 && b <= 1 + 1e-15) << a << " " << b;
          }
        }
      }
}

// The transcription of the paper's curves, checked against the exact values printed in the paper.
TEST(DatasetsPaperCurves, MatchThePaper) {
  {
    const auto P = exact_curve(paper_example2_curve()).point(mpq_class(1, 7));
    EXPECT_EQ(P[0], mpq_class(mpz_class("78193109744768"), mpz_class("9191995131007")));
    EXPECT_EQ(P[1], mpq_class(mpz_class("131831466405881"), mpz_class("9191995131007")));
    EXPECT_EQ(paper_example2_curve().degree(), 15);
  }
  {
    const auto P = exact_curve(paper_example4_curve()).point(mpq_class(1, 3));
    EXPECT_EQ(P[0], mpq_class(8, 3));
    EXPECT_EQ(P[1], mpq_class(109, 45));
  }
  {
    // Example 1: p = X - x W = 4 - x - 6t^2 + 8t^3 + (1 - 2x) t^4, q = Y - y = 2 - y + 4t - 6t^2 + 4t^3.
    const Curve c = paper_example1_curve();
    EXPECT_EQ(c.kind, CurveKind::rational);
    const auto X = exact::power_from_bernstein(exact::to_exact(c.x_num));
    const auto W = exact::power_from_bernstein(exact::to_exact(c.x_den));
    const auto Y = exact::power_from_bernstein(exact::to_exact(c.y_num));
    const auto V = exact::power_from_bernstein(exact::to_exact(c.y_den));
    EXPECT_EQ(X, (exact::Poly{4, 0, -6, 8, 1}));
    EXPECT_EQ(W, (exact::Poly{1, 0, 0, 0, 2}));
    EXPECT_EQ(Y, (exact::Poly{2, 4, -6, 4, 0}));
    EXPECT_EQ(V, (exact::Poly{1, 0, 0, 0, 0}));
    // Example 3: P(1/3) ~ (3.5542169, 2.8148148) to the 8 digits printed.
    const auto P = exact_curve(c).point(mpq_class(1, 3));
    EXPECT_NEAR(P[0].get_d(), 3.5542169, 1e-7);
    EXPECT_NEAR(P[1].get_d(), 2.8148148, 1e-7);
  }
  {
    const auto P = exact_curve(default_cubic_curve()).point(mpq_class(1, 2));
    EXPECT_EQ(P[0], 2);
    EXPECT_EQ(P[1], mpq_class(3, 2));
  }
}

// Every on-curve set: the point is P(t) rounded, checked exactly.
// Under the sanitizers each kind and polygon keeps every fourth degree, a different one each, so
// that every degree is still checked (support/sanitizers.hpp).
bool degree_thinned_out(CurveKind kind, ControlPolygon polygon, std::size_t degree_index) {
  const std::size_t kind_and_polygon = 2 * static_cast<std::size_t>(kind) + (polygon == kPolygons[1]);
  return test_support::thinned_out(kind_and_polygon + degree_index);
}

TEST(DatasetsOnCurve, PointsAreOnTheCurveAtTheirParameter) {
  int checked = 0;
  constexpr int kDegrees[] = {1, 2, 3, 5, 8, 13, 20};
  for (CurveKind kind : kAllKinds)
    for (ControlPolygon polygon : kPolygons)
      for (std::size_t d = 0; d < std::size(kDegrees); ++d) {
        if (degree_thinned_out(kind, polygon, d)) continue;
        const int degree = kDegrees[d];
        const std::uint64_t seed = 1000 + degree;
        std::mt19937_64 rng(seed);
        const CurveSampling sampling(random_curve(kind, degree, rng, polygon));
        const auto exact = exact_curve(sampling.curve());
        const double diagonal = sampling.diagonal();
        SCOPED_TRACE(label(kind, degree, seed) + " " + to_string(polygon));
        const auto segment = segment_points(sampling, 12, rng);
        const auto ends = end_points(sampling);
        const auto extension = extension_points(sampling, 12, rng);
        // The retries fill the sets (a shortfall would mean the isolation check rejects everything).
        EXPECT_EQ(segment.size(), 12u);
        EXPECT_GE(ends.size(), 4u);
        EXPECT_GE(extension.size(), 6u);
        for (const auto* set : {&segment, &ends, &extension})
          for (const KnownPoint& k : *set) {
            const auto P = exact.point(mpq_class(k.t));
            // Rounding to the nearest double: at most half an ulp per coordinate.
            const double bound = 1.2e-16 * std::max(diagonal, norm(P));
            EXPECT_LE(gap(P, k.point), bound) << "t = " << k.t;
            // `distance` is the rounding itself, to long double accuracy (a small fraction of it).
            EXPECT_NEAR(k.distance, gap(P, k.point), 0.02 * bound);
            const auto T = exact.tangent(mpq_class(k.t));
            EXPECT_NEAR(k.speed, norm(T), 1e-12 * norm(T));
            EXPECT_GE(k.scale, 0.999 * norm(P));
            ++checked;
          }
        for (const KnownPoint& k : segment) EXPECT_TRUE(k.t >= 0 && k.t <= 1);
        for (const KnownPoint& k : extension)
          EXPECT_TRUE((k.t >= -0.3 && k.t <= -0.01) || (k.t >= 1.01 && k.t <= 1.3)) << k.t;
        EXPECT_EQ(ends.front().t == 0.0 || ends.back().t == 1.0, true);
      }
  EXPECT_GT(checked, 800 / test_support::kSanitizerThinning);
}

// Isolation, checked by brute force: no other branch within kIsolation * diagonal.
TEST(DatasetsOnCurve, SegmentPointsAreIsolated) {
  for (CurveKind kind : kAllKinds)
    for (int degree : {3, 8, 20}) {
      const std::uint64_t seed = 77 + degree;
      std::mt19937_64 rng(seed);
      const CurveSampling sampling(random_curve(kind, degree, rng));
      SCOPED_TRACE(label(kind, degree, seed));
      const auto points = segment_points(sampling, 6, rng);
      const double margin = kIsolation * sampling.diagonal();
      const auto samples = textbook_samples(sampling.curve(), 0, 1, 50000);
      for (const KnownPoint& k : points) {
        // Away from the own branch (beyond the parameter distance at which the branch itself has
        // moved 10 margins away), the curve stays farther than the margin.
        const double own = 10 * margin / k.speed;
        for (const auto& [t, p] : samples) {
          if (std::abs(static_cast<double>(t) - k.t) < own) continue;
          ASSERT_GT(distance_to(p, k.point), 0.99 * margin) << "t = " << k.t << ", other branch at " << static_cast<double>(t);
        }
      }
    }
}

// Off-curve points: the constructed parameter is the nearest point of the segment (brute force
// over 20001 samples plus the ends), at the stated distance, and the extension keeps away.
TEST(DatasetsOffCurve, NearestPointIsTheConstructedOne) {
  int checked = 0, at_ends = 0;
  constexpr int kDegrees[] = {1, 2, 4, 9, 15, 20};
  for (CurveKind kind : kAllKinds)
    for (ControlPolygon polygon : kPolygons)
      for (std::size_t d = 0; d < std::size(kDegrees); ++d) {
        if (degree_thinned_out(kind, polygon, d)) continue;
        const int degree = kDegrees[d];
        const std::uint64_t seed = 500 + degree;
        std::mt19937_64 rng(seed);
        const CurveSampling sampling(random_curve(kind, degree, rng, polygon));
        const auto exact = exact_curve(sampling.curve());
        const double diagonal = sampling.diagonal();
        SCOPED_TRACE(label(kind, degree, seed) + " " + to_string(polygon));
        const auto points = normal_offset_points(sampling, 12, 1e-5, 0.1, rng);
        EXPECT_GE(points.size(), 6u);
        const auto segment = textbook_samples(sampling.curve(), 0, 1, 20000);
        auto extension = textbook_samples(sampling.curve(), -4, -0.001, 4000);
        const auto right = textbook_samples(sampling.curve(), 1.001, 5, 4000);
        extension.insert(extension.end(), right.begin(), right.end());
        for (const KnownPoint& k : points) {
          ASSERT_TRUE(k.t >= 0 && k.t <= 1) << k.t;
          const auto P = exact.point(mpq_class(k.t));
          EXPECT_NEAR(gap(P, k.point), k.distance, 1e-12 * k.distance) << "t = " << k.t;
          EXPECT_GE(k.distance, 0.99e-5 * diagonal);
          EXPECT_LE(k.distance, 0.11 * diagonal);
          if (k.t == 0.0 || k.t == 1.0) ++at_ends;
          // t is the nearest parameter to the last bit: in exact arithmetic, neither neighbouring
          // double parameter (inside [0,1]) is closer.
          auto squared_distance = [&](double t) {
            const auto Q = exact.point(mpq_class(t));
            const mpq_class dx = Q[0] - mpq_class(k.point.x), dy = Q[1] - mpq_class(k.point.y);
            return mpq_class(dx * dx + dy * dy);
          };
          const mpq_class here = squared_distance(k.t);
          for (double toward : {-1.0, 2.0}) {
            const double neighbour = std::nextafter(k.t, toward);
            if (neighbour >= 0 && neighbour <= 1) {
              EXPECT_LE(here, squared_distance(neighbour)) << "t = " << k.t;
            }
          }
          for (const auto& [t, p] : segment)
            ASSERT_GE(distance_to(p, k.point), k.distance * (1 - 1e-12))
                << "t = " << k.t << ": sample " << static_cast<double>(t) << " is closer";
          for (const auto& [t, p] : extension) {
            const double d = distance_to(p, k.point);
            if (std::isfinite(d)) {
              ASSERT_GT(d, 0.99 * kIsolation * diagonal) << "extension at " << static_cast<double>(t);
            }
          }
          ++checked;
        }
      }
  EXPECT_GT(checked, 300 / test_support::kSanitizerThinning);
  EXPECT_GT(at_ends, 5 / test_support::kSanitizerThinning);
}

TEST(DatasetsSelfIntersection, ConstructedCrossingHolds) {
  for (CurveKind kind : kAllKinds)
    for (int degree = 3; degree <= 20; degree += 1) {
      const std::uint64_t seed = 9000 + degree;
      std::mt19937_64 rng(seed);
      const double t1 = uniform(rng, 0.05, 0.45), t2 = uniform(rng, 0.55, 0.95);
      SCOPED_TRACE(label(kind, degree, seed) + " t1 " + std::to_string(t1) + " t2 " + std::to_string(t2));
      const Curve c = with_self_intersection(kind, degree, t1, t2, rng);
      EXPECT_EQ(c.kind, kind);
      EXPECT_EQ(c.degree(), degree);
      EXPECT_NO_THROW(validate(c));
      const auto exact = exact_curve(c);
      const auto P1 = exact.point(mpq_class(t1)), P2 = exact.point(mpq_class(t2));
      const CurveSampling sampling(c);
      EXPECT_LE(gap(P1, P2), 1e-14 * sampling.diagonal());
      const auto T1 = exact.tangent(mpq_class(t1)), T2 = exact.tangent(mpq_class(t2));
      const double sine = std::abs(mpq_class(T1[0] * T2[1] - T1[1] * T2[0]).get_d()) / (norm(T1) * norm(T2));
      EXPECT_GT(sine, 0.25);
      const auto points = crossing_points(sampling, t1, t2, 4, 3e-7, rng);
      ASSERT_GE(points.size(), 3u);
      EXPECT_EQ(points[0].t, t1);
      EXPECT_EQ(points[0].t2, t2);
      EXPECT_LE(gap(P1, points[0].point), 1.2e-16 * std::max(norm(P1), sampling.diagonal()));
      for (std::size_t i = 1; i < points.size(); ++i) {
        const KnownPoint& k = points[i];
        EXPECT_NEAR(gap(P1, k.point), 3e-7 * sampling.diagonal(), 1e-9 * sampling.diagonal());
        // Nearest points of the two branches: close to t1, t2 and at most the offset away.
        EXPECT_NEAR(k.t, t1, 1e-4);
        EXPECT_NEAR(k.t2, t2, 1e-4);
        EXPECT_LE(gap(exact.point(mpq_class(k.t)), k.point), 3.01e-7 * sampling.diagonal());
        EXPECT_LE(gap(exact.point(mpq_class(k.t2)), k.point), 3.01e-7 * sampling.diagonal());
      }
    }
  std::mt19937_64 rng(1);
  EXPECT_THROW(with_self_intersection(CurveKind::bezier, 2, 0.2, 0.8, rng), std::invalid_argument);
  EXPECT_THROW(with_self_intersection(CurveKind::bezier, 5, 0.8, 0.2, rng), std::invalid_argument);
}

TEST(DatasetsDegreeElevation, PreservesTheCurve) {
  for (CurveKind kind : kAllKinds)
    for (int degree : {1, 2, 3, 7, 12, 20})
      for (int times : {1, 3}) {
        const std::uint64_t seed = 31 * degree + times;
        std::mt19937_64 rng(seed);
        const Curve c = random_curve(kind, degree, rng, ControlPolygon::perturbed_arc);
        const Curve e = degree_elevated(c, times);
        SCOPED_TRACE(label(kind, degree, seed) + " times " + std::to_string(times));
        ASSERT_EQ(e.degree(), degree + times);
        EXPECT_EQ(e.kind, kind);
        EXPECT_EQ(e.common_denominator(), c.common_denominator());
        if (kind == CurveKind::bezier) {
          for (double w : e.x_den) EXPECT_EQ(w, 1.0);
        }
        // Coefficient by coefficient against exact elevation (through the power basis).
        const auto expected = exact::elevate(exact::to_exact(c.x_num), degree + times);
        for (int i = 0; i <= degree + times; ++i)
          EXPECT_NEAR(e.x_num[i], expected[i].get_d(), 4e-16 * times * (1 + std::abs(e.x_num[i]))) << i;
        const auto P = exact_curve(c), Q = exact_curve(e);
        const double diagonal = control_diagonal(c);
        for (double t : {0.0, 0.1, 1.0 / 3, 0.5, 0.77, 1.0}) {
          const mpq_class tq(t);
          EXPECT_LE(gap(P.point(tq), Q.point(tq)), 1e-14 * diagonal) << "t = " << t;
        }
      }
}

TEST(DatasetsTranslation, MovesEveryPointByTheOffset) {
  for (CurveKind kind : kAllKinds)
    for (int degree : {1, 4, 15}) {
      std::mt19937_64 rng(degree);
      const Curve c = random_curve(kind, degree, rng);
      const Curve m = translated(c, 1e6, -1e6);
      EXPECT_EQ(m.kind, kind);
      EXPECT_EQ(m.x_den, c.x_den);
      const auto P = exact_curve(c), Q = exact_curve(m);
      for (double t : {0.0, 0.3, 0.9, 1.0}) {
        const mpq_class tq(t);
        const auto p = P.point(tq), q = Q.point(tq);
        const mpq_class dx = q[0] - p[0] - 1000000, dy = q[1] - p[1] + 1000000;
        // Each coefficient is rounded once at magnitude ~1e6 (ulp 1.2e-10).
        EXPECT_LE(std::hypot(dx.get_d(), dy.get_d()), 1e-9) << to_string(kind) << " " << degree << " t " << t;
      }
    }
}

// improper(Q)(t) = Q(t^2), exactly up to the rounding of the coefficients; and each coefficient
// matches an independent route (power basis: substitute t^2, convert back).
TEST(DatasetsImproper, EqualsQOfTSquared) {
  for (CurveKind kind : kAllKinds)
    for (int m = 1; m <= 10; ++m) {
      std::mt19937_64 rng(m);
      const Curve q = random_curve(kind, m, rng, ControlPolygon::perturbed_arc);
      const Curve p = improper(q);
      SCOPED_TRACE(label(kind, m, m));
      ASSERT_EQ(p.degree(), 2 * m);
      EXPECT_EQ(p.kind, kind);
      EXPECT_EQ(p.common_denominator(), q.common_denominator());
      EXPECT_NO_THROW(validate(p));
      const auto Q = exact_curve(q), P = exact_curve(p);
      const double diagonal = control_diagonal(q);
      // On the segment: the rounding of the coefficients is not amplified there (on the extension
      // it is, by (|1-t| + |t|)^{2m}; the coefficient check below covers every t).
      for (double t : {0.0, 0.125, 0.4, 0.7, 1.0}) {
        const mpq_class tq(t);
        EXPECT_LE(gap(P.point(tq), Q.point(tq * tq)), 1e-14 * std::max(diagonal, norm(Q.point(tq * tq)))) << t;
      }
      const std::vector<double>* fields_q[] = {&q.x_num, &q.x_den, &q.y_num, &q.y_den};
      const std::vector<double>* fields_p[] = {&p.x_num, &p.x_den, &p.y_num, &p.y_den};
      for (int f = 0; f < 4; ++f) {
        const auto a = exact::power_from_bernstein(exact::to_exact(*fields_q[f]));
        exact::Poly squared(2 * m + 1, 0);
        for (int k = 0; k <= m; ++k) squared[2 * k] = a[k];
        const auto expected = exact::bernstein_from_power(squared, 2 * m);
        for (int i = 0; i <= 2 * m; ++i)
          EXPECT_NEAR((*fields_p[f])[i], expected[i].get_d(), 1e-15 * (1 + std::abs(expected[i].get_d())));
      }
    }
}

}  // namespace
}  // namespace bezinv::datasets
