// Curves people actually have, which the engine used to refuse or get wrong: graphs of functions
// (as polynomials x is linear in t, so p = X - x0 W has degree 1 and B is ill-conditioned
// everywhere), near-parabolas
// and exactly degree-elevated curves (a top power coefficient at or near zero), and rational Bezier
// curves with weights over many decades. Every point is made from a known t by exact evaluation of
// the curve as given (tests/support/known_parameter.hpp has the accuracy model); no expected value
// comes from the engine.
#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <numbers>
#include <random>
#include <string>
#include <vector>

#include "bezinv/curve.hpp"
#include "bezinv/datasets/curve_sampling.hpp"
#include "bezinv/datasets/random_curve.hpp"
#include "bezinv/datasets/random_numbers.hpp"
#include "bezinv/invert.hpp"
#include "bezinv/plan.hpp"
#include "support/exact.hpp"
#include "support/known_parameter.hpp"
#include "support/sanitizers.hpp"

namespace bezinv {
namespace {

using test_support::ExactCurve;
using test_support::expect_known;
using test_support::Findings;
using test_support::known_at;
using test_support::KnownParameter;
using Points = std::vector<std::array<double, 2>>;

// The parameters every curve is probed at: both ends exactly, the middle, and random interior ones.
std::vector<double> probe_parameters(std::mt19937_64& rng, int interior) {
  std::vector<double> t{0.0, 1.0, 0.5};
  for (int i = 0; i < interior; ++i) t.push_back(datasets::uniform(rng, 0.0, 1.0));
  return t;
}

// Inverts P(t) for each t and checks it against the accuracy model (none of these curves crosses
// itself, see each test: ok every time), alone and in a batch.
void probe(Findings& findings, const std::string& name, const Curve& curve, const std::vector<double>& parameters) {
  const ExactCurve exact(curve);
  const InversionPlan plan = make_plan(curve);
  findings.check(plan.usable(), [&] { return name + ": plan not usable: " + plan.reason(); });
  std::vector<Point> points;
  std::vector<PointResult> results;
  for (double t : parameters) {
    const KnownParameter k = known_at(exact, t);
    points.push_back(k.point);
    results.push_back(invert_point(plan, k.point));
    expect_known(findings, name, exact, k, results.back());
  }
  test_support::expect_batched_as_single(findings, name, plan, points, results);
}

Points rotated_45(const Points& points) {
  const double c = std::sqrt(0.5);
  Points out;
  for (const auto& p : points) out.push_back({c * p[0] - c * p[1], c * p[0] + c * p[1]});
  return out;
}

std::vector<double> coordinate(const Points& points, int k) {
  std::vector<double> out;
  for (const auto& p : points) out.push_back(p[k]);
  return out;
}

// ---- 1. graphs of functions --------------------------------------------------------------------

enum class Ordinates { random, sine, exponential, cubic, mod5 };
const char* to_string(Ordinates f) {
  switch (f) {
    case Ordinates::random:
      return "random";
    case Ordinates::sine:
      return "sin";
    case Ordinates::exponential:
      return "exp";
    case Ordinates::cubic:
      return "cubic";
    case Ordinates::mod5:
      return "x=i,y=7i mod 5";
  }
  return "?";
}

// How the graph is written down.
enum class Form { bezier, rational_bezier, rational_common, rational_separate };
const char* to_string(Form form) {
  switch (form) {
    case Form::bezier:
      return "bezier";
    case Form::rational_bezier:
      return "rational_bezier";
    case Form::rational_common:
      return "rational (denominators 1)";
    case Form::rational_separate:
      return "rational (x_den 1, y_den w)";
  }
  return "?";
}

// Control points x_i = i/n (x_i = i for mod5), y_i from the ordinates.
Points graph_polygon(Ordinates f, int n, std::mt19937_64& rng) {
  Points p;
  for (int i = 0; i <= n; ++i) {
    const double x = static_cast<double>(i) / n;
    switch (f) {
      case Ordinates::random:
        p.push_back({x, datasets::uniform(rng, 0.0, 1.0)});
        break;
      case Ordinates::sine:
        p.push_back({x, std::sin(3 * x)});
        break;
      case Ordinates::exponential:
        p.push_back({x, std::exp(x)});
        break;
      case Ordinates::cubic:
        p.push_back({x, 1 - 3 * x + 2 * x * x * x});
        break;
      case Ordinates::mod5:
        p.push_back({static_cast<double>(i), static_cast<double>((7 * i) % 5)});
        break;
    }
  }
  return p;
}

// x(t) is increasing on the segment in every form (positive weights and increasing x_i: a rational
// Bezier function is variation-diminishing), so the graph meets no point twice.
Curve graph_curve(const Points& polygon, Form form, std::mt19937_64& rng) {
  const int n = static_cast<int>(polygon.size()) - 1;
  std::vector<double> w(n + 1);
  for (double& v : w) v = datasets::uniform(rng, 0.5, 2.0);
  const std::vector<double> ones(n + 1, 1.0), x = coordinate(polygon, 0), y = coordinate(polygon, 1);
  switch (form) {
    case Form::bezier:
      return Curve::bezier("graph", polygon);
    case Form::rational_bezier:
      return Curve::rational_bezier("graph", polygon, w);
    case Form::rational_common:
      return Curve::rational("graph", x, ones, y, ones);
    case Form::rational_separate: {
      std::vector<double> yw(n + 1);
      for (int i = 0; i <= n; ++i) yw[i] = y[i] * w[i];
      return Curve::rational("graph", x, ones, yw, w);
    }
  }
  return Curve::bezier("graph", polygon);
}

// Every degree 2..32 in every form, each family of ordinates, as given and rotated by 45 degrees
// (separate denominators cannot be rotated: a rotation mixes x and y).
TEST(OrdinaryCurves, GraphsOfFunctions) {
  Findings findings("graphs of functions, degree 2..32");
  int curves = 0, curves_seen = 0;
  for (int n = 2; n <= 32; ++n)
    for (Ordinates f : {Ordinates::random, Ordinates::sine, Ordinates::exponential, Ordinates::cubic, Ordinates::mod5})
      for (Form form : {Form::bezier, Form::rational_bezier, Form::rational_common, Form::rational_separate})
        for (bool rotate : {false, true}) {
          if (rotate && form == Form::rational_separate) continue;
          // The smooth families at every third degree, shifted with the form and the rotation, so
          // each family meets each form across the whole range of degrees.
          if (f != Ordinates::random && (n + static_cast<int>(form) + rotate) % 3 != 0) continue;
          // Under the sanitizers one curve in kSanitizerThinning, every degree still met.
          if (test_support::thinned_out(static_cast<std::size_t>(curves_seen++))) continue;
          const std::uint64_t seed =
              1000ULL * n + 100ULL * static_cast<int>(f) + 10ULL * static_cast<int>(form) + rotate;
          std::mt19937_64 rng(seed);
          Points polygon = graph_polygon(f, n, rng);
          if (rotate) polygon = rotated_45(polygon);
          const Curve curve = graph_curve(polygon, form, rng);
          const std::string name = std::string(to_string(form)) + " degree " + std::to_string(n) + " " + to_string(f) +
                                   (rotate ? " rotated 45" : "") + " seed " + std::to_string(seed);
          probe(findings, name, curve, probe_parameters(rng, 5));
          ++curves;
        }
  std::printf("[ measured ] %d graph curves\n", curves);
  EXPECT_GT(findings.points(), 2000 / test_support::kSanitizerThinning);
}

// A smooth function's graph is close to a curve of lower degree (its top differences are tiny), so
// B is nearly singular twice over at every point and the Bezout seed settles few of them. With
// x(t) linear the default (Algebraic::automatic) starts from t = (x - x(0)) / x' instead: the
// on-curve points are answered on the formula path, and every point, on the curve or near it, gets
// the status and t the SVD path gives it (fast_path false: every point by the SVD). The SVD path
// is the reference here; GraphsOfFunctions checks the same families against exact arithmetic.
TEST(OrdinaryCurves, SmoothGraphsTakeTheLinearFormulaWithTheSvdPathsAnswers) {
  int curves = 0, curves_seen = 0, on_curve = 0, by_formula = 0, compared = 0;
  for (int n = 3; n <= 32; ++n)
    for (Ordinates f : {Ordinates::sine, Ordinates::exponential})
      for (Form form : {Form::bezier, Form::rational_common})
        for (bool rotate : {false, true}) {
          if (test_support::thinned_out(static_cast<std::size_t>(curves_seen++))) continue;
          const std::uint64_t seed = 7000ULL * n + 100ULL * static_cast<int>(f) + 10ULL * static_cast<int>(form) + rotate;
          std::mt19937_64 rng(seed);
          Points polygon = graph_polygon(f, n, rng);
          if (rotate) polygon = rotated_45(polygon);
          const Curve curve = graph_curve(polygon, form, rng);
          const std::string name = std::string(to_string(form)) + " degree " + std::to_string(n) + " " + to_string(f) +
                                   (rotate ? " rotated 45" : "");
          const ExactCurve exact(curve);
          const InversionPlan plan = make_plan(curve);
          ASSERT_TRUE(plan.usable()) << name;
          // On the curve, and moved off it by 1e-9 .. 1e-3 of the diagonal (within the tolerance
          // and beyond it) in a random direction.
          std::vector<Point> points;
          constexpr int kOn = 16;
          for (int k = 0; k < kOn; ++k) points.push_back(known_at(exact, datasets::uniform(rng, 0.0, 1.0)).point);
          for (double offset : {1e-9, 1e-7, 1e-5, 1e-3})
            for (int k = 0; k < 4; ++k) {
              const Point p = known_at(exact, datasets::uniform(rng, 0.0, 1.0)).point;
              const double angle = datasets::uniform(rng, 0.0, 2 * std::numbers::pi);
              const double r = offset * std::sqrt(2.0);  // the polygon's diagonal is about sqrt(2)
              points.push_back({p.x + r * std::cos(angle), p.y + r * std::sin(angle)});
            }
          std::vector<PointResult> got(points.size()), svd(points.size());
          invert(plan, points, got);
          invert(plan, points, svd, {.fast_path = false});
          for (std::size_t i = 0; i < points.size(); ++i) {
            ++compared;
            EXPECT_EQ(got[i].status, svd[i].status) << name << ", point " << i;
            if (got[i].status == Status::ok || got[i].status == Status::off_curve) {
              EXPECT_NEAR(got[i].t, svd[i].t, 1e-9) << name << ", point " << i;
            }
          }
          for (int k = 0; k < kOn; ++k) {
            EXPECT_EQ(got[k].status, Status::ok) << name << ", point " << k;
            // From degree 7 these graphs are within kNearLowerDegreeRatio of a lower degree (below
            // it the Bezout seed settles them, and automatic keeps it).
            if (n < 7) continue;
            ++on_curve;
            by_formula += got[k].path == Path::formula;
          }
          ++curves;
        }
  std::printf("[ measured ] %d graphs, %d points compared; from degree 7, %d of %d on-curve points by the formula\n",
              curves, compared, by_formula, on_curve);
  EXPECT_GT(curves, 200 / test_support::kSanitizerThinning);
  // Every on-curve point of these graphs has the linear formula's start; a few may still go the
  // SVD's way (a start the certificate cannot settle), not more.
  EXPECT_GE(by_formula, on_curve * 95 / 100);
}

// ---- 2. near-parabolas and exactly elevated curves ----------------------------------------------

// Like probe(), but a point another part of the segment comes near (a loop of a random curve) is
// left out and counted: there double_point is a right answer. Margin 1e-4 of the diagonal, 100x
// the engine's tolerance, so the expected status never hinges on a near double point.
int probe_isolated(Findings& findings, const std::string& name, const Curve& curve,
                   const std::vector<double>& parameters) {
  const ExactCurve exact(curve);
  const datasets::CurveSampling sampling(curve, 64);
  const InversionPlan plan = make_plan(curve);
  findings.check(plan.usable(), [&] { return name + ": plan not usable: " + plan.reason(); });
  int skipped = 0;
  std::vector<Point> points;
  std::vector<PointResult> results;
  for (double t : parameters) {
    const KnownParameter k = known_at(exact, t);
    if (!test_support::isolated_on_segment(sampling, k.point, t, 1e-4 * exact.diagonal())) {
      ++skipped;
      continue;
    }
    points.push_back(k.point);
    results.push_back(invert_point(plan, k.point));
    expect_known(findings, name, exact, k, results.back());
  }
  test_support::expect_batched_as_single(findings, name, plan, points, results);
  return skipped;
}

// [[0,0],[1/3,1/3],[2/3,1/3],[1,e]]: x(t) = t (up to the rounding of 1/3), y(t) = t - t^2 + e t^3,
// a parabola plus e t^3. No loop: x is increasing.
TEST(OrdinaryCurves, NearParabolaCubics) {
  Findings findings("cubic [[0,0],[1/3,1/3],[2/3,1/3],[1,e]]");
  std::mt19937_64 rng(17);
  for (int k = 3; k <= 13; ++k) {
    const double e = k == 13 ? 0.0 : std::pow(10.0, -k);
    const Points polygon{{0, 0}, {1.0 / 3, 1.0 / 3}, {2.0 / 3, 1.0 / 3}, {1, e}};
    char name_text[32];
    std::snprintf(name_text, sizeof name_text, "e %g", e);
    const std::string name = name_text;
    probe(findings, name, Curve::bezier("near-parabola", polygon), probe_parameters(rng, 12));
    probe(findings, name + " rotated 45", Curve::bezier("near-parabola", rotated_45(polygon)),
          probe_parameters(rng, 12));
    probe(findings, name + " rational_bezier, weights 1",
          Curve::rational_bezier("near-parabola", polygon, {1, 1, 1, 1}), probe_parameters(rng, 12));
    probe(findings, name + " rational_bezier, weights 1,2,2,1",
          Curve::rational_bezier("near-parabola", polygon, {1, 2, 2, 1}), probe_parameters(rng, 12));
  }
  EXPECT_GT(findings.points(), 600);
}

// Bernstein coefficients at degree n of the power-basis polynomial a (exact), rounded once.
std::vector<double> rounded_bernstein(const std::vector<double>& power, int n) {
  return exact::to_double(exact::bernstein_from_power(exact::to_exact(power), n));
}

// A curve of degree n whose top power coefficient is r of the others (random in [-1, 1]), in x
// and y, or in x only (y of degree n - 1, its top coefficient the rounding of its Bernstein form);
// as bezier, or as rational with denominators 1 (`variant` 0, 1 as bezier; 2 as rational).
Curve tiny_top_curve(int n, double r, int variant, std::mt19937_64& rng) {
  std::vector<double> x(n + 1), y(n + 1);
  for (int i = 0; i < n; ++i) {
    x[i] = datasets::uniform(rng, -1.0, 1.0);
    y[i] = datasets::uniform(rng, -1.0, 1.0);
  }
  x[n] = datasets::uniform(rng, 0.0, 1.0) < 0.5 ? r : -r;
  y[n] = variant == 1 ? 0.0 : (datasets::uniform(rng, 0.0, 1.0) < 0.5 ? -r : r);
  const std::vector<double> bx = rounded_bernstein(x, n), by = rounded_bernstein(y, n);
  if (variant == 2)
    return Curve::rational("tiny-top", bx, std::vector<double>(n + 1, 1.0), by, std::vector<double>(n + 1, 1.0));
  Points p;
  for (int i = 0; i <= n; ++i) p.push_back({bx[i], by[i]});
  return Curve::bezier("tiny-top", p);
}

void tiny_top_sweep(Findings& findings, int min_degree, int max_degree, int min_exponent, int max_exponent) {
  int skipped = 0, curves = 0;
  for (int n = min_degree; n <= max_degree; ++n)
    for (int e = min_exponent; e <= max_exponent; ++e)
      for (int variant = 0; variant < 3; ++variant) {
        const std::uint64_t seed = 100ULL * n + 10ULL * e + variant;
        std::mt19937_64 rng(seed);
        const Curve curve = tiny_top_curve(n, std::pow(10.0, -e), variant, rng);
        const std::string name = "degree " + std::to_string(n) + " top 1e-" + std::to_string(e) +
                                 std::array{"", " (x only)", " as rational"}[variant] + " seed " + std::to_string(seed);
        skipped += probe_isolated(findings, name, curve, probe_parameters(rng, 12));
        ++curves;
      }
  std::printf("[ measured ] %d curves, %d points skipped (near another branch)\n", curves, skipped);
}

// Cubics, quartics and quintics whose top power coefficient is 1e-5 .. 1e-12 of the others: a real
// term, above what rounding leaves in a degree-elevated curve (at most ~2^n eps of the
// coefficients), which the engine must keep.
TEST(OrdinaryCurves, TinyTopPowerCoefficient) {
  Findings findings("tiny top power coefficient, degree 3..5");
  tiny_top_sweep(findings, 3, 5, 5, 12);
  EXPECT_GT(findings.points(), 1000);
}

// The same down to 1e-14, and at degrees 3..12, where the top coefficient is comparable to the
// engine's bound on what rounding leaves in an elevated curve's (kElevatedLeadingRatio: 8 eps 2^n
// times the largest coefficient). The curve is reduced only where the reduction moves no
// coefficient by more than rounding could (8 eps of the largest): on the leading coefficient's test
// alone, the curve inverted was not the one given, and the exact residual at the returned t
// exceeded the accuracy bound (up to 1.42x, 9 of 1800 points, e.g. degree 5, top 1e-13, as
// rational, seed 632), where P(t_true) itself is within half an ulp.
TEST(OrdinaryCurves, TinyTopPowerCoefficientAtTheReductionThreshold) {
  Findings findings("tiny top power coefficient at the reduction threshold, degree 3..12", 20);
  tiny_top_sweep(findings, 3, 12, 11, 14);
}

// Least common multiple of the denominators of the coefficients.
mpz_class common_denominator(const std::vector<exact::Poly>& polys) {
  mpz_class l = 1;
  for (const auto& p : polys)
    for (const mpq_class& c : p) mpz_lcm(l.get_mpz_t(), l.get_mpz_t(), c.get_den().get_mpz_t());
  return l;
}

// Integer curves of degree m = 2..10 elevated exactly (GMP) by 1..3 degrees: once scaled to
// integers (every coefficient exactly a double, the top power coefficients exactly 0) and once
// rounded to the nearest doubles (top coefficients at rounding level). Either way the plan must
// find the degree m, and every point invert as on the original curve.
TEST(OrdinaryCurves, ExactlyElevatedCurves) {
  Findings findings("exactly elevated curves, degree 2..10 + 1..3");
  int skipped = 0, curves = 0;
  for (int m = 2; m <= 10; ++m)
    for (int times = 1; times <= 3; ++times)
      for (int form = 0; form < 3; ++form) {  // bezier, rational (one W), rational (separate denominators)
        const std::uint64_t seed = 1000ULL * m + 10ULL * times + form;
        std::mt19937_64 rng(seed);
        exact::Poly x(m + 1), y(m + 1), wx(m + 1, mpq_class(1)), wy(m + 1, mpq_class(1));
        for (int i = 0; i <= m; ++i) {
          x[i] = datasets::uniform_int(rng, -20, 20);
          y[i] = datasets::uniform_int(rng, -20, 20);
          if (form >= 1) wx[i] = datasets::uniform_int(rng, 1, 4);
          wy[i] = form == 2 ? mpq_class(datasets::uniform_int(rng, 1, 4)) : wx[i];
          if (form >= 1) {  // numerators of points with integer coordinates
            x[i] *= wx[i];
            y[i] *= wy[i];
          }
        }
        const int n = m + times;
        std::vector<exact::Poly> elevated{exact::elevate(x, n), exact::elevate(wx, n), exact::elevate(y, n),
                                          exact::elevate(wy, n)};
        for (bool scaled : {true, false}) {
          std::vector<std::vector<double>> c;
          const mpz_class l = scaled ? common_denominator(elevated) : mpz_class(1);
          for (const exact::Poly& p : elevated) {
            exact::Poly q = p;
            for (mpq_class& v : q) v *= l;
            c.push_back(exact::to_double(q));
            if (scaled) {
              ASSERT_EQ(exact::to_exact(c.back()), q) << "degree " << m << " + " << times << ": not exact in double";
            }
          }
          Points polygon;  // form 0: the denominators are exactly 1 (elevated 1 is 1), a bezier curve
          for (int i = 0; i <= n; ++i) polygon.push_back({c[0][i] / c[1][i], c[2][i] / c[3][i]});
          const Curve curve =
              form == 0 ? Curve::bezier("elevated", polygon) : Curve::rational("elevated", c[0], c[1], c[2], c[3]);
          const std::string name = std::string(std::array{"polynomial", "one weight", "separate"}[form]) + " degree " +
                                   std::to_string(m) + " elevated " + std::to_string(times) +
                                   (scaled ? "x, exact integers" : "x, rounded") + " seed " + std::to_string(seed);
          const InversionPlan plan = make_plan(curve);
          EXPECT_EQ(plan.degree(), m) << name;
          skipped += probe_isolated(findings, name, curve, probe_parameters(rng, 6));
          ++curves;
        }
      }
  std::printf("[ measured ] %d curves, %d points skipped (near another branch)\n", curves, skipped);
  EXPECT_GT(findings.points(), 1000);
}

// ---- 3. wide weights ----------------------------------------------------------------------------

// Control points of a "reasonable" design curve (datasets' perturbed arc) with the given weights.
Curve weighted_arc(int n, const std::vector<double>& weights, std::mt19937_64& rng) {
  const Curve arc = datasets::random_curve(CurveKind::bezier, n, rng, datasets::ControlPolygon::perturbed_arc);
  Points p;
  for (int i = 0; i <= n; ++i) p.push_back({arc.x_num[i], arc.y_num[i]});
  return Curve::rational_bezier("weighted", p, weights);
}

// A point exactly at an end of the segment: ok at that end (within its condition), never a
// double point. Near a large weight the curve lingers at its control point, so other parameters
// reach the point to within the tolerance too; they are the same branch, not a crossing.
void expect_end(Findings& findings, const std::string& name, const ExactCurve& exact, const InversionPlan& plan,
                double end) {
  const KnownParameter k = known_at(exact, end);
  const PointResult r = invert_point(plan, k.point);
  findings.check(r.status != Status::double_point,
                 [&] { return name + " (at an end): " + test_support::describe(k, r); });
  expect_known(findings, name + " (at an end)", exact, k, r);
}

// Weights log-uniform in [1e-4, 1e4] at degrees 3..30: both ends, the middle and random
// parameters (points another part of the segment comes near are left out, see probe_isolated).
TEST(OrdinaryCurves, WideRandomWeights) {
  Findings findings("weights 1e-4..1e4, degree 3..30"), ends("weights 1e-4..1e4: P(0), P(1)");
  int skipped = 0, curves = 0;
  for (int n = 3; n <= 30; ++n)
    for (int copy = 0; copy < 2; ++copy) {
      const std::uint64_t seed = 7000ULL + 10ULL * n + copy;
      std::mt19937_64 rng(seed);
      std::vector<double> w(n + 1);
      for (double& v : w) v = datasets::log_uniform(rng, 1e-4, 1e4);
      const Curve curve = weighted_arc(n, w, rng);
      const std::string name = "degree " + std::to_string(n) + " seed " + std::to_string(seed);
      const ExactCurve exact(curve);
      const InversionPlan plan = make_plan(curve);
      for (double end : {0.0, 1.0}) expect_end(ends, name, exact, plan, end);
      std::vector<double> interior;
      for (int i = 0; i < 6; ++i) interior.push_back(datasets::uniform(rng, 0.0, 1.0));
      skipped += probe_isolated(findings, name, curve, interior);
      ++curves;
    }
  std::printf("[ measured ] %d curves, %d points skipped (near another branch)\n", curves, skipped);
  EXPECT_GT(findings.points(), 250);
}

// Weights 10^(-12 + 2.4 i) at degree 10, increasing and decreasing: the curve spends most of the
// segment at the heavy end's control point.
TEST(OrdinaryCurves, MonotoneWeightsOverTwentyFourDecades) {
  Findings findings("weights 1e-12..1e12, degree 10"), ends("weights 1e-12..1e12: P(0), P(1)");
  int skipped = 0;
  for (bool increasing : {true, false})
    for (int copy = 0; copy < 8; ++copy) {
      const std::uint64_t seed = 9000ULL + 10ULL * copy + increasing;
      std::mt19937_64 rng(seed);
      std::vector<double> w(11);
      for (int i = 0; i <= 10; ++i) w[i] = std::pow(10.0, -12 + 2.4 * (increasing ? i : 10 - i));
      const Curve curve = weighted_arc(10, w, rng);
      const std::string name = std::string(increasing ? "increasing" : "decreasing") + " seed " + std::to_string(seed);
      const ExactCurve exact(curve);
      const InversionPlan plan = make_plan(curve);
      for (double end : {0.0, 1.0}) expect_end(ends, name, exact, plan, end);
      std::vector<double> interior{1e-9, 1e-6, 1e-3, 0.5, 1 - 1e-3, 1 - 1e-6, 1 - 1e-9};
      for (int i = 0; i < 6; ++i) interior.push_back(datasets::uniform(rng, 0.0, 1.0));
      skipped += probe_isolated(findings, name, curve, interior);
    }
  std::printf("[ measured ] %d points skipped (near another branch)\n", skipped);
  EXPECT_GT(findings.points(), 150);
}

// The conics and cubics people draw, which the default now inverts from their inversion formula
// (engine/src/formula/linear_inversion_formula.hpp): CSS easing cubics, font outlines in integer
// units of a 2048 em (TrueType quadratics, CFF cubics), circular arcs as rational quadratics, and
// cubics in map coordinates (degrees of longitude and latitude, 1e-3 across). Points made exactly
// from a known t meet the accuracy model; points moved off the curve by 1e-9 .. 1 of its size get
// the Bezout path's status; and the formula answers most on-curve points.
TEST(OrdinaryCurves, ConicsAndCubicsPeopleDrawTakeTheFormulaWithTheBezoutPathsStatuses) {
  Findings findings("conics and cubics people draw, by default");
  int on_curve = 0, by_formula = 0, compared = 0;
  std::mt19937_64 rng(20261204);
  auto check = [&](const std::string& name, const Curve& curve) {
    const ExactCurve exact(curve);
    const InversionPlan plan = make_plan(curve);
    ASSERT_TRUE(plan.usable()) << name;
    std::vector<Point> points;
    for (double t : probe_parameters(rng, 12)) {
      const KnownParameter k = known_at(exact, t);
      const PointResult r = invert_point(plan, k.point);
      expect_known(findings, name, exact, k, r);
      ++on_curve;
      by_formula += r.path == Path::formula;
      points.push_back(k.point);
    }
    for (double offset : {1e-9, 1e-6, 1e-3, 1.0}) {
      const Point p = known_at(exact, datasets::uniform(rng, 0.0, 1.0)).point;
      const double angle = datasets::uniform(rng, 0.0, 2 * std::numbers::pi);
      const double r = offset * plan.diagonal();
      points.push_back({p.x + r * std::cos(angle), p.y + r * std::sin(angle)});
    }
    std::vector<PointResult> automatic(points.size()), bezout(points.size());
    invert(plan, points, automatic);
    invert(plan, points, bezout, {.algebraic = Algebraic::bezout});
    for (std::size_t i = 0; i < points.size(); ++i) {
      ++compared;
      EXPECT_EQ(automatic[i].status, bezout[i].status) << name << ", point " << i;
    }
  };
  for (int c = 0; c < 20; ++c) {
    const double x1 = datasets::uniform(rng, 0.0, 1.0), x2 = datasets::uniform(rng, 0.0, 1.0);
    check("easing " + std::to_string(c),
          Curve::bezier("easing", {{0, 0}, {x1, datasets::uniform(rng, -0.5, 1.5)}, {x2, datasets::uniform(rng, -0.5, 1.5)}, {1, 1}}));
    Points glyph;
    const double x0 = std::round(datasets::uniform(rng, 0.0, 2048.0)), y0 = std::round(datasets::uniform(rng, 0.0, 2048.0));
    for (int i = 0; i <= 2 + c % 2; ++i)
      glyph.push_back({x0 + std::round(datasets::uniform(rng, -400.0, 400.0)), y0 + std::round(datasets::uniform(rng, -400.0, 400.0))});
    check("glyph " + std::to_string(c), Curve::bezier("glyph", glyph));
    // An arc of angle 2 a on the unit circle: end points at +-a, the middle control point where
    // their tangents meet, its weight cos(a).
    const double a = datasets::uniform(rng, 0.1, 1.5);
    check("arc " + std::to_string(c),
          Curve::rational_bezier("arc", {{std::cos(a), -std::sin(a)}, {1 / std::cos(a), 0}, {std::cos(a), std::sin(a)}},
                                 {1, std::cos(a), 1}));
    const double lon = datasets::uniform(rng, -180.0, 180.0), lat = datasets::uniform(rng, -80.0, 80.0);
    Points track;
    for (int i = 0; i <= 3; ++i)
      track.push_back({lon + datasets::uniform(rng, -5e-4, 5e-4), lat + datasets::uniform(rng, -5e-4, 5e-4)});
    check("map " + std::to_string(c), Curve::rational_bezier("map", track, {1, datasets::uniform(rng, 0.5, 2.0),
                                                                            datasets::uniform(rng, 0.5, 2.0), 1}));
  }
  std::printf("[ measured ] %d on-curve points, %d by the formula; %d statuses compared with the Bezout path\n", on_curve,
              by_formula, compared);
  EXPECT_GT(by_formula, on_curve / 2);
}

}  // namespace
}  // namespace bezinv
