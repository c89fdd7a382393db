// `bezinv profile`: generate curves (datasets_gen) and points at known parameters, run the batch
// pipeline in memory, report throughput per stage. Stage figures are points per second of work
// in that stage summed over threads; the total is points per wall-clock second.
#include "profile.hpp"

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>
#include <tbb/task_arena.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <numbers>
#include <random>
#include <span>
#include <vector>

#include "bezinv/datasets/random_curve.hpp"
#include "bezinv/datasets/random_numbers.hpp"
#include "bezinv/invert.hpp"
#include "bezinv/profile.hpp"
#include "bezinv/plan.hpp"

namespace bezinv::cli {
namespace {

struct Workload {
  std::vector<InversionPlan> plans;
  std::vector<std::vector<Point>> points;   // per curve (plane curves)
  std::vector<std::vector<Point3>> points3;  // per curve (space curves)
  std::vector<std::vector<double>> t_true;  // per curve
};

Workload generate(const ProfileOptions& options) {
  std::mt19937_64 rng(options.seed);
  Workload w;
  const int curves = std::max(1, options.curves);
  for (int c = 0; c < curves; ++c) {
    Curve curve = datasets::random_curve(options.kind, options.degree, rng, datasets::ControlPolygon::perturbed_arc);
    if (options.dimension == 3) {
      // Lifted off its plane: z = z_num / x_den, z_i uniform in +-0.3 of the plane curve's size.
      const double size = make_plan(curve).diagonal();
      for (std::size_t i = 0; i < curve.x_den.size(); ++i)
        curve.z_num.push_back(curve.x_den[i] * datasets::uniform(rng, -0.3, 0.3) * size);
      curve.z_den = curve.x_den;
    }
    w.plans.push_back(make_plan(curve));
    // Made here, untimed, as the rest of the plan: otherwise the first off-curve point of each
    // curve would make it inside the timed inversion.
    if (options.noise > 0) w.plans.back().prepare_off_curve();
    const std::size_t count = options.points / curves + (static_cast<std::size_t>(c) < options.points % curves);
    std::vector<double> t(count), angle(count), offset(count), polar(count);
    for (std::size_t i = 0; i < count; ++i) {
      t[i] = datasets::uniform(rng, 0.0, 1.0);
      angle[i] = datasets::uniform(rng, 0.0, 2 * std::numbers::pi);
      offset[i] = options.noise * datasets::uniform(rng, 0.0, 1.0) * w.plans.back().diagonal();
      if (options.mixed && i % 2 == 0) offset[i] = 0.0;  // drawn all the same: the off ones stay as without
      // A direction uniform on the sphere (space curves only: the plane workload's random numbers
      // stay as they were, so its figures compare across versions).
      if (options.dimension == 3) polar[i] = std::acos(datasets::uniform(rng, -1.0, 1.0));
    }
    if (options.dimension == 3) {
      std::vector<Point3> points(count);
      tbb::parallel_for(tbb::blocked_range<std::size_t>(0, count, 4096), [&](const auto& range) {
        for (std::size_t i = range.begin(); i != range.end(); ++i) {
          const auto p = curve.point3(t[i]);
          const double s = std::sin(polar[i]);
          points[i] = Point3(p[0] + offset[i] * s * std::cos(angle[i]), p[1] + offset[i] * s * std::sin(angle[i]),
                             p[2] + offset[i] * std::cos(polar[i]));
        }
      });
      w.points3.push_back(std::move(points));
      w.t_true.push_back(std::move(t));
      continue;
    }
    std::vector<Point> points(count);
    // P(t) in double (Curve::point, de Casteljau): the profile measures speed; the accuracy
    // figures it prints are a sanity check, the tests hold the accuracy guarantees.
    tbb::parallel_for(tbb::blocked_range<std::size_t>(0, count, 4096), [&](const auto& range) {
      for (std::size_t i = range.begin(); i != range.end(); ++i) {
        const auto p = curve.point(t[i]);
        points[i] = {p[0] + offset[i] * std::cos(angle[i]), p[1] + offset[i] * std::sin(angle[i])};
      }
    });
    w.points.push_back(std::move(points));
    w.t_true.push_back(std::move(t));
  }
  return w;
}

}  // namespace

int run_profile(const ProfileOptions& options) {
  if (options.degree < 1 || options.degree > kMaxDegree) {
    std::fprintf(stderr, "bezinv profile: --degree must be in 1..%d\n", kMaxDegree);
    return 2;
  }
  const Workload w = generate(options);
  InvertOptions invert_options;
  invert_options.refine = options.refine;
  invert_options.fast_path = options.fast_path;
  invert_options.algebraic = options.algebraic;
  invert_options.off_curve = options.off_curve;
  invert_options.threads = options.threads;

  const bool space = options.dimension == 3;
  auto count_of = [&](std::size_t c) { return space ? w.points3[c].size() : w.points[c].size(); };
  // One curve's points, every point or the first `limit`, with or without the stage clocks.
  auto run = [&](std::size_t c, std::span<PointResult> out, StageSeconds* stages) {
    if (space) {
      const std::span<const Point3> p(w.points3[c].data(), out.size());
      if (stages) invert(w.plans[c], p, out, invert_options, *stages);
      else invert(w.plans[c], p, out, invert_options);
    } else {
      const std::span<const Point> p(w.points[c].data(), out.size());
      if (stages) invert(w.plans[c], p, out, invert_options, *stages);
      else invert(w.plans[c], p, out, invert_options);
    }
  };
  std::vector<std::vector<PointResult>> results(w.plans.size());
  for (std::size_t c = 0; c < w.plans.size(); ++c) results[c].resize(count_of(c));
  // Three passes over the same points. A short one first, so that neither timed pass pays for
  // the first call's per-thread workspaces and thread pool. The total from a pass without the
  // stage clocks: reading them costs about a tenth of the work at degree 3 (eight reads a batch
  // of 64 points). The stages from a pass with them.
  {
    const std::size_t warm = std::min<std::size_t>(count_of(0), 1 << 16);
    run(0, std::span<PointResult>(results[0].data(), warm), nullptr);
  }
  const auto start = std::chrono::steady_clock::now();
  for (std::size_t c = 0; c < w.plans.size(); ++c) run(c, results[c], nullptr);
  const double wall = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  StageSeconds stages;  // (into the same results: a point's answer does not depend on the pass)
  for (std::size_t c = 0; c < w.plans.size(); ++c) run(c, results[c], &stages);

  std::size_t total = 0, ok = 0, fast = 0, formula = 0, certified = 0, by_distance = 0, projected = 0;
  double max_dt = 0;
  for (std::size_t c = 0; c < w.plans.size(); ++c)
    for (std::size_t i = 0; i < results[c].size(); ++i, ++total) {
      const PointResult& r = results[c][i];
      ok += r.status == Status::ok;
      fast += r.path == Path::bezout_lu || r.path == Path::formula;
      formula += r.path == Path::formula;
      certified += (r.path == Path::bezout_lu || r.path == Path::formula) && std::isnan(r.sigma_next);  // the isolation certificate's rows
      by_distance += r.path == Path::nearest && std::isnan(r.sigma_min);    // the off-curve path's rows
      projected += r.path == Path::projection;
      if (r.status == Status::ok) max_dt = std::max(max_dt, std::abs(r.t - w.t_true[c][i]));
    }
  const int threads = options.threads > 0 ? options.threads : tbb::this_task_arena::max_concurrency();
  const double pps = wall > 0 ? static_cast<double>(total) / wall : 0.0;
  auto rate = [&](double seconds) { return seconds > 0 ? static_cast<double>(total) / seconds : 0.0; };
  const std::string_view kernel = active_kernel_name();

  if (options.json) {
    std::printf(
        "{\"points_per_second\": %.6g, \"degree\": %d, \"dimension\": %d, \"threads\": %d, \"kernel\": \"%.*s\", \"kind\": \"%s\", "
        "\"points\": %zu, \"curves\": %zu, \"noise\": %g, \"mixed\": %s, \"refine\": %s, \"seconds\": %.6g, "
        "\"stages_points_per_second\": {\"form_b\": %.6g, \"kernel\": %.6g, \"read_out\": %.6g, \"refine\": %.6g, "
        "\"off_curve\": %.6g, \"decide\": %.6g, \"space\": %.6g}, \"ok\": %zu, \"fast_path\": %zu, \"certified\": %zu, "
        "\"formula\": %zu, \"off_curve_path\": %zu, \"projection\": %zu, \"max_abs_dt_ok\": %.3g}\n",
        pps, options.degree, options.dimension, threads, static_cast<int>(kernel.size()), kernel.data(), to_string(options.kind), total,
        w.plans.size(), options.noise, options.mixed ? "true" : "false", options.refine ? "true" : "false", wall,
        rate(stages.form_b),
        rate(stages.kernel), rate(stages.read_out), rate(stages.refine), rate(stages.off_curve), rate(stages.decide),
        rate(stages.space), ok, fast, certified, formula, by_distance, projected, max_dt);
    return 0;
  }
  std::printf("bezinv profile: %zu points on %zu %s %s curves of degree %d, noise %g%s, refine %s, threads %d, kernel %.*s\n\n",
              total, w.plans.size(), space ? "space" : "plane", to_string(options.kind), options.degree, options.noise,
              options.mixed ? " (every other point on the curve)" : "", options.refine ? "on" : "off", threads,
              static_cast<int>(kernel.size()), kernel.data());
  std::printf("%-34s %14s %10s\n", "stage", "points/s", "share");
  const double work =
      stages.form_b + stages.kernel + stages.read_out + stages.refine + stages.off_curve + stages.decide + stages.space;
  auto line = [&](const char* name, double seconds) {
    std::printf("%-34s %14.4g %9.1f%%\n", name, rate(seconds), work > 0 ? 100 * seconds / work : 0.0);
  };
  line("form B", stages.form_b);
  line("kernel (seed, LU, SVD; formula)", stages.kernel);
  line("read-out", stages.read_out);
  line("refine + residual", stages.refine);
  line("off the curve, by distance", stages.off_curve);
  line("decide (status, rare paths)", stages.decide);
  if (space) line("in space (project, check, refine)", stages.space);
  std::printf("%-34s %14.4g   (wall clock, %.3f s)\n\n", "total", pps, wall);
  std::printf("ok %zu of %zu; max |t - t_true| over ok rows %.3g\n", ok, total, max_dt);
  auto percent = [&](std::size_t k) { return total ? 100.0 * static_cast<double>(k) / static_cast<double>(total) : 0.0; };
  std::printf("answered by the fast path (null vector or inversion formula without an SVD, paths bezout_lu and "
              "formula): %zu of %zu (%.1f%%), "
              "%zu (%.1f%%) of them settled by the isolation certificate without a gap; the others by the SVD\n",
              fast, total, percent(fast), certified, percent(certified));
  std::printf("of them started by the inversion formula (path formula): %zu (%.1f%%)\n", formula, percent(formula));
  std::printf("answered off_curve by distance alone (path nearest, no singular values): %zu (%.1f%%)\n", by_distance,
              percent(by_distance));
  if (options.off_curve == OffCurve::projection)
    std::printf("answered off_curve by the inversion formula's projection (path projection): %zu (%.1f%%)\n",
                projected, percent(projected));
  return 0;
}

}  // namespace bezinv::cli
