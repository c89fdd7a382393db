// bezinv/profile.hpp: the profiled invert gives the unprofiled one's answers, bit for bit, and
// accounts its time to the stages.
#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <random>
#include <vector>

#include "support/bits.hpp"
#include "bezinv/datasets/curve_sampling.hpp"
#include "bezinv/datasets/on_curve_points.hpp"
#include "bezinv/datasets/random_curve.hpp"
#include "bezinv/invert.hpp"
#include "bezinv/plan.hpp"
#include "bezinv/profile.hpp"

namespace bezinv {
namespace {

using test_support::same_bits;

TEST(Profile, SameAnswersAsInvertWithTheTimeOfEachStage) {
  std::mt19937_64 rng(41);
  for (int degree : {3, 8, 17}) {
    const Curve curve = datasets::random_curve(CurveKind::rational_bezier, degree, rng);
    const InversionPlan plan = make_plan(curve);
    std::vector<Point> points;
    for (const datasets::KnownPoint& k : datasets::segment_points(datasets::CurveSampling(curve), 500, rng)) {
      points.push_back(k.point);
      points.push_back({k.point.x + 1e-3 * plan.diagonal(), k.point.y});  // off the curve: the SVD path too
    }
    std::vector<PointResult> plain(points.size()), profiled(points.size());
    InvertOptions options;
    options.threads = 2;
    invert(plan, points, plain, options);
    StageSeconds stages;
    invert(plan, points, profiled, options, stages);
    for (std::size_t i = 0; i < points.size(); ++i) {
      ASSERT_TRUE(same_bits(plain[i].t, profiled[i].t)) << "degree " << degree << ", point " << i;
      ASSERT_TRUE(same_bits(plain[i].residual, profiled[i].residual)) << i;
      ASSERT_EQ(plain[i].status, profiled[i].status) << i;
      ASSERT_EQ(plain[i].path, profiled[i].path) << i;
    }
    for (double s : {stages.form_b, stages.kernel, stages.read_out, stages.refine, stages.decide})
      EXPECT_GE(s, 0.0) << "degree " << degree;
    // Every stage that does work is timed: 1000 points take far more than a clock tick.
    EXPECT_GT(stages.kernel, 0.0) << "degree " << degree;
    EXPECT_GT(stages.refine, 0.0) << "degree " << degree;
    EXPECT_GT(stages.decide, 0.0) << "degree " << degree;
  }
}

}  // namespace
}  // namespace bezinv
