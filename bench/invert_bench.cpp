// Points per second of the engine's batched `invert`, per degree: refined (the full answer, with
// the fast path), refined by the SVD alone (`fast_path = false`), algebraic (refine = false: the
// paper's t, always by the SVD), one thread and all cores. 64 curves x 1024 points per degree,
// cycled so that no curve's plan or points stay cache-hot between iterations (one iteration = one
// curve's 1024 points). Also noisy points (BM_Engine_refined_noisy) and mixed batches (BM_Engine_refined_mixed). The baselines (the paper's way, Eigen per point, OpenCASCADE, SISL) run in
// bench/baselines_bench.cpp, beside bezinv in the same process.
#include <benchmark/benchmark.h>

#include <cmath>
#include <cstddef>
#include <map>
#include <tuple>
#include <numbers>
#include <utility>
#include <random>
#include <vector>

#include "bezinv/datasets/on_curve_points.hpp"
#include "bezinv/datasets/random_curve.hpp"
#include "bezinv/datasets/random_numbers.hpp"
#include "bezinv/invert.hpp"
#include "bezinv/plan.hpp"

namespace {

using namespace bezinv;

constexpr int kCurves = 64;
constexpr int kPointsPerCurve = 1024;

struct Workload {
  std::vector<Curve> curves;
  std::vector<InversionPlan> plans;
  std::vector<std::vector<Point>> points;  // kPointsPerCurve per curve, t uniform in [0,1]
};

// Which of a noisy workload's points are moved off the curve: all, every other one (a mixed batch:
// measured points, some within the tolerance and some not), or none (its points on the curve). The
// three share their curves and parameters, so a mixed batch's rate compares with the other two's.
enum class Moved { all, every_other, none };

// Random rational Bezier curves (the paper's Sect. 3 setting) on perturbed arcs, built once per
// degree, noise and Moved: the points are P(t) moved by noise * uniform(0, 1) * the curve's
// diagonal in a random direction, as `bezinv profile --noise` does (noise 0: on the curve).
const Workload& workload(int degree, double noise = 0.0, Moved moved = Moved::all) {
  static std::map<std::tuple<int, double, Moved>, Workload> cache;
  auto [it, inserted] = cache.try_emplace({degree, noise, moved});
  Workload& w = it->second;
  if (inserted) {
    std::mt19937_64 rng(4242 + degree);
    for (int c = 0; c < kCurves; ++c) {
      w.curves.push_back(datasets::random_curve(CurveKind::rational_bezier, degree, rng,
                                                datasets::ControlPolygon::perturbed_arc));
      w.plans.push_back(make_plan(w.curves.back()));
      std::vector<Point> pts(kPointsPerCurve);
      for (std::size_t i = 0; i < pts.size(); ++i) {
        Point& p = pts[i];
        p = datasets::on_curve(w.curves.back(), datasets::uniform(rng, 0.0, 1.0));
        if (noise == 0.0) continue;
        const double angle = datasets::uniform(rng, 0.0, 2 * std::numbers::pi);
        const double offset = noise * datasets::uniform(rng, 0.0, 1.0) * w.plans.back().diagonal();
        if (moved == Moved::none || (moved == Moved::every_other && i % 2 == 0)) continue;
        p = {p.x + offset * std::cos(angle), p.y + offset * std::sin(angle)};
      }
      w.points.push_back(std::move(pts));
    }
  }
  return w;
}

// ---- the engine ------------------------------------------------------------------------------------

void run_engine(benchmark::State& state, bool refine, int threads, bool fast_path = true, double noise = 0.0,
                Moved moved = Moved::all) {
  const Workload& w = workload(static_cast<int>(state.range(0)), noise, moved);
  std::vector<PointResult> results(kPointsPerCurve);
  const InvertOptions options{.refine = refine, .threads = threads, .fast_path = fast_path};
  int c = 0;
  for (auto _ : state) {
    invert(w.plans[c], w.points[c], results, options);
    benchmark::DoNotOptimize(results.data());
    benchmark::ClobberMemory();
    c = (c + 1) % kCurves;
  }
  state.SetItemsProcessed(state.iterations() * kPointsPerCurve);
}

void BM_Engine_refined(benchmark::State& state) { run_engine(state, true, 1); }
void BM_Engine_algebraic(benchmark::State& state) { run_engine(state, false, 1); }
void BM_Engine_refined_svd_only(benchmark::State& state) { run_engine(state, true, 1, false); }
void BM_Engine_refined_all_cores(benchmark::State& state) { run_engine(state, true, 0); }
// Noisy points, 1 thread, the default tolerance (1e-6 of the diagonal): within it (1e-7), and
// beyond it (1e-5, 1e-4: rows off_curve, answered on the fast path where the isolation certificate
// proves the nearest point, by the SVD path's search elsewhere). range(1) = -log10(noise).
void BM_Engine_refined_noisy(benchmark::State& state) {
  run_engine(state, true, 1, true, std::pow(10.0, -static_cast<double>(state.range(1))));
}

// Mixed batches: the noisy workload with every other point moved (range(2) = 1), beside the same
// points all moved (2) and none moved (0), so that "mixed / apart", the mixed rate over
// 2 / (1 / none + 1 / all), is measured on one set of curves and parameters in one run.
void BM_Engine_refined_mixed(benchmark::State& state) {
  constexpr Moved kMoved[] = {Moved::none, Moved::every_other, Moved::all};
  run_engine(state, true, 1, true, std::pow(10.0, -static_cast<double>(state.range(1))), kMoved[state.range(2)]);
}

#define BEZINV_DEGREES ->Arg(3)->Arg(5)->Arg(8)->Arg(15)->Arg(20)->Unit(benchmark::kMicrosecond)
BENCHMARK(BM_Engine_refined) BEZINV_DEGREES;
BENCHMARK(BM_Engine_algebraic) BEZINV_DEGREES;
BENCHMARK(BM_Engine_refined_svd_only) BEZINV_DEGREES;
BENCHMARK(BM_Engine_refined_all_cores) BEZINV_DEGREES->UseRealTime();
BENCHMARK(BM_Engine_refined_noisy)
    ->ArgsProduct({{3, 8, 15, 20}, {7, 5, 4}})
    ->ArgNames({"n", "noise_exp"})
    ->Unit(benchmark::kMicrosecond);
BENCHMARK(BM_Engine_refined_mixed)
    ->ArgsProduct({{3, 8, 15}, {4, 2}, {0, 1, 2}})
    ->ArgNames({"n", "noise_exp", "moved"})
    ->Unit(benchmark::kMicrosecond);
#undef BEZINV_DEGREES

}  // namespace
