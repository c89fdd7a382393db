#include "pipeline/form_b.hpp"

#include <array>
#include <cmath>

#include "bezinv/kernels/batch.hpp"
#include "pipeline/decide.hpp"
#include "pipeline/far_point.hpp"

namespace bezinv::detail {

void normalize_batch(const PlanData& plan, const Point* points, std::size_t count, BatchWorkspace& w) {
  for (std::size_t l = 0; l < count; ++l) {
    const auto uv = plan.normalize(points[l].x, points[l].y);
    w.u[l] = uv[0];
    w.v[l] = uv[1];
  }
}

void admit_batch(const PlanData& plan, const Point* points, LaneRows rows, std::size_t count, BatchWorkspace& w) {
  for (std::size_t l = 0; l < count; ++l) {
    w.active[l] = admit(plan, points[l], w.u[l], w.v[l], rows[l]);
    if (!w.active[l]) w.u[l] = w.v[l] = 0.0;
  }
}

void form_batch(const PlanData& plan, const Point* points, LaneRows rows, std::size_t count, bool form,
                BatchWorkspace& w) {
  const int n = plan.degree, nn = n * n;
  const std::size_t stride = kBatchLanes;
  normalize_batch(plan, points, count, w);
  admit_batch(plan, points, rows, count, w);
  if (!form) return;
  // A kernel, so that it runs in the CPU's widest vectors (this file is compiled for baseline
  // x86-64). An entry that overflowed makes its lane's poison (sum of entry * 0) NaN.
  std::array<double, kBatchLanes> poison;
  kernels::active_implementation().bezout_matrix(n, count, stride, plan.B0.data(), plan.Bx.data(), plan.By.data(),
                                                 bilinear_coefficients(plan), w.u.data(), w.v.data(), w.B.data(),
                                                 poison.data());
  mark_overflowing_b(plan, points, poison.data(), count, w, rows);
  for (std::size_t l = 0; l < count; ++l) {
    if (!w.active[l])
      for (int i = 0; i < nn; ++i) w.B[i * stride + l] = (i % (n + 1) == 0) ? 1.0 : 0.0;
  }
}

void mark_overflowing_b(const PlanData& plan, const Point* points, const double* poison, std::size_t count,
                        BatchWorkspace& w, LaneRows rows) {
  for (std::size_t l = 0; l < count; ++l)
    if (w.active[l] && !(poison[l] == 0.0)) {
      answer_far_point(plan, points[l], rows[l]);
      w.active[l] = 0;
    }
}

void form_compacted_b(const PlanData& plan, const double* u, const double* v, std::size_t m, double* B) {
  std::array<double, kBatchLanes> poison;
  kernels::active_implementation().bezout_matrix(plan.degree, m, kBatchLanes, plan.B0.data(), plan.Bx.data(),
                                                 plan.By.data(), bilinear_coefficients(plan), u, v, B, poison.data());
}

}  // namespace bezinv::detail
