// --off-curve projection against exact rational arithmetic (GMP): for a conic or a cubic, the
// inversion formula's projection of an off-curve point P* is where the line from the formula's
// centre C through P* meets the curve again (Wang & Joe, Sect. 4). That parameter is computed here
// exactly, independently of the engine's formula: the line through C and P* meets the curve where
//     c(t) = (X - cx W)(y* - cy) - (Y - cy W)(x* - cx) = 0,
// a polynomial of degree n whose other roots are C's own parameters, known by construction:
//   - a conic's centre is P(inf) = (X_2, Y_2) / W_2 (power-basis leading coefficients; the engine's
//     default): c's leading coefficient vanishes and c is linear;
//   - a cubic's centre is its double point, at parameters t1, t2 made so: c / ((t - t1)(t - t2)) is
//     linear (the division's remainder must vanish, which checks the construction).
// The one root left is the exact projection t*, which the engine's t must match to rounding.
#include <gtest/gtest.h>
#include <gmpxx.h>

#include <array>
#include <cmath>
#include <cstdio>
#include <random>
#include <vector>

#include "bezinv/curve.hpp"
#include "bezinv/invert.hpp"
#include "bezinv/plan.hpp"
#include "support/exact.hpp"

namespace bezinv {
namespace {

using exact::Poly;

// Power-basis coefficients (index = power) of the Bernstein coefficients c.
Poly projection_power_of(const std::vector<double>& c) { return exact::power_from_bernstein(exact::to_exact(c)); }

Poly projection_combine(const Poly& a, const mpq_class& s, const Poly& b) {  // a - s b
  Poly out(std::max(a.size(), b.size()));
  for (std::size_t i = 0; i < out.size(); ++i) {
    if (i < a.size()) out[i] += a[i];
    if (i < b.size()) out[i] -= s * b[i];
  }
  return out;
}

Poly projection_scaled(Poly a, const mpq_class& s) {
  for (mpq_class& c : a) c *= s;
  return a;
}

// a / d for power-basis polynomials; the remainder goes to *remainder.
Poly projection_divide(Poly a, const Poly& d, Poly* remainder) {
  while (!a.empty() && a.back() == 0) a.pop_back();
  const int dd = static_cast<int>(d.size()) - 1;
  Poly q(a.size() > d.size() - 1 ? a.size() - dd : 1);
  for (int k = static_cast<int>(a.size()) - 1; k >= dd; --k) {
    const mpq_class f = a[k] / d[dd];
    q[k - dd] = f;
    for (int j = 0; j <= dd; ++j) a[k - dd + j] -= f * d[j];
  }
  a.resize(dd);
  *remainder = a;
  return q;
}

struct ProjectedCurve {
  Curve curve;
  mpq_class cx, cy;  // the formula's centre
  Poly centre_factor;  // power basis: 1 (conic, centre at infinity) or (t - t1)(t - t2)
};

// t* exactly for the point (x, y): the root of c(t) / centre_factor, or no value (c vanishes
// identically, or the line meets the curve again only at infinity).
bool projection_exact_parameter(const ProjectedCurve& e, double x, double y, mpq_class* t) {
  const Curve& c = e.curve;
  const Poly X = projection_power_of(c.x_num), Y = projection_power_of(c.y_num), W = projection_power_of(c.x_den);
  const mpq_class dx = mpq_class(x) - e.cx, dy = mpq_class(y) - e.cy;
  Poly cross = projection_combine(projection_scaled(projection_combine(X, e.cx, W), dy), 1, projection_scaled(projection_combine(Y, e.cy, W), dx));
  Poly remainder;
  const Poly linear = projection_divide(cross, e.centre_factor, &remainder);
  for (const mpq_class& r : remainder) EXPECT_EQ(r, 0) << "the centre is not on the line: the construction is wrong";
  if (linear.size() < 2 || linear[1] == 0) return false;
  for (std::size_t k = 2; k < linear.size(); ++k) EXPECT_EQ(linear[k], 0) << "c / factor is not linear";
  *t = -linear[0] / linear[1];
  return true;
}

// Random conics with integer control points and weights, centre P(inf).
ProjectedCurve projection_random_conic(std::mt19937_64& rng) {
  std::uniform_int_distribution<int> coordinate(-8, 8), weight(1, 5);
  for (;;) {
    std::vector<std::array<double, 2>> p(3);
    std::vector<double> w(3);
    for (int i = 0; i < 3; ++i) p[i] = {double(coordinate(rng)), double(coordinate(rng))}, w[i] = weight(rng);
    const double cross = (p[1][0] - p[0][0]) * (p[2][1] - p[0][1]) - (p[1][1] - p[0][1]) * (p[2][0] - p[0][0]);
    const mpq_class w2 = mpq_class(w[0]) - 2 * mpq_class(w[1]) + mpq_class(w[2]);
    if (cross == 0 || w2 == 0) continue;  // a line, or a parabola (centre at infinity in direction only)
    ProjectedCurve e{Curve::rational_bezier("conic", p, w), 0, 0, Poly{1}};
    const Poly X = projection_power_of(e.curve.x_num), Y = projection_power_of(e.curve.y_num), W = projection_power_of(e.curve.x_den);
    e.cx = X[2] / W[2];
    e.cy = Y[2] / W[2];
    return e;
  }
}

// Polynomial cubics with a double point at t = 1/4 and 3/4: per coordinate,
// P(1/4) = P(3/4) is 26 P0 + 18 P1 - 18 P2 - 26 P3 = 0, met by P2 = P1 - 13 k, P3 = P0 + 9 k.
ProjectedCurve projection_crossing_cubic(std::mt19937_64& rng) {
  std::uniform_int_distribution<int> coordinate(-8, 8), step(-2, 2);
  for (;;) {
    const int kx = step(rng), ky = step(rng);
    if (kx == 0 && ky == 0) continue;
    std::array<double, 2> p0{double(coordinate(rng)), double(coordinate(rng))},
        p1{double(coordinate(rng)), double(coordinate(rng))};
    if (p0 == p1) continue;
    const std::vector<std::array<double, 2>> p{p0, p1, {p1[0] - 13 * kx, p1[1] - 13 * ky}, {p0[0] + 9 * kx, p0[1] + 9 * ky}};
    ProjectedCurve e{Curve::bezier("cubic", p), 0, 0, Poly{mpq_class(3, 16), -1, 1}};
    const mpq_class quarter(1, 4);
    e.cx = exact::bernstein_value(exact::to_exact(e.curve.x_num), quarter);
    e.cy = exact::bernstein_value(exact::to_exact(e.curve.y_num), quarter);
    EXPECT_EQ(e.cx, exact::bernstein_value(exact::to_exact(e.curve.x_num), mpq_class(3, 4)));
    return e;
  }
}

// The paper's Example 3 (P = (0,0), (1,1), (0,1), (1,0), w = 1, 2, 2, 1; double point (1/2, 3/5) at
// the roots of 7t^2 - 7t + 1) under a random integer affine map, which moves the double point with
// the curve and keeps its parameters.
ProjectedCurve projection_example_3(std::mt19937_64& rng) {
  std::uniform_int_distribution<int> entry(-4, 4);
  for (;;) {
    const int a = entry(rng), b = entry(rng), c = entry(rng), d = entry(rng), ex = entry(rng), ey = entry(rng);
    if (a * d - b * c == 0) continue;
    auto map = [&](double x, double y) { return std::array<double, 2>{a * x + b * y + ex, c * x + d * y + ey}; };
    const std::vector<std::array<double, 2>> p{map(0, 0), map(1, 1), map(0, 1), map(1, 0)};
    ProjectedCurve e{Curve::rational_bezier("example3", p, {1, 2, 2, 1}), 0, 0, Poly{mpq_class(1, 7), -1, 1}};
    const mpq_class x(1, 2), y(3, 5);
    e.cx = a * x + b * y + ex;
    e.cy = c * x + d * y + ey;
    return e;
  }
}

// Off-curve points around the segment: P(s) plus 2% to 30% of the diagonal in a random direction,
// rounded to multiples of 1/1024 (exact in double and in mpq).
std::vector<Point> projection_points_around(const Curve& curve, double diagonal, std::mt19937_64& rng) {
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  std::vector<Point> out;
  for (int k = 0; k < 40; ++k) {
    const auto p = curve.point(unit(rng));
    const double angle = 2 * M_PI * unit(rng), r = diagonal * (0.02 + 0.28 * unit(rng));
    out.push_back({std::round((p[0] + r * std::cos(angle)) * 1024) / 1024, std::round((p[1] + r * std::sin(angle)) * 1024) / 1024});
  }
  return out;
}

void expect_exact_projections(ProjectedCurve (*make)(std::mt19937_64&), int curves, std::uint64_t seed, int* projected,
                              int* off_curve) {
  std::mt19937_64 rng(seed);
  for (int i = 0; i < curves; ++i) {
    const ProjectedCurve e = make(rng);
    const InversionPlan plan = make_plan(e.curve);
    const std::vector<Point> points = projection_points_around(e.curve, plan.diagonal(), rng);
    std::vector<PointResult> results(points.size());
    invert(plan, points, results, {.off_curve = OffCurve::projection});
    for (std::size_t k = 0; k < points.size(); ++k) {
      const PointResult& r = results[k];
      *off_curve += r.status == Status::off_curve;
      if (r.path != Path::projection) continue;
      ++*projected;
      mpq_class t;
      ASSERT_TRUE(projection_exact_parameter(e, points[k].x, points[k].y, &t))
          << e.curve.id << " " << i << ": the engine projected a point whose line meets the curve only at its centre";
      const double expected = t.get_d();
      EXPECT_LE(std::abs(r.t - expected), 1e-9 * std::max(1.0, std::abs(expected)))
          << e.curve.id << " " << i << ", point (" << points[k].x << ", " << points[k].y << "): t " << r.t
          << ", exact " << expected;
    }
  }
}

TEST(Projection, AConicsPointIsProjectedFromPAtInfinity) {
  int projected = 0, off_curve = 0;
  expect_exact_projections(projection_random_conic, 60, 71, &projected, &off_curve);
  std::printf("[ measured ] %d of %d off_curve rows projected\n", projected, off_curve);
  EXPECT_GT(projected, off_curve * 3 / 4);
}

TEST(Projection, ACubicsPointIsProjectedFromItsDoublePoint) {
  int projected = 0, off_curve = 0;
  expect_exact_projections(projection_crossing_cubic, 40, 72, &projected, &off_curve);
  expect_exact_projections(projection_example_3, 40, 73, &projected, &off_curve);
  std::printf("[ measured ] %d of %d off_curve rows projected\n", projected, off_curve);
  EXPECT_GT(projected, off_curve * 3 / 4);
}

// Without refinement the status is decided at the algebraic t, and the projection can land
// nearer than it, within the tolerance: the row then keeps its algebraic answer, so that an
// off_curve row's residual stays beyond the tolerance (found by fuzz_invert on this quartic, whose
// two middle control points coincide, with its points as the fuzzer made them).
TEST(Projection, AProjectionWithinTheToleranceLeavesTheRowAsItWas) {
  const Curve quartic = Curve::bezier("q", {{-3200, 0}, {0, 0}, {256, 256}, {256, 256}, {256, 512}});
  const InversionPlan plan = make_plan(quartic);
  const double tolerance = 1e-2 * plan.diagonal();
  const std::vector<Point> points = {{-3539.308022207153, 1.0406508739113338}, {128, 256},
                                     {128.64287472483437, 243.50559694981382}};
  for (const bool fast_path : {true, false}) {
    InvertOptions options{.off_curve = OffCurve::projection};
    options.threads = 1;
    options.refine = false;
    options.fast_path = fast_path;
    options.algebraic = Algebraic::formula;
    options.relative_tolerance = 1e-2;
    std::vector<PointResult> results(points.size());
    invert(plan, points, results, options);
    for (std::size_t k = 0; k < points.size(); ++k) {
      const PointResult& r = results[k];
      if (r.status == Status::off_curve)
        EXPECT_GT(r.residual, tolerance) << "point " << k << ", path " << static_cast<int>(r.path) << ", t " << r.t;
      else
        EXPECT_LE(r.residual, tolerance) << "point " << k;
    }
  }
}

}  // namespace
}  // namespace bezinv
