// `bezinv demo`: points with known parameters on the paper's Example 2 curve (degree 15) and on a
// cubic, inverted by the batched engine; prints speed and accuracy against the known parameters.
#include "demo.hpp"

#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <random>
#include <vector>

#include "bezinv/datasets/on_curve_points.hpp"
#include "bezinv/datasets/paper_curves.hpp"
#include "bezinv/datasets/random_numbers.hpp"
#include "bezinv/invert.hpp"
#include "bezinv/plan.hpp"

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>
#include <tbb/task_arena.h>

namespace bezinv::cli {
namespace {

// The accuracy the demo demands of every row. The points are P(t) rounded to double, so each is
// off the curve by at most half an ulp of its coordinates, and the default refinement (Newton to
// the nearest point, full double precision) returns t within about n u scale / |P'(t)| of t_true
// (scale ~ the size of the terms of P(t), u = 2^-53). On these two curves on [0,1] (Example 2:
// n = 15, |P'| >= 12, scale <= 30; the cubic: |P'| >= 4.5, scale <= 8) that is below 1e-14. 1e-9
// leaves five orders of magnitude for honest rounding and still fails at once on a wrong branch
// (the other parameter of a near double point), a wrong status, or a refinement that stalls.
constexpr double kMaxParameterError = 1e-9;

constexpr std::uint64_t kSeed = 20240607;

struct Row {
  int degree = 0;
  std::size_t points = 0;
  double points_per_second = 0;
  double median_error = 0, max_error = 0, max_relative_residual = 0;
  std::array<std::size_t, 6> status_counts{};
};

Row run_curve(const Curve& curve, std::size_t count, int threads, std::mt19937_64& rng) {
  const InversionPlan plan = make_plan(curve);
  std::vector<double> t_true(count);
  std::vector<Point> points(count);
  // Parameters come from one random stream (the same data for any thread count); the points are
  // evaluated in parallel, since the generator's compensated long-double evaluation costs more
  // than the inversion itself.
  for (std::size_t i = 0; i < count; ++i) t_true[i] = datasets::uniform(rng, 0.0, 1.0);
  auto evaluate = [&](const tbb::blocked_range<std::size_t>& range) {
    for (std::size_t i = range.begin(); i != range.end(); ++i) points[i] = datasets::on_curve(curve, t_true[i]);
  };
  tbb::task_arena arena(threads > 0 ? threads : tbb::task_arena::automatic);
  arena.execute([&] { tbb::parallel_for(tbb::blocked_range<std::size_t>(0, count, 4096), evaluate); });
  std::vector<PointResult> results(count);
  const auto start = std::chrono::steady_clock::now();
  invert(plan, points, results, {.threads = threads});
  const std::chrono::duration<double> elapsed = std::chrono::steady_clock::now() - start;

  Row row;
  row.degree = plan.degree();
  row.points = count;
  row.points_per_second = elapsed.count() > 0 ? static_cast<double>(count) / elapsed.count() : 0.0;
  std::vector<double> errors(count);
  for (std::size_t i = 0; i < count; ++i) {
    const PointResult& r = results[i];
    ++row.status_counts[static_cast<std::size_t>(r.status)];
    // A row without a finite t counts as an infinite error (NaN would slip through std::max).
    errors[i] = std::isfinite(r.t) ? std::abs(r.t - t_true[i]) : INFINITY;
    row.max_error = std::max(row.max_error, errors[i]);
    if (std::isfinite(r.residual))
      row.max_relative_residual = std::max(row.max_relative_residual, r.residual / plan.diagonal());
  }
  if (count > 0) {
    std::nth_element(errors.begin(), errors.begin() + count / 2, errors.end());
    row.median_error = errors[count / 2];
  }
  return row;
}

}  // namespace

int run_demo(std::size_t points, int threads) {
  const Curve curves[] = {datasets::paper_example2_curve(), datasets::default_cubic_curve()};
  const std::size_t share[] = {points - points / 2, points / 2};
  std::mt19937_64 rng(kSeed);

  std::printf("bezinv demo: %zu points with known t uniform in [0,1], threads %d (0 = all cores)\n\n", points,
              threads);
  std::printf("%-16s %6s %9s %10s %10s %10s %10s  %s\n", "curve", "degree", "points", "points/s", "median|dt|",
              "max|dt|", "max res/d", "statuses");
  bool pass = true;
  for (int c = 0; c < 2; ++c) {
    const Row row = run_curve(curves[c], share[c], threads, rng);
    std::printf("%-16s %6d %9zu %10.3g %10.2e %10.2e %10.2e  ", curves[c].id.c_str(), row.degree, row.points,
                row.points_per_second, row.median_error, row.max_error, row.max_relative_residual);
    for (std::size_t s = 0; s < row.status_counts.size(); ++s)
      if (row.status_counts[s] > 0 || s == 0)
        std::printf("%s%s=%zu", s == 0 ? "" : " ", to_string(static_cast<Status>(s)), row.status_counts[s]);
    std::printf("\n");
    pass = pass && row.status_counts[static_cast<std::size_t>(Status::ok)] == row.points &&
           row.max_error <= kMaxParameterError;
  }
  std::printf("\n%s: every row ok and max |t - t_true| <= %.0e\n", pass ? "PASS" : "FAIL", kMaxParameterError);
  return pass ? 0 : 1;
}

}  // namespace bezinv::cli
