// The fused formula path kernel (Implementation::formula_newton), every available implementation,
// conics and cubics: each lane it settles must have exactly the t and distance of the kernels it
// fuses, run one after the other (formula_parameter, then rational_newton), which pass the
// isolation certificate's first test, computed here from its definition; and it must settle most
// points on the curve, at their known t. The curves are graphs of functions, x(t) = x0 + w t (a
// polynomial) and y(t) a polynomial or a quotient of its own (separate denominators), whose
// formula t = (x - x0) / w is exact: the points, made at a known t, start at it. Steep graphs
// (|P'| up to 1e3) take the converged steps whose last ulps move P, and the ends the clamped steps.
// With somewhere to put them, every lane's normalized point and N / M must be the kernels' too.
// For a lane it does not settle (t NaN), its first distance must tell exactly the lanes
// rational_newton's first iteration leaves (distance +inf there): points moved off the graph by
// 1e-16 to 1e-8, the leave distance 1e-10 among them.
// tests/engine/formula_first_test.cpp checks the engine's rows with it against the stages' rows.
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cstdint>
#include <cmath>
#include <cstdio>
#include <limits>
#include <random>
#include <stdexcept>
#include <string>
#include <vector>

#include "bezinv/kernels/batch.hpp"
#include "support/bits.hpp"

namespace bezinv::kernels {
namespace {

using test_support::kNaN;
using test_support::same_bits;

// The engine's formula-path settings (engine/include/bezinv/tolerances.hpp; the formula path's
// last step 1e-9, leave distance 1e-10).
constexpr NewtonSettings kFormulaPathSettings{60, 0.125, 1e-6, 40, 1e-9, 1e-10};

struct FunctionGraph {
  std::vector<double> x_num, x_den, y_num, y_den;
  double x0 = 0, width = 1;
  RationalCurve view(bool shared_denominator) const {
    return {static_cast<int>(x_num.size()) - 1, x_num.data(), x_den.data(), y_num.data(),
            shared_denominator ? x_den.data() : y_den.data()};
  }
  // The point at t, in doubles (x exact to rounding; y by the quotient of its Bernstein sums).
  std::array<double, 2> at(double t) const {
    const int n = static_cast<int>(x_num.size()) - 1;
    auto value = [&](const std::vector<double>& c) {
      std::vector<double> f = c;
      for (int r = 1; r <= n; ++r)
        for (int i = 0; i <= n - r; ++i) f[i] = (1 - t) * f[i] + t * f[i + 1];
      return f[0];
    };
    return {value(x_num) / value(x_den), value(y_num) / value(y_den)};
  }
};

// x = x0 + width t; y of amplitude `steep` (with `rational`, its own denominator of weights 0.5-2).
FunctionGraph random_function_graph(int n, double steep, bool rational, std::mt19937_64& rng) {
  std::uniform_real_distribution<double> unit(-1.0, 1.0), weight(0.5, 2.0);
  FunctionGraph g;
  g.x0 = unit(rng);
  g.width = 1.5 + unit(rng);
  for (int i = 0; i <= n; ++i) {
    const double w = rational ? weight(rng) : 1.0;
    g.x_num.push_back(g.x0 + g.width * i / n);
    g.x_den.push_back(1.0);
    g.y_num.push_back(w * steep * unit(rng));
    g.y_den.push_back(w);
  }
  return g;
}

TEST(FormulaNewton, SettlesLanesWithTheBitsOfTheKernelsItFuses) {
  std::mt19937_64 rng(20261206);
  std::uniform_real_distribution<double> unit(0.0, 1.0), exponent(-16.0, -8.0);
  // The certificate: eight pieces; `refusing` 2: two of them refuse every lane (piece 3 by its
  // bounds around t, piece 5 by a box near); 1: piece 5 alone; 0: all pass near the curve. Its
  // floors as the engine makes them, the least bounds: they pass no lane with 2, most with 0, and
  // with 1 the lanes whose piece's box is far (the far floor then refuses them all); every lane
  // must come out as by the pieces alone.
  constexpr int kPieces = 8;
  for (int refusing : {2, 1, 0}) {
    std::array<double, kPieces> monotone, unique, far;
    for (int j = 0; j < kPieces; ++j) {
      monotone[j] = refusing == 2 && j == 3 ? 0.0 : 1e-3 * (1 + j);
      unique[j] = refusing == 2 && j == 3 ? 0.0 : 1e-12;
      far[j] = refusing >= 1 && j == 5 ? 1e-9 : 0.5;
    }
    const double factor = 0.25, tolerance = 1e-8, limit = tolerance * (1 + 1e-6);
    const PieceCertificate by_pieces{kPieces, monotone.data(), factor, unique.data(), far.data(), limit};
    PieceCertificate certificate = by_pieces;
    certificate.around_floor = std::max(*std::min_element(monotone.begin(), monotone.end()) * factor,
                                        *std::min_element(unique.begin(), unique.end()));
    certificate.far_floor = *std::min_element(far.begin(), far.end());
    for (const Implementation* implementation : available_implementations()) {
      std::size_t settled = 0, on_curve = 0, lanes_total = 0, left_lanes = 0;
      for (int n : {2, 3})
        for (bool rational : {false, true})
          for (bool shared : {false, true}) {
            if (rational && shared) continue;  // separate denominators are two arrays
            for (double steep : {1.0, 30.0, 1e3}) {
              const FunctionGraph g = random_function_graph(n, steep, rational, rng);
              // Normalization: a power of two, a centre, a rotation by 0 (the formula's frame is
              // then the graph's x): u = x s - c, t = (u - (x0 s - c)) / (width s). The kernels take
              // the curve in those units.
              const double s = 0.5, c = 0.25;
              FunctionGraph normalized = g;
              for (std::size_t i = 0; i < g.x_num.size(); ++i) {
                normalized.x_num[i] = g.x_num[i] * s - c * g.x_den[i];
                normalized.y_num[i] = g.y_num[i] * s + 0.125 * g.y_den[i];
              }
              const PointFrame frame{s, c, -0.125, 1.0, 0.0};
              const std::array<double, 3> n_terms{-(g.x0 * s - c) / (g.width * s), 1.0 / (g.width * s), 0.0};
              const std::array<double, 3> m_terms{1.0, 0.0, 0.0};
              const PlaneFormula formula{1, 0.0, 0.0, 1.0, 1.0, 1e6, 1e-6, n_terms.data(), m_terms.data()};
              std::vector<double> xy, known;
              for (int k = 0; k < 61; ++k) {  // 61: not a multiple of any group's width
                double t = unit(rng);
                if (k < 6) t = k % 2 ? 1.0 - std::pow(10.0, -3.0 * k) : std::pow(10.0, -3.0 * k);  // the ends, near
                if (k == 6) t = 0.0;
                std::array<double, 2> p = g.at(t);
                if (k % 5 == 4) p[1] += std::pow(10.0, exponent(rng));  // near it: some beyond the leave distance
                if (k == 7) p = {kNaN, 0.0};
                if (k == 8) p[0] = g.x0 + g.width * 1.001;  // its t past the end
                xy.push_back(p[0]);
                xy.push_back(p[1]);
                known.push_back(k % 5 == 4 || k == 7 || k == 8 ? kNaN : t);
              }
              const std::size_t count = known.size();
              // The kernels one after the other, and the certificate by its definition.
              std::vector<double> u(count), v(count), t_ref(count), d_ref(count);
              for (std::size_t l = 0; l < count; ++l) {
                const double dx = xy[2 * l] * s - c, dy = xy[2 * l + 1] * s - -0.125;
                u[l] = 1.0 * dx - 0.0 * dy;
                v[l] = 0.0 * dx + 1.0 * dy;
              }
              implementation->formula_parameter(formula, count, u.data(), v.data(), t_ref.data());
              const std::vector<double> t_formula = t_ref;
              implementation->rational_newton(normalized.view(shared), kFormulaPathSettings, count, u.data(), v.data(),
                                              t_ref.data(), d_ref.data());
              std::vector<double> t(count, -1.0), d(count, -1.0), ku(count, -1.0), kv(count, -1.0),
                  kt(count, -1.0);
              const FormulaStart on_the_way{ku.data(), kv.data(), kt.data()};
              std::vector<std::uint64_t> left_bits((count + 63) / 64), leaves_bits((count + 63) / 64);
              const FormulaLanes lane_bits{left_bits.data(), leaves_bits.data()};
              const std::size_t got =
                  implementation->formula_newton(formula, normalized.view(shared), kFormulaPathSettings, frame,
                                                 certificate, tolerance, count, xy.data(), t.data(), d.data(),
                                                 &on_the_way, &lane_bits);
              std::vector<double> t_pieces(count, -1.0), d_pieces(count, -1.0);
              implementation->formula_newton(formula, normalized.view(shared), kFormulaPathSettings, frame, by_pieces,
                                             tolerance, count, xy.data(), t_pieces.data(), d_pieces.data(), nullptr,
                                             nullptr);
              const auto bit = [](const std::vector<std::uint64_t>& words, std::size_t l) {
                return ((words[l / 64] >> (l % 64)) & 1u) != 0;
              };
              std::size_t counted = 0;
              for (std::size_t l = 0; l < count; ++l) {
                SCOPED_TRACE(std::string(implementation->name) + " n=" + std::to_string(n) + " steep " +
                             std::to_string(steep) + (rational ? " rational" : "") + (shared ? " shared" : "") +
                             " lane " + std::to_string(l));
                EXPECT_TRUE(same_bits(d[l], d_pieces[l])) << "with the floors " << d[l] << ", without " << d_pieces[l];
                EXPECT_TRUE(same_bits(t[l], t_pieces[l]));
                EXPECT_TRUE(same_bits(ku[l], u[l]) && same_bits(kv[l], v[l]))
                    << "(" << ku[l] << ", " << kv[l] << ") against (" << u[l] << ", " << v[l] << ")";
                EXPECT_TRUE(same_bits(kt[l], t_formula[l])) << kt[l] << " against " << t_formula[l];
                EXPECT_EQ(bit(left_bits, l), std::isnan(t[l]));
                if (std::isnan(t[l])) {  // not settled
                  const bool leaves = t_formula[l] >= 0.0 && t_formula[l] <= 1.0 && d[l] > 1e-150 && d[l] < 1e150 &&
                                      d[l] > kFormulaPathSettings.leave_distance;
                  const bool left = d_ref[l] == std::numeric_limits<double>::infinity();
                  EXPECT_EQ(leaves, left) << "first distance " << d[l] << ", rational_newton's " << d_ref[l];
                  EXPECT_EQ(bit(leaves_bits, l), left) << "first distance " << d[l];
                  left_lanes += left;
                  continue;
                }
                EXPECT_FALSE(bit(leaves_bits, l));
                ++counted;
                EXPECT_TRUE(same_bits(t[l], t_ref[l])) << t[l] << " against " << t_ref[l];
                EXPECT_TRUE(same_bits(d[l], d_ref[l])) << d[l] << " against " << d_ref[l];
                const int j = std::min(kPieces - 1, static_cast<int>(t_ref[l] * kPieces));
                EXPECT_TRUE((d_ref[l] < monotone[j] * factor || d_ref[l] < unique[j]) && far[j] - d_ref[l] > limit &&
                            d_ref[l] <= tolerance);
                if (!std::isnan(known[l])) {
                  EXPECT_NEAR(t[l], known[l], 1e-12 * std::max(1.0, steep));
                }
              }
              EXPECT_EQ(got, counted);
              for (std::size_t l = count; l < 64 * left_bits.size(); ++l)  // a group's padding lanes
                EXPECT_FALSE(bit(left_bits, l) || bit(leaves_bits, l)) << "lane " << l << " of " << count;
              settled += counted;
              lanes_total += count;
              for (std::size_t l = 0; l < count; ++l) {
                if (std::isnan(known[l])) continue;
                const int j = std::min(kPieces - 1, static_cast<int>(known[l] * kPieces));
                const bool refused = (refusing >= 1 && j == 5) || (refusing == 2 && j == 3);
                on_curve += !refused;
              }
            }
          }
      std::printf("%s%s: %zu of %zu lanes settled; %zu on the curve in pieces that can pass\n",
                  std::string(implementation->name).c_str(),
                  refusing == 2   ? ", two pieces refusing"
                  : refusing == 1 ? ", one piece refusing"
                                  : "",
                  settled, lanes_total, on_curve);
      EXPECT_GE(settled, on_curve * 9 / 10);
      EXPECT_GT(left_lanes, 0u);  // the points moved off the graph beyond the leave distance
    }
  }
}

TEST(FormulaNewton, RefusesDegreesItIsNotCompiledFor) {
  const std::vector<double> c(5, 1.0);
  const std::array<double, 3> terms{0.0, 1.0, 0.0};
  const PlaneFormula formula{1, 0.0, 0.0, 1.0, 1.0, 1e6, 1e-6, terms.data(), terms.data()};
  const RationalCurve quartic{4, c.data(), c.data(), c.data(), c.data()};
  const double piece = 1.0;
  const PieceCertificate certificate{1, &piece, 1.0, &piece, &piece, 0.0};
  double xy[2] = {0.5, 0.5}, t = 0, d = 0;
  for (const Implementation* implementation : available_implementations())
    EXPECT_THROW(implementation->formula_newton(formula, quartic, kFormulaPathSettings, PointFrame{1, 0, 0, 1, 0},
                                                certificate, 1e-8, 1, xy, &t, &d, nullptr, nullptr),
                 std::out_of_range);
}

}  // namespace
}  // namespace bezinv::kernels
