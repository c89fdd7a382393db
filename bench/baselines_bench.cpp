// Points per second: bezinv against what a user would otherwise call one point at a time,
//   - OpenCASCADE: Geom2dAPI_ProjectPointOnCurve on a Geom2d_BezierCurve (poles + weights), the
//     parameter of the nearest extremum (LowerDistanceParameter);
//   - SISL: s1953 (all closest points between a curve and a point) on the same curve written as a
//     rational B-spline with Bezier knots, the candidate nearest to the point;
// the paper's way (bench/paper_way.hpp) and Eigen per point, and bezinv's batched `invert` (refined,
// one and two threads) on the very same points, so the ratios come from one run. Per degree: 64 random rational Bezier curves x 1024 isolated on-curve points at
// known t (datasets_gen), cycled so nothing is cache-hot (one iteration = one curve's 1024 points).
//
// Each benchmark also reports, from a separate untimed pass over all 64 x 1024 points,
//   agree      the fraction of points whose parameter is within kAgreement of the known t,
//   median_dt  the median |t - t_known|,
//   no_answer  the fraction of points for which the library returned no parameter at all.
// Which libraries are compiled in is decided by bench/CMakeLists.txt (BEZINV_HAVE_OCCT,
// BEZINV_HAVE_SISL); the bezinv benchmark is always there.
#include <benchmark/benchmark.h>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <functional>
#include <limits>
#include <map>
#include <tuple>
#include <memory>
#include <random>
#include <string>
#include <vector>

#include "bezinv/datasets/curve_sampling.hpp"
#include "plan_data.hpp"
#include "bezinv/datasets/on_curve_points.hpp"
#include "bezinv/datasets/random_curve.hpp"
#include "bezinv/invert.hpp"
#include "bezinv/plan.hpp"
#include "bezinv/null_vector.hpp"
#include "baselines.hpp"
#include "paper_way.hpp"

#include <Eigen/Eigenvalues>


namespace {

using namespace bezinv;

constexpr int kCurves = 64;
constexpr int kPointsPerCurve = 1024;

// A parameter "agrees" with the known one within this: far above what any of the three can reach
// on these curves (bezinv's refined t is within ~1e-15), far below what a wrong extremum gives.
constexpr double kAgreement = 1e-7;


constexpr double kNan = std::numeric_limits<double>::quiet_NaN();

struct Workload {
  std::vector<Curve> curves;
  std::vector<std::vector<Point>> points;  // kPointsPerCurve per curve
  std::vector<std::vector<double>> t;      // their known parameters, uniform in [0,1]
  // Noisy workloads: each point's distance to P(t), the point it was moved from (an upper bound of
  // its distance to the segment); empty on the curve.
  std::vector<std::vector<double>> base_distance;
};

// Random rational Bezier curves on perturbed arcs (the same family as invert_bench.cpp) and
// isolated points on them (segment_points: no other branch within 1e-4 of the diagonal, so the
// nearest point of the curve - what OCCT and SISL return - is the known one). A curve that cannot
// give kPointsPerCurve isolated points is replaced by another draw.
const Workload& workload(int degree) {
  static std::map<int, Workload> cache;
  auto [it, inserted] = cache.try_emplace(degree);
  Workload& w = it->second;
  if (inserted) {
    std::mt19937_64 rng(7000 + degree);
    while (static_cast<int>(w.curves.size()) < kCurves) {
      Curve curve = datasets::random_curve(CurveKind::rational_bezier, degree, rng,
                                           datasets::ControlPolygon::perturbed_arc);
      const datasets::CurveSampling sampling(curve);
      const std::vector<datasets::KnownPoint> known = datasets::segment_points(sampling, kPointsPerCurve, rng);
      if (static_cast<int>(known.size()) < kPointsPerCurve) continue;
      std::vector<Point> points;
      std::vector<double> t;
      for (const datasets::KnownPoint& k : known) {
        points.push_back(k.point);
        t.push_back(k.t);
      }
      w.curves.push_back(std::move(curve));
      w.points.push_back(std::move(points));
      w.t.push_back(std::move(t));
    }
  }
  return w;
}

const Workload& workload(int degree, int noise_exponent);

// Half and half: the points of workload(degree, noise_exponent) at odd k, those on the curve at
// even k (base distances ~0 there), so every batch holds both kinds.
const Workload& mixed_workload(int degree, int noise_exponent) {
  static std::map<std::pair<int, int>, Workload> cache;
  auto [it, inserted] = cache.try_emplace(std::make_pair(degree, noise_exponent));
  Workload& w = it->second;
  if (inserted) {
    const Workload &on = workload(degree), &off = workload(degree, noise_exponent);
    w = off;
    for (std::size_t c = 0; c < w.curves.size(); ++c)
      for (std::size_t k = 0; k < w.points[c].size(); k += 2) {
        w.points[c][k] = on.points[c][k];
        const auto q = on.curves[c].point(on.t[c][k]);
        w.base_distance[c][k] = std::hypot(on.points[c][k].x - q[0], on.points[c][k].y - q[1]);
      }
  }
  return w;
}

// The same curves and parameters, each point moved off the curve by Gaussian noise of standard
// deviation 10^-noise_exponent x the curve's diagonal in each coordinate (noise_exponent 0: the
// points on the curve, workload(degree); negative: mixed_workload(degree, -noise_exponent)).
const Workload& workload(int degree, int noise_exponent) {
  if (noise_exponent == 0) return workload(degree);
  if (noise_exponent < 0) return mixed_workload(degree, -noise_exponent);
  static std::map<std::pair<int, int>, Workload> cache;
  auto [it, inserted] = cache.try_emplace(std::make_pair(degree, noise_exponent));
  Workload& w = it->second;
  if (inserted) {
    const Workload& on = workload(degree);
    w.curves = on.curves;
    w.t = on.t;
    std::mt19937_64 rng(9100 + 31 * degree + noise_exponent);
    std::normal_distribution<double> gaussian;
    for (std::size_t c = 0; c < on.curves.size(); ++c) {
      const double sigma = std::pow(10.0, -noise_exponent) * make_plan(on.curves[c]).diagonal();
      std::vector<Point> points;
      std::vector<double> base;
      for (std::size_t k = 0; k < on.points[c].size(); ++k) {
        const Point p = on.points[c][k];
        const Point moved{p.x + sigma * gaussian(rng), p.y + sigma * gaussian(rng)};
        const auto q = on.curves[c].point(on.t[c][k]);
        points.push_back(moved);
        base.push_back(std::hypot(moved.x - q[0], moved.y - q[1]));
      }
      w.points.push_back(std::move(points));
      w.base_distance.push_back(std::move(base));
    }
  }
  return w;
}

struct Agreement {
  double agree = 0, median_dt = 0, no_answer = 0;
  double fast_path = -1;    // bezinv only: the share of rows answered by the fast path (bezout_lu, formula)
  double by_distance = -1;  // bezinv only: the share answered off_curve by distance alone
};

// The untimed check: parameter(c, k) for every point of every curve against the known t. Off the
// curve the known t is not the answer (the nearest point is): there a parameter agrees when its
// point is at least as near as the point the noisy point was made from (to 1e-9 relative, 1e-12
// of the diagonal), which a wrong extremum is not; dt is still |t - t_known|.
Agreement measure_agreement(const Workload& w, const std::function<double(int, int)>& parameter) {
  std::vector<double> dt;
  int agreeing = 0, missing = 0;
  for (int c = 0; c < kCurves; ++c)
    for (int k = 0; k < kPointsPerCurve; ++k) {
      const double t = parameter(c, k);
      if (std::isnan(t)) {
        ++missing;
        dt.push_back(std::numeric_limits<double>::infinity());
        continue;
      }
      dt.push_back(std::abs(t - w.t[c][k]));
      if (w.base_distance.empty()) {
        if (dt.back() <= kAgreement) ++agreeing;
      } else {
        const auto q = w.curves[c].point(t);
        const double d = std::hypot(w.points[c][k].x - q[0], w.points[c][k].y - q[1]);
        if (d <= w.base_distance[c][k] * (1 + 1e-9) + 1e-12) ++agreeing;
      }
    }
  std::nth_element(dt.begin(), dt.begin() + dt.size() / 2, dt.end());
  const double total = static_cast<double>(dt.size());
  return {agreeing / total, dt[dt.size() / 2], missing / total};
}

// Google Benchmark calls a benchmark function several times while it sizes the run: the check is
// made once per (library, degree).
void report_agreement(benchmark::State& state, const std::string& library, int noise_exponent,
                      const std::function<Agreement()>& measure) {
  static std::map<std::tuple<std::string, int, int>, Agreement> cache;
  const auto key = std::make_tuple(library, static_cast<int>(state.range(0)), noise_exponent);
  auto it = cache.find(key);
  if (it == cache.end()) it = cache.emplace(key, measure()).first;
  state.counters["agree"] = it->second.agree;
  state.counters["median_dt"] = it->second.median_dt;
  state.counters["no_answer"] = it->second.no_answer;
  if (it->second.fast_path >= 0) state.counters["fast_path"] = it->second.fast_path;
  if (it->second.by_distance >= 0) state.counters["by_distance"] = it->second.by_distance;
}

// ---- bezinv ----------------------------------------------------------------------------------------

const std::vector<InversionPlan>& plans(int degree) {
  static std::map<int, std::vector<InversionPlan>> cache;
  auto [it, inserted] = cache.try_emplace(degree);
  if (inserted)
    for (const Curve& curve : workload(degree).curves) it->second.push_back(make_plan(curve));
  return it->second;
}

void run_bezinv(benchmark::State& state, int threads, const char* label, int noise_exponent = 0,
                Algebraic algebraic = Algebraic::automatic) {
  const int n = static_cast<int>(state.range(0));
  const Workload& w = workload(n, noise_exponent);
  const std::vector<InversionPlan>& p = plans(n);
  const InvertOptions options{.threads = threads, .algebraic = algebraic};
  std::vector<PointResult> results(kPointsPerCurve);
  // What a plan makes on first use (the formula path's formula: ~1 ms at degree 8, tens of ms at
  // 20) is made before the timing, as the plans are: one untimed pass.
  for (int curve = 0; curve < kCurves; ++curve) invert(p[curve], w.points[curve], results, options);
  int c = 0;
  for (auto _ : state) {
    invert(p[c], w.points[c], results, options);
    benchmark::DoNotOptimize(results.data());
    benchmark::ClobberMemory();
    c = (c + 1) % kCurves;
  }
  state.SetItemsProcessed(state.iterations() * kPointsPerCurve);
  report_agreement(state, label, noise_exponent, [&] {
    std::vector<std::vector<double>> t(kCurves);
    std::size_t fast = 0, by_distance = 0;
    for (int curve = 0; curve < kCurves; ++curve) {
      invert(p[curve], w.points[curve], results, options);
      for (const PointResult& r : results) {
        t[curve].push_back(r.t);
        fast += r.path == Path::bezout_lu || r.path == Path::formula;
        by_distance += r.path == Path::nearest && std::isnan(r.sigma_min);
      }
    }
    Agreement a = measure_agreement(w, [&](int curve, int k) { return t[curve][k]; });
    a.fast_path = static_cast<double>(fast) / (kCurves * kPointsPerCurve);
    a.by_distance = static_cast<double>(by_distance) / (kCurves * kPointsPerCurve);
    return a;
  });
}

void BM_Bezinv_refined(benchmark::State& state) { run_bezinv(state, 1, "bezinv"); }
// The Bezout path on every curve (--algebraic bezout): what the default ran on conics and cubics
// before it took their inversion formula; beside the default, in the same run.
void BM_Bezinv_refined_bezout(benchmark::State& state) {
  run_bezinv(state, 1, "bezinv_bezout", 0, Algebraic::bezout);
}
// The formula path on every curve that has a formula (--algebraic formula): the inversion formula's
// N/M as the start of the refinement where the default forms B and runs its seed, from degree 4.
void BM_Bezinv_refined_formula(benchmark::State& state) {
  run_bezinv(state, 1, "bezinv_formula", 0, Algebraic::formula);
}
// Two threads: wall-clock time (UseRealTime at registration), so items_per_second is the throughput.
void BM_Bezinv_refined_2threads(benchmark::State& state) { run_bezinv(state, 2, "bezinv"); }
// Off the curve (range(1): the noise exponent, workload(degree, noise_exponent)), one thread.
void BM_Bezinv_refined_noisy(benchmark::State& state) {
  run_bezinv(state, 1, "bezinv", static_cast<int>(state.range(1)));
}

// Half the points on the curve, half at noise 10^-e (alternating): no slower than the two apart.
void BM_Bezinv_refined_mixed(benchmark::State& state) {
  run_bezinv(state, 1, "bezinv", -static_cast<int>(state.range(1)));
}

// ---- the paper's way, and Eigen per point ----------------------------------------------------------

// bench/paper_way.hpp: recurrence as printed + Eigen::JacobiSVD per point, algebraic t only.
void BM_Paper_recurrence_JacobiSVD(benchmark::State& state) {
  const int n = static_cast<int>(state.range(0));
  const Workload& w = workload(n);
  bench::PaperWay paper(n);
  std::vector<double> t(kPointsPerCurve);
  int c = 0;
  for (auto _ : state) {
    for (int k = 0; k < kPointsPerCurve; ++k) t[k] = paper.parameter(w.curves[c], w.points[c][k]);
    benchmark::DoNotOptimize(t.data());
    benchmark::ClobberMemory();
    c = (c + 1) % kCurves;
  }
  state.SetItemsProcessed(state.iterations() * kPointsPerCurve);
  report_agreement(state, "paper", 0, [&] {
    return measure_agreement(w, [&](int curve, int k) { return paper.parameter(w.curves[curve], w.points[curve][k]); });
  });
}

// bezinv's plan (B from four precomputed matrices) with Eigen's SelfAdjointEigenSolver per point on
// fixed-capacity storage (no allocation), and bezinv's read-out: what the engine would be with
// Eigen as its kernel and no batching. Algebraic t only.
using EigenMatrix = Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, 0, kMaxDegree, kMaxDegree>;
double eigen_parameter(const InversionPlan& plan, Point point, EigenMatrix& B,
                       Eigen::SelfAdjointEigenSolver<EigenMatrix>& solver) {
  const int n = plan.degree();
  const auto uv = bezinv::detail::plan_data(plan).normalize(point.x, point.y);
  bezinv::detail::bezout_at(bezinv::detail::plan_data(plan), uv[0], uv[1], std::span<double>(B.data(), static_cast<std::size_t>(n) * n));
  solver.compute(B, Eigen::ComputeEigenvectors);
  // The eigenvalue of least magnitude and its vector.
  int k = 0;
  for (int i = 1; i < n; ++i)
    if (std::abs(solver.eigenvalues()[i]) < std::abs(solver.eigenvalues()[k])) k = i;
  const Eigen::Matrix<double, Eigen::Dynamic, 1, 0, kMaxDegree, 1> z = solver.eigenvectors().col(k);
  return parameter_from_null_vector(std::span<const double>(z.data(), n));
}

void BM_Eigen_SelfAdjoint_per_point(benchmark::State& state) {
  const int n = static_cast<int>(state.range(0));
  const Workload& w = workload(n);
  const std::vector<InversionPlan>& p = plans(n);
  EigenMatrix B(n, n);
  Eigen::SelfAdjointEigenSolver<EigenMatrix> solver(n);
  std::vector<double> t(kPointsPerCurve);
  int c = 0;
  for (auto _ : state) {
    for (int k = 0; k < kPointsPerCurve; ++k) t[k] = eigen_parameter(p[c], w.points[c][k], B, solver);
    benchmark::DoNotOptimize(t.data());
    benchmark::ClobberMemory();
    c = (c + 1) % kCurves;
  }
  state.SetItemsProcessed(state.iterations() * kPointsPerCurve);
  report_agreement(state, "eigen", 0, [&] {
    return measure_agreement(w, [&](int curve, int k) { return eigen_parameter(p[curve], w.points[curve][k], B, solver); });
  });
}

// The workload's curves as the library holds them (engine/cli/baselines.hpp).
using Projectors = std::vector<std::unique_ptr<baselines::Projector>>;
const Projectors& projectors(baselines::Library library, int degree) {
  static std::map<std::pair<baselines::Library, int>, Projectors> cache;
  auto [it, inserted] = cache.try_emplace({library, degree});
  if (inserted)
    for (const Curve& curve : workload(degree).curves) it->second.push_back(baselines::projector(library, curve));
  return it->second;
}

// ---- OpenCASCADE -----------------------------------------------------------------------------------

#ifdef BEZINV_HAVE_OCCT

void run_occt(benchmark::State& state, int noise_exponent) {
  const int n = static_cast<int>(state.range(0));
  const Workload& w = workload(n, noise_exponent);
  const Projectors& curves = projectors(baselines::Library::occt, n);
  std::vector<double> t(kPointsPerCurve);
  int c = 0;
  for (auto _ : state) {
    for (int k = 0; k < kPointsPerCurve; ++k) t[k] = curves[c]->parameter(w.points[c][k]);
    benchmark::DoNotOptimize(t.data());
    benchmark::ClobberMemory();
    c = (c + 1) % kCurves;
  }
  state.SetItemsProcessed(state.iterations() * kPointsPerCurve);
  report_agreement(state, "occt", noise_exponent, [&] {
    return measure_agreement(w, [&](int curve, int k) { return curves[curve]->parameter(w.points[curve][k]); });
  });
}

void BM_OCCT_ProjectPointOnCurve(benchmark::State& state) { run_occt(state, 0); }
void BM_OCCT_ProjectPointOnCurve_noisy(benchmark::State& state) { run_occt(state, static_cast<int>(state.range(1))); }

#endif  // BEZINV_HAVE_OCCT

// ---- SISL ------------------------------------------------------------------------------------------

#ifdef BEZINV_HAVE_SISL

void run_sisl(benchmark::State& state, int noise_exponent) {
  if (!baselines::stack_is_large()) {
    state.SkipWithError("SISL's s1953 can overflow an 8 MiB stack: run under `ulimit -s unlimited`");
    for (auto _ : state) {
    }
    return;
  }
  const int n = static_cast<int>(state.range(0));
  const Workload& w = workload(n, noise_exponent);
  const Projectors& curves = projectors(baselines::Library::sisl, n);
  std::vector<double> t(kPointsPerCurve);
  int c = 0;
  for (auto _ : state) {
    for (int k = 0; k < kPointsPerCurve; ++k) t[k] = curves[c]->parameter(w.points[c][k]);
    benchmark::DoNotOptimize(t.data());
    benchmark::ClobberMemory();
    c = (c + 1) % kCurves;
  }
  state.SetItemsProcessed(state.iterations() * kPointsPerCurve);
  report_agreement(state, "sisl", noise_exponent, [&] {
    return measure_agreement(w, [&](int curve, int k) { return curves[curve]->parameter(w.points[curve][k]); });
  });
}

void BM_SISL_ClosestPoint(benchmark::State& state) { run_sisl(state, 0); }
void BM_SISL_ClosestPoint_noisy(benchmark::State& state) { run_sisl(state, static_cast<int>(state.range(1))); }

#endif  // BEZINV_HAVE_SISL

// Registered degree by degree (OCCT/n, SISL/n, the paper's way, Eigen, bezinv on 1 and 2 threads,
// then the next n), so a degree's figures are measured close together and its ratios compare.
const bool registered = [] {
  for (int n = 1; n <= 24; ++n) {
#ifdef BEZINV_HAVE_OCCT
    benchmark::RegisterBenchmark("BM_OCCT_ProjectPointOnCurve", BM_OCCT_ProjectPointOnCurve)->Arg(n)->Unit(benchmark::kMicrosecond);
#endif
#ifdef BEZINV_HAVE_SISL
    benchmark::RegisterBenchmark("BM_SISL_ClosestPoint", BM_SISL_ClosestPoint)->Arg(n)->Unit(benchmark::kMicrosecond);
#endif
    if (n >= 2) {  // B is 1 x 1 at degree 1: no null vector to read
      benchmark::RegisterBenchmark("BM_Paper_recurrence_JacobiSVD", BM_Paper_recurrence_JacobiSVD)->Arg(n)->Unit(benchmark::kMicrosecond);
      benchmark::RegisterBenchmark("BM_Eigen_SelfAdjoint_per_point", BM_Eigen_SelfAdjoint_per_point)->Arg(n)->Unit(benchmark::kMicrosecond);
    }
    benchmark::RegisterBenchmark("BM_Bezinv_refined", BM_Bezinv_refined)->Arg(n)->Unit(benchmark::kMicrosecond);
    if (n <= 3)
      benchmark::RegisterBenchmark("BM_Bezinv_refined_bezout", BM_Bezinv_refined_bezout)
          ->Arg(n)
          ->Unit(benchmark::kMicrosecond);
    if (n >= 4 && n <= 20)
      benchmark::RegisterBenchmark("BM_Bezinv_refined_formula", BM_Bezinv_refined_formula)
          ->Arg(n)
          ->Unit(benchmark::kMicrosecond);
    benchmark::RegisterBenchmark("BM_Bezinv_refined_2threads", BM_Bezinv_refined_2threads)
        ->Arg(n)
        ->UseRealTime()
        ->Unit(benchmark::kMicrosecond);
  }
  // Off the curve: degrees 2-20 at noise 1e-6, 1e-4 and 1e-2 of the diagonal (Gaussian, per
  // coordinate), OCCT, SISL and bezinv on one thread, degree by degree and noise by noise.
  for (int n = 2; n <= 20; ++n)
    for (int noise_exponent : {6, 4, 2}) {
#ifdef BEZINV_HAVE_OCCT
      benchmark::RegisterBenchmark("BM_OCCT_ProjectPointOnCurve_noisy", BM_OCCT_ProjectPointOnCurve_noisy)
          ->Args({n, noise_exponent})
          ->Unit(benchmark::kMicrosecond);
#endif
#ifdef BEZINV_HAVE_SISL
      benchmark::RegisterBenchmark("BM_SISL_ClosestPoint_noisy", BM_SISL_ClosestPoint_noisy)
          ->Args({n, noise_exponent})
          ->Unit(benchmark::kMicrosecond);
#endif
      benchmark::RegisterBenchmark("BM_Bezinv_refined_noisy", BM_Bezinv_refined_noisy)
          ->Args({n, noise_exponent})
          ->Unit(benchmark::kMicrosecond);
      if (noise_exponent != 6)
        benchmark::RegisterBenchmark("BM_Bezinv_refined_mixed", BM_Bezinv_refined_mixed)
            ->Args({n, noise_exponent})
            ->Unit(benchmark::kMicrosecond);
    }
  return true;
}();

}  // namespace
