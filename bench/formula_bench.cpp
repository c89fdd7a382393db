// The inversion formula as an algebraic step: t = N(x, y) / M(x, y) per point (Wang & Joe), against
// the engine's whole refined inversion of the same points (BM_Engine_refined in invert_bench.cpp,
// the same binary and run). 64 rational Bezier curves on perturbed arcs x 1024 on-curve points per
// degree, cycled as in invert_bench.cpp. The formula's figure is what the formula path would spend
// in place of forming B, the seed and the read-out: the answer would still be refined and certified.
#include <benchmark/benchmark.h>

#include <random>
#include <vector>

#include "bezinv/datasets/on_curve_points.hpp"
#include "bezinv/datasets/random_curve.hpp"
#include "bezinv/datasets/random_numbers.hpp"
#include "bezinv/inversion_formula.hpp"
#include "bezinv/plan.hpp"

namespace {

using namespace bezinv;

constexpr int kFormulaCurves = 64;
constexpr int kFormulaPoints = 1024;

struct FormulaWorkload {
  std::vector<InversionFormula> formulae;
  std::vector<std::vector<Point>> points;
};

const FormulaWorkload& formula_workload(int degree) {
  static std::vector<FormulaWorkload> cache(kMaxDegree + 1);
  FormulaWorkload& w = cache[static_cast<std::size_t>(degree)];
  if (w.formulae.empty()) {
    std::mt19937_64 rng(4242 + degree);
    for (int c = 0; c < kFormulaCurves; ++c) {
      const Curve curve =
          datasets::random_curve(CurveKind::rational_bezier, degree, rng, datasets::ControlPolygon::perturbed_arc);
      w.formulae.emplace_back(make_plan(curve));
      std::vector<Point> pts(kFormulaPoints);
      for (Point& p : pts) p = datasets::on_curve(curve, datasets::uniform(rng, 0.0, 1.0));
      w.points.push_back(std::move(pts));
    }
  }
  return w;
}

void BM_Formula_parameter(benchmark::State& state) {
  const FormulaWorkload& w = formula_workload(static_cast<int>(state.range(0)));
  std::vector<double> t(kFormulaPoints);
  int c = 0;
  for (auto _ : state) {
    const InversionFormula& f = w.formulae[static_cast<std::size_t>(c)];
    const std::vector<Point>& pts = w.points[static_cast<std::size_t>(c)];
    for (int i = 0; i < kFormulaPoints; ++i) t[static_cast<std::size_t>(i)] = f(pts[i].x, pts[i].y);
    benchmark::DoNotOptimize(t.data());
    benchmark::ClobberMemory();
    c = (c + 1) % kFormulaCurves;
  }
  state.SetItemsProcessed(state.iterations() * kFormulaPoints);
}

// What the formula path pays once per plan before its first point: the curve's inversion formula,
// made from its plan (the plans made before the timing), one curve per iteration, cycled.
void BM_Formula_made(benchmark::State& state) {
  const int degree = static_cast<int>(state.range(0));
  std::mt19937_64 rng(77 + degree);
  std::vector<InversionPlan> plans;
  for (int c = 0; c < 16; ++c)
    plans.push_back(make_plan(
        datasets::random_curve(CurveKind::rational_bezier, degree, rng, datasets::ControlPolygon::perturbed_arc)));
  std::size_t c = 0;
  for (auto _ : state) {
    InversionFormula formula(plans[c]);
    benchmark::DoNotOptimize(&formula);
    c = (c + 1) % plans.size();
  }
  state.SetItemsProcessed(state.iterations());
}

BENCHMARK(BM_Formula_made)->DenseRange(4, 20, 2)->Unit(benchmark::kMillisecond);

BENCHMARK(BM_Formula_parameter)->Arg(2)->Arg(3)->Arg(5)->Arg(8)->Arg(15)->Arg(20)->Unit(benchmark::kMicrosecond);

}  // namespace
