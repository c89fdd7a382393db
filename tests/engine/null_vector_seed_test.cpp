// The seed kernels (kernels::Implementation::null_vector_seed: L D L^T without pivoting, and
// bezout_null_vector_seed, the same on B formed from the plan, where the engine uses it) on the
// matrices they are used for: Bezout matrices of points on random curves, constructed from a known t.
// The engine's answers do not depend on how good the seed is (every lane the isolation
// certificate does not settle is redone pivoted), so the other tests would not notice a poor one:
// this one does. Newton from the seed must land on the known parameter, as it does from the
// pivoted null vector, on every implementation.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <random>
#include <string>
#include <vector>

#include "bezinv/datasets/random_curve.hpp"
#include "plan_data.hpp"
#include "bezinv/datasets/random_numbers.hpp"
#include "bezinv/kernels/batch.hpp"
#include "bezinv/null_vector.hpp"
#include "bezinv/plan.hpp"
#include "bezinv/tolerances.hpp"
#include "refine.hpp"

namespace bezinv {
namespace {

TEST(NullVectorSeed, RefinesToTheKnownParameterOnBezoutMatrices) {
  constexpr std::size_t kLanes = 64;
  const std::size_t stride = kernels::batch_stride(kLanes);
  std::size_t points = 0, landed = 0;
  for (auto polygon : {datasets::ControlPolygon::perturbed_arc, datasets::ControlPolygon::unit_square})
    for (CurveKind kind : {CurveKind::rational_bezier, CurveKind::rational})
      for (int n : {3, 5, 8, 12, 15, 20}) {
        std::mt19937_64 rng(977 + n);
        for (int curve_index = 0; curve_index < 4; ++curve_index) {
          const detail::PlanData plan = detail::plan_data(make_plan(datasets::random_curve(kind, n, rng, polygon)));
          const std::size_t nn = static_cast<std::size_t>(n) * n;
          std::vector<double> B(nn * stride), entries(nn), z(n * stride), defect(stride), residual(stride);
          std::vector<double> t_true(kLanes), u(kLanes), v(kLanes);
          for (std::size_t l = 0; l < kLanes; ++l) {
            t_true[l] = datasets::uniform(rng, 0.0, 1.0);
            const auto p = plan.normalized_point(t_true[l]);
            u[l] = p[0];
            v[l] = p[1];
            bezinv::detail::bezout_at(plan, u[l], v[l], entries);
            for (std::size_t i = 0; i < nn; ++i) B[i * stride + l] = entries[i];
          }
          for (const kernels::Implementation* impl : kernels::available_implementations()) {
            if (n <= kernels::kNullVectorSeedMaxSize) {
              impl->null_vector_seed(n, kLanes, stride, B.data(), z.data(), defect.data(), residual.data(), 1.0);
            } else {
              std::vector<double> poison(kLanes);
              impl->bezout_null_vector_seed(n, kLanes, stride, plan.B0.data(), plan.Bx.data(), plan.By.data(),
                                            plan.common_denominator ? nullptr : plan.Bxy.data(), u.data(), v.data(),
                                            z.data(), defect.data(), residual.data(), poison.data(), 1.0);
            }
            for (std::size_t l = 0; l < kLanes; ++l) {
              std::vector<double> lane(n);
              for (int r = 0; r < n; ++r) lane[r] = z[r * stride + l];
              const double t0 = parameter_from_null_vector(lane);
              ++points;
              if (!std::isfinite(t0)) continue;
              const detail::Refined r = detail::refine_parameter(plan, u[l], v[l], std::clamp(t0, 0.0, 1.0), true);
              // The same point of the curve (a loop of a unit-square curve may pass through it twice).
              const auto q = plan.normalized_point(r.t);
              const bool same = std::abs(r.t - t_true[l]) <= 1e-9 ||
                                std::hypot(q[0] - u[l], q[1] - v[l]) <= 1e-12;
              landed += same;
              EXPECT_TRUE(same) << impl->name << " " << to_string(kind) << " degree " << n << " t_true "
                                << t_true[l] << " seed t " << t0 << " refined " << r.t;
            }
          }
        }
      }
  RecordProperty("points", static_cast<int>(points));
  RecordProperty("landed", static_cast<int>(landed));
  std::printf("[ measured ] seed refined to the known point on %zu of %zu Bezout matrices\n", landed, points);
}

}  // namespace
}  // namespace bezinv
