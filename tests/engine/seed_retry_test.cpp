// The seed retry (engine/src/pipeline/seed_retry.hpp): points near a high-degree curve, within the
// tolerance, whose seed does not settle in its two solves. Such points are found the way the engine
// finds them, by running the seed kernel on their Bezout matrices; each is made from a known foot
// of the perpendicular t0 (datasets::normal_offset_points: P(t0) moved along the normal, no other
// part of the segment as near). The retry must answer most of them without the SVD (path
// bezout_lu), each as the SVD path answers it: the same status, the known t0, the same distance;
// and a point's answer must not depend on the others waiting in the queue with it.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <random>
#include <vector>

#include "bezinv/datasets/curve_sampling.hpp"
#include "bezinv/datasets/off_curve_points.hpp"
#include "bezinv/datasets/random_curve.hpp"
#include "bezinv/invert.hpp"
#include "bezinv/kernels/batch.hpp"
#include "bezinv/plan.hpp"
#include "bezinv/tolerances.hpp"
#include "isolation.hpp"
#include "pipeline/seed_retry.hpp"
#include "plan_data.hpp"
#include "support/same_row.hpp"
#include "support/sanitizers.hpp"

namespace bezinv {
namespace {

// The accuracy model's slack on n u scale (as in invert_property_test.cpp).
constexpr double kUnitRoundoff = 0x1p-53;
constexpr double kSlack = 16;

struct RetryPoint {
  const InversionPlan* plan;
  datasets::KnownPoint known;
};

TEST(SeedRetry, AnswersTheLanesWhoseSeedFellShortAsTheSvdPathDoes) {
  const kernels::Implementation& kernel = kernels::active_implementation();
  // The same curves under the sanitizers, fewer points on each (a subset of the same points: each
  // curve draws its points from a generator of its own).
  constexpr int kCurves = 10;
  constexpr int kPointsPerCurve = test_support::kSanitizerThinning > 1 ? 250 : 800;
  constexpr std::size_t kLeastRetried = test_support::kSanitizerThinning > 1 ? 5 : 20;
  std::vector<InversionPlan> plans;
  plans.reserve(3 * kCurves);
  std::vector<RetryPoint> retried;
  std::size_t points = 0;
  for (int n : {12, 16, 20}) {
    std::mt19937_64 curves_rng(4100 + n);
    for (int c = 0; c < kCurves; ++c) {
      const Curve curve =
          datasets::random_curve(CurveKind::rational_bezier, n, curves_rng, datasets::ControlPolygon::perturbed_arc);
      std::mt19937_64 rng(9100 + 100 * n + c);
      plans.push_back(make_plan(curve));
      const detail::PlanData& data = detail::plan_data(plans.back());
      const datasets::CurveSampling sampling(curve);
      // Half the tolerance off the curve: status ok, and the off-curve path leaves every one.
      const std::vector<datasets::KnownPoint> known =
          datasets::normal_offset_points(sampling, kPointsPerCurve, 0.5 * kDefaultRelativeTolerance,
                                         0.5 * kDefaultRelativeTolerance, rng);
      points += known.size();
      // The engine's seed on each point's B (formed from the plan at these degrees), as the fast
      // path runs it.
      const std::size_t count = known.size(), stride = kernels::batch_stride(count);
      std::vector<double> u(count), v(count), z(n * stride), defect(stride), residual(stride), poison(stride);
      for (std::size_t i = 0; i < count; ++i) {
        const auto p = data.normalize(known[i].point.x, known[i].point.y);
        u[i] = p[0], v[i] = p[1];
      }
      kernel.bezout_null_vector_seed(n, count, stride, data.B0.data(), data.Bx.data(), data.By.data(),
                                     data.common_denominator ? nullptr : data.Bxy.data(), u.data(), v.data(),
                                     z.data(), defect.data(), residual.data(), poison.data(), kFastPathMaxDefect);
      for (std::size_t i = 0; i < count; ++i)
        if (defect[i] > kFastPathMaxDefect && defect[i] <= detail::kSeedRetryMaxDefect)
          retried.push_back({&plans.back(), known[i]});
    }
  }
  std::size_t answered = 0, by_gap = 0;
  double worst_dt = 0;
  for (const RetryPoint& r : retried) {
    const PointResult fast = invert_point(*r.plan, r.known.point);
    const PointResult svd = invert_point(*r.plan, r.known.point, {.fast_path = false});
    ASSERT_EQ(fast.status, svd.status) << "t0 " << r.known.t;
    EXPECT_EQ(fast.status, Status::ok) << "t0 " << r.known.t;
    if (fast.path != Path::bezout_lu) {
      EXPECT_TRUE(test_support::same_row(fast, svd)) << "t0 " << r.known.t;  // not retried successfully: the SVD path's row
      continue;
    }
    ++answered;
    // The known foot of the perpendicular, as the SVD path finds it, within the accuracy model's
    // bound (docs/accuracy-model.md: evaluating P(t) errs by about n u scale, which moves t by
    // that over the speed); the distance to within that rounding.
    const int n = r.plan->degree();
    const double rounding = kSlack * (n + 1) * kUnitRoundoff * std::max(r.known.scale, r.plan->diagonal());
    const double t_bound = rounding / r.known.speed + 4 * kUnitRoundoff;
    worst_dt = std::max(worst_dt, std::abs(fast.t - svd.t));
    EXPECT_LE(std::abs(fast.t - svd.t), 2 * t_bound) << "t0 " << r.known.t << ", t " << fast.t << ", SVD's " << svd.t;
    EXPECT_LE(std::abs(fast.t - r.known.t), t_bound) << "t0 " << r.known.t << ", t " << fast.t;
    EXPECT_LE(std::abs(fast.residual - r.known.distance), rounding) << "t0 " << r.known.t;
    // The evidence as on the fast path: no gap where the isolation certificate decided, the full
    // kernel's estimate where its gap did.
    const detail::PlanData& data = detail::plan_data(*r.plan);
    const auto p0 = data.normalize(r.known.point.x, r.known.point.y);
    const bool certified = detail::isolated(data, p0[0], p0[1], fast.t, fast.residual / data.scale,
                                            kDefaultRelativeTolerance * r.plan->diagonal() / data.scale);
    EXPECT_EQ(std::isnan(fast.sigma_next), certified) << "t0 " << r.known.t;
    by_gap += !certified;
  }
  std::printf("[ measured ] %zu of %zu points near curves of degree 12-20 had a seed that fell short; the retry "
              "answered %zu of them (%zu by the gap, the others by the isolation certificate; |t - t_svd| at most "
              "%.3g), the SVD path the rest\n",
              retried.size(), points, answered, by_gap, worst_dt);
  ASSERT_GE(retried.size(), kLeastRetried) << "the test needs seeds that fall short";
  EXPECT_GT(answered, retried.size() / 2);

  // Batched, with the queue shared by the points of a curve's batches, on one and two threads:
  // each row as the point alone gives it.
  for (const InversionPlan& plan : plans) {
    // Each point eight times over, so that the queue fills and runs between batches too.
    std::vector<Point> xy;
    for (int copy = 0; copy < 8; ++copy)
      for (const RetryPoint& r : retried)
        if (r.plan == &plan) xy.push_back(r.known.point);
    if (xy.empty()) continue;
    std::vector<PointResult> single(xy.size());
    for (std::size_t i = 0; i < xy.size(); ++i) single[i] = invert_point(plan, xy[i]);
    for (int threads : {1, 2}) {
      std::vector<PointResult> batched(xy.size());
      invert(plan, xy, batched, {.threads = threads});
      for (std::size_t i = 0; i < xy.size(); ++i)
        EXPECT_TRUE(test_support::same_row(batched[i], single[i])) << "threads " << threads << ", point " << i;
    }
  }
}

}  // namespace
}  // namespace bezinv
