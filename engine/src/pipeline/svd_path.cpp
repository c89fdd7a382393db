#include "pipeline/svd_path.hpp"

#include <array>
#include <cmath>
#include <span>

#include "bezinv/kernels/batch.hpp"
#include "bezinv/kernels/symmetric_svd.hpp"
#include "pipeline/candidate.hpp"
#include "pipeline/decide.hpp"
#include "pipeline/limits.hpp"
#include "pipeline/point_polynomials.hpp"

namespace bezinv::detail {
namespace {

// Stage 2 for a whole batch. Lane l's B is entry (r, c) at B[(r n + c) stride + l]; sigma and V
// come back in the same lane-major layout (kernels/include/bezinv/kernels/batch.hpp). Up to
// kLaneBatchedSvdMaxDegree the lane-batched Jacobi kernel, above it Eigen's tridiagonal QR one
// matrix at a time (docs/kernels.md).
void batch_symmetric_svd(int n, std::size_t count, std::size_t stride, const double* B, double* sigma, double* V) {
  if (n <= kLaneBatchedSvdMaxDegree) {
    kernels::active_implementation().symmetric_svd(n, count, stride, B, sigma, V);
    return;
  }
  std::array<double, kMaxDegree * kMaxDegree> b, vectors;
  std::array<double, kMaxDegree> values;
  const int nn = n * n;
  for (std::size_t l = 0; l < count; ++l) {
    for (int i = 0; i < nn; ++i) b[i] = B[i * stride + l];
    kernels::symmetric_svd(n, std::span<const double>(b.data(), nn), values, vectors);
    for (int k = 0; k < n; ++k) sigma[k * stride + l] = values[k];
    for (int i = 0; i < nn; ++i) V[i * stride + l] = vectors[i];
  }
}

// Degree 1: B is 1 x 1 and has no null vector to read. p and q are linear; the least-squares
// root of both, t = -(p0 a + q0 b) / (a^2 + b^2) with a = p1 - p0, b = q1 - q0, is exact for a
// point on the line.
double linear_parameter(const PointPolynomials& pq) {
  const double a = pq.p[1] - pq.p[0], b = pq.q[1] - pq.q[0];
  return -(pq.p[0] * a + pq.q[0] * b) / (a * a + b * b);
}

}  // namespace

void svd_path(const PlanData& plan, const double* B, const double* u, const double* v,
              PointResult* const* target, std::size_t m, const InvertOptions& options, BatchWorkspace& w,
              StageClock& clock) {
  const int n = plan.degree, nn = n * n;
  const std::size_t stride = kBatchLanes;
  const double tolerance = normalized_tolerance(plan, options);
  // 2. kernel.
  if (n >= 2 && m > 0) batch_symmetric_svd(n, m, stride, B, w.sigma.data(), w.V.data());
  clock.lap(&StageSeconds::kernel);

  // 3. read-out: the right singular vector of the smallest singular value (degree 1: B is 1 x 1
  // with no null vector to read; p and q are linear, see linear_parameter).
  if (n >= 2 && m > 0)
    kernels::active_implementation().bernstein_parameter(n, m, stride, w.V.data() + (n - 1) * n * stride,
                                                         w.t_algebraic.data());
  for (std::size_t k = 0; k < m; ++k) {
    if (n == 1)
      w.t_algebraic[k] = linear_parameter(point_polynomials(plan, u[k], v[k]));
    else if (!(w.sigma[k] > 0 && std::isfinite(w.sigma[k])))
      w.t_algebraic[k] = PointResult::nan;
  }
  clock.lap(&StageSeconds::read_out);

  // 4. refine and measure the main candidate.
  for (std::size_t k = 0; k < m; ++k) {
    w.main[k] = Candidate{};
    if (n == 1 || (w.sigma[k] > 0 && std::isfinite(w.sigma[k])))
      w.main[k] = settle(plan, u[k], v[k], w.t_algebraic[k], Path::bezout, tolerance, options.refine);
  }
  clock.lap(&StageSeconds::refine);

  // 5. decide.
  std::array<double, kMaxDegree> sigma;
  std::array<double, kMaxDegree * kMaxDegree> V;
  for (std::size_t k = 0; k < m; ++k) {
    for (int i = 0; i < n && n >= 2; ++i) sigma[i] = w.sigma[i * stride + k];
    for (int i = 0; i < nn && n >= 2; ++i) V[i] = w.V[i * stride + k];
    if (n == 1) sigma[0] = 0.0;
    decide(plan, u[k], v[k], w.main[k], sigma.data(), V.data(), options, *target[k]);
  }
  clock.lap(&StageSeconds::decide);
}

}  // namespace bezinv::detail
