#include "bezinv/invert.hpp"

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>
#include <tbb/enumerable_thread_specific.h>
#include <tbb/task_arena.h>

#include <Eigen/QR>
#include <Eigen/SVD>
#include <algorithm>
#include <array>
#include <chrono>
#include <cstdint>
#include <map>
#include <memory>
#include <mutex>
#include <optional>
#include <vector>
#include <cmath>

#include "bezinv/bernstein.hpp"
#include "bezinv/kernels/batch.hpp"
#include "bezinv/kernels/symmetric_svd.hpp"
#include "bezinv/null_vector.hpp"
#include "bezinv/sylvester.hpp"
#include "degree_drop.hpp"
#include "isolation.hpp"
#include "refine.hpp"

namespace bezinv {

const char* to_string(Status status) {
  switch (status) {
    case Status::ok: return "ok";
    case Status::outside_segment: return "outside_segment";
    case Status::double_point: return "double_point";
    case Status::off_curve: return "off_curve";
    case Status::invalid_input: return "invalid_input";
    case Status::failed: return "failed";
  }
  return "?";
}

const char* to_string(Path path) {
  switch (path) {
    case Path::none: return "none";
    case Path::bezout: return "bezout";
    case Path::bezout_pair: return "bezout_pair";
    case Path::sylvester: return "sylvester";
    case Path::nearest: return "nearest";
    case Path::bezout_lu: return "bezout_lu";
  }
  return "?";
}

namespace {

using Coefficients = std::array<double, kMaxDegree + 1>;

// The tolerance on |P(t) - P0| in normalized units: relative to the curve's size, never below the
// resolution of its coordinates.
double normalized_tolerance(const InversionPlan& plan, const InvertOptions& options) {
  return std::max(options.relative_tolerance * plan.normalized_diagonal, plan.normalized_resolution);
}

// Points per batch (see "The pipeline" below).
constexpr std::size_t kBatchLanes = 64;
// From this degree the fast path's seed forms B in registers instead of reading the batch's
// (invert_batch_lanes). Measured, BM_KernelBezoutSeed_formed against _stored (points/s, 3 runs):
// AVX-512 0.8x at n = 5, 1.13x at 8, 1.3x at 10-12, 1.25-1.35x at 15-24; AVX2 0.9x at 8, 1.0x at
// 10, 1.1x at 12, 1.15-1.6x at 15-24. Below, B fits in L1 and forming it twice (factorization and
// residual) costs more than reading it. Since the affine form (one denominator) made forming
// cheaper, the kernels alone favour forming from n = 6 on AVX-512 (1.2x at 6 and 7; AVX2 even),
// but the pipeline did not follow: bezinv profile, 1 thread, 3 alternating runs with the switch
// at 6, 0.91x at n = 6 and 0.93-1.0x at 7 for one denominator, 1.0x for separate ones.
constexpr int kFormedBMinDegree = 8;

// p = X_num - u0 X_den and q = Y_num - v0 Y_den at the plan's degree.
struct PointPolynomials {
  int n;
  Coefficients p, q;
  std::span<const double> p_span() const { return {p.data(), static_cast<std::size_t>(n + 1)}; }
  std::span<const double> q_span() const { return {q.data(), static_cast<std::size_t>(n + 1)}; }
};

PointPolynomials point_polynomials(const InversionPlan& plan, double u0, double v0) {
  PointPolynomials pq;
  pq.n = plan.degree;
  for (int i = 0; i <= pq.n; ++i) {
    pq.p[i] = plan.x_num[i] - u0 * plan.x_den[i];
    pq.q[i] = plan.y_num[i] - v0 * plan.y_den[i];
  }
  return pq;
}

// p written at its true degree, in place: reduce while the leading power coefficient vanishes.
// Returns the degree.
int reduce_to_true_degree(Coefficients& p, int n) {
  Coefficients r;
  while (n >= 1) {
    const std::span<const double> current(p.data(), n + 1);
    if (std::abs(power_leading_coefficient(current)) > kDegreeDropRatio * power_leading_bound(current)) break;
    reduce_degree(current, std::span<double>(r.data(), n));
    --n;
    std::copy_n(r.begin(), n + 1, p.begin());
  }
  return n;
}

// The Sylvester path (paper Sect. 4, taken only at degree drops): the left null vector of S(p, q)
// at the true degrees is the Bernstein basis of degree m+k-1 at the common root. Fixed-size
// storage (m + k < 2 kMaxDegree), so no allocation here either.
double sylvester_parameter(const PointPolynomials& pq) {
  Coefficients p = pq.p, q = pq.q;
  const int m = reduce_to_true_degree(p, pq.n), k = reduce_to_true_degree(q, pq.n);
  if (m < 1 || k < 1) return std::nan("");
  constexpr int kMaxSize = 2 * kMaxDegree;
  using Matrix = Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor, kMaxSize, kMaxSize>;
  const int size = m + k;
  Matrix S(size, size);
  sylvester_matrix(std::span<const double>(p.data(), m + 1), std::span<const double>(q.data(), k + 1),
                   std::span<double>(S.data(), static_cast<std::size_t>(size) * size));
  Eigen::JacobiSVD<Matrix> svd(S, Eigen::ComputeFullU);
  const Eigen::Matrix<double, Eigen::Dynamic, 1, 0, kMaxSize, 1> z = svd.matrixU().col(size - 1);  // v^T S = 0
  return parameter_from_null_vector(std::span<const double>(z.data(), size));
}

// Degree 1: B is 1 x 1 and has no null vector to read. p and q are linear; the least-squares
// root of both, t = -(p0 a + q0 b) / (a^2 + b^2) with a = p1 - p0, b = q1 - q0, is exact for a
// point on the line.
double linear_parameter(const PointPolynomials& pq) {
  const double a = pq.p[1] - pq.p[0], b = pq.q[1] - pq.q[0];
  return -(pq.p[0] * a + pq.q[0] * b) / (a * a + b * b);
}

struct Candidate {
  double t = PointResult::nan;
  double distance = PointResult::nan;  // normalized units
  Path path = Path::none;
  bool on_segment = false;  // t in [0,1] and within tolerance
  bool on_curve = false;    // within tolerance (segment or extension)
};

void classify(Candidate& c, double tolerance) {
  c.on_curve = c.distance <= tolerance;
  c.on_segment = c.on_curve && c.t >= 0.0 && c.t <= 1.0;
}

// From an algebraic parameter to a verified one: refine (or not), then measure.
Candidate settle(const InversionPlan& plan, double u0, double v0, double t_algebraic, Path path,
                 double tolerance, bool refine) {
  Candidate c;
  c.path = path;
  if (!std::isfinite(t_algebraic)) return c;
  const bool inside = t_algebraic >= 0.0 && t_algebraic <= 1.0;
  auto measure = [&](double t) { return detail::distance(plan, u0, v0, t); };
  if (!refine) {
    // The paper's algebraic t. A point within tolerance of an end of the segment whose algebraic t
    // fell just outside [0,1] is on the segment: its t is clamped onto it.
    const double clamped = std::clamp(t_algebraic, 0.0, 1.0);
    c.t = t_algebraic;
    c.distance = measure(t_algebraic);
    if (!inside && measure(clamped) <= tolerance) { c.t = clamped; c.distance = measure(clamped); }
  } else {
    const detail::Refined main = detail::refine_parameter(plan, u0, v0, t_algebraic, /*stay_on_segment=*/inside);
    c.t = main.t;
    c.distance = main.distance;
    const bool at_end = c.t == 0.0 || c.t == 1.0;
    if (inside && at_end && !(c.distance <= tolerance)) {
      // Clamped at an end but not there: the point may be on the extension just past it.
      const detail::Refined beyond = detail::refine_parameter(plan, u0, v0, t_algebraic, false);
      if (beyond.distance < c.distance) { c.t = beyond.t; c.distance = beyond.distance; }
    } else if (!inside) {
      // Started on the extension: the nearest point of the segment wins if it is within tolerance.
      const detail::Refined on_segment =
          detail::refine_parameter(plan, u0, v0, std::clamp(t_algebraic, 0.0, 1.0), true);
      if (on_segment.distance <= tolerance) { c.t = on_segment.t; c.distance = on_segment.distance; }
    }
  }
  classify(c, tolerance);
  return c;
}

// ---------------------------------------------------------------------------------------------
// The pipeline. Points of one curve go through it in batches of kBatchLanes, stage by stage, so
// each stage is one loop over the batch (vectorizable, and timed separately for `bezinv profile`):
//   1. form B    normalize the points; B = B0 - u0 Bx - v0 By (+ u0 v0 Bxy for separate
//                denominators) for every lane (SoA)
//                (on the fast path from kFormedBMinDegree, formed by the seed kernel instead)
//   2. kernel    singular values and vectors of every lane's B
//   3. read-out  the algebraic t from the last singular vector (paper Sect. 3)
//   4. refine    Newton from it to the nearest point, and its distance (the residual)
//   5. decide    status; the rare paths (second null direction, Sylvester, nearest-point search)
//                run only for the lanes that need them
// invert_point is a batch of one, so there is one code path.

// A root of the second-parameter check this close to the lane's t is "near" (see queue_second_parameters).
constexpr double kNearRoot = 1e-3;
// A root this close to the lane's refined t is the root of z itself (z ~ b(t) lies in the span):
// refining it lands on t again, so it cannot be a parameter distinct from t by more than
// kDistinctParameterGap (100x farther). Measured on on-curve points (degrees 8 and 15): one root of
// every lane that looks lies within 1e-13 of t, so this halves the Newton runs of the check (those
// are the cheap ones: the refine stage gained 5-10% at degrees 8-20, 1 thread).
// Points off the curve by noise have that root within the noise of t, and keep refining it.
constexpr double kSameRoot = 1e-2 * kDistinctParameterGap;


// Per-thread storage for one batch, sized for the largest degree once: nothing is allocated per
// point or per batch.
struct BatchWorkspace {
  std::array<double, kBatchLanes> u, v;
  std::array<std::uint8_t, kBatchLanes> active;  // lane still undecided after stage 1
  std::vector<double> B = std::vector<double>(static_cast<std::size_t>(kMaxDegree) * kMaxDegree * kBatchLanes);
  std::vector<double> sigma = std::vector<double>(static_cast<std::size_t>(kMaxDegree) * kBatchLanes);
  std::vector<double> V = std::vector<double>(static_cast<std::size_t>(kMaxDegree) * kMaxDegree * kBatchLanes);
  std::array<double, kBatchLanes> t_algebraic;
  // The fast path's lane-batched refinement: t and |P(t) - P0| (NaN where it left the lane to settle()).
  std::array<double, kBatchLanes> t_refined, distance;
  std::array<std::uint8_t, kBatchLanes> drops;
  std::array<std::uint8_t, kBatchLanes> certified;  // pass 1: settled by the isolation certificate's first test
  std::array<Candidate, kBatchLanes> main;
  // Fast path (LU null vector): z, defect and the two sigma estimates, lane-major like sigma.
  std::vector<double> z = std::vector<double>(static_cast<std::size_t>(kMaxDegree) * kBatchLanes);
  std::vector<double> second = std::vector<double>(static_cast<std::size_t>(kMaxDegree) * kBatchLanes);
  std::array<double, kBatchLanes> defect;
  std::array<double, 2 * kBatchLanes> estimate;
  // The gap pass (see invert_batch_lanes): its lanes compacted, gap lane k being batch lane
  // gap_lane_of[k], and the full kernel's outputs for them before they go back to their lanes.
  std::vector<double> gap_B = std::vector<double>(static_cast<std::size_t>(kMaxDegree) * kMaxDegree * kBatchLanes);
  std::vector<double> gap_z = std::vector<double>(static_cast<std::size_t>(kMaxDegree) * kBatchLanes);
  std::vector<double> gap_second = std::vector<double>(static_cast<std::size_t>(kMaxDegree) * kBatchLanes);
  std::array<double, kBatchLanes> gap_defect;
  std::array<double, 2 * kBatchLanes> gap_estimate;
  std::array<std::uint8_t, kBatchLanes> gap_lane_of;
  // The lanes left for the SVD path, compacted to the front: compact lane k is batch lane lane_of[k].
  std::array<std::uint8_t, kBatchLanes> lane_of;
};

BatchWorkspace& batch_workspace() {
  thread_local BatchWorkspace workspace;
  return workspace;
}

// The lanes a batch leaves for the SVD path (stages 2-5 below), when they are too few to fill a
// SIMD group of the Jacobi kernel: they wait here, per thread, for the next batches' until there
// are kSvdGroupLanes, and whatever is left is run at the end of each range of batches (so the
// queue never outlives the plan it was filled for). With the fast path on, 0.1-0.3% of on-curve
// points take the SVD path (degrees 8-16), less than one per batch of kBatchLanes: run at once,
// each cost a whole group of 8 lanes, 13% of the pipeline at degree 15 (perf). A lane's answer
// does not depend on the others of its group (the Jacobi kernel freezes converged lanes, the
// rest of the path is per lane), so neither the batch nor the thread count changes it.
constexpr std::size_t kSvdGroupLanes = 8;

struct SvdQueue {
  std::vector<double> B = std::vector<double>(static_cast<std::size_t>(kMaxDegree) * kMaxDegree * kBatchLanes);
  std::array<double, kBatchLanes> u, v;
  std::array<PointResult*, kBatchLanes> target;  // where lane k's answer goes
  std::size_t size = 0;

  // Appends lane `lane` of the n x n matrices `from` (lane-major, stride kBatchLanes); size < kBatchLanes.
  void push(int nn, const double* from, std::size_t lane, double lane_u, double lane_v, PointResult* answer) {
    for (int i = 0; i < nn; ++i) B[i * kBatchLanes + size] = from[i * kBatchLanes + lane];
    u[size] = lane_u;
    v[size] = lane_v;
    target[size++] = answer;
  }
};

SvdQueue& svd_queue() {
  thread_local SvdQueue queue;
  return queue;
}

// The fast path's lanes that must look for a second parameter (see queue_second_parameters) and
// are not certified isolated wait here, per thread, with their roots, until the roots fill a SIMD
// group of the Newton kernel: at degree 3 0.8% of the lanes look (one root each), at degree 5 7%,
// at degree 8 19% (measured), so a batch of kBatchLanes has 0.5, 4 and 12 roots, and checked batch
// by batch most of a group's lanes idled (the kernel's 8-lane groups for those roots were 9-11% of
// the pipeline at degree 3, perf; with the queue the pipeline is 4-7% faster at degrees 3-6 and 3%
// at 8, `bezinv profile`, 1 thread, alternating; measured before the isolation certificate, which
// now answers most of those lanes without their roots). A lane is answered when the queue is
// flushed: ok on the fast path if none of its roots refines onto the segment at a distinct
// parameter, else by the SVD path. Flushed once kPairCheckFlushRoots roots wait, before a batch
// that might not fit, and at the end of each range of batches, so it never outlives the plan it
// was filled for. A lane's answer does not depend on the others of its group, so neither does it
// on the queue.
constexpr std::size_t kPairCheckFlushRoots = 16;
// Room for a whole batch besides the fewer than kPairCheckFlushRoots lanes left waiting.
constexpr std::size_t kPairCheckLanes = 2 * kBatchLanes;

struct PairCheckQueue {
  // Lane k: its point, its answer if no second parameter is found (t, distance, the two sigma
  // estimates), and where the answer goes.
  std::array<double, kPairCheckLanes> u, v, t, distance, sigma_min, sigma_next;
  std::array<PointResult*, kPairCheckLanes> target;
  std::array<std::uint8_t, kPairCheckLanes> second_found;
  std::size_t lanes = 0;
  // The roots (two per lane at most): those near their lane's t from the front, the others from
  // the back, so that the kernel's SIMD groups hold roots of similar work.
  std::array<double, 2 * kPairCheckLanes> root_t, root_u, root_v, root_distance;
  std::array<std::uint8_t, 2 * kPairCheckLanes> root_lane;
  std::size_t near = 0, far = 0;
};

PairCheckQueue& pair_check_queue() {
  thread_local PairCheckQueue queue;
  return queue;
}

// Empties this thread's queues when it goes out of scope: after the last flush they are empty
// anyway; if an exception (bad_alloc) cut the work short, the waiting lanes point into the
// caller's results and must not be run by a later call.
struct QueueScope {
  QueueScope() = default;
  QueueScope(const QueueScope&) = delete;
  QueueScope& operator=(const QueueScope&) = delete;
  ~QueueScope() {
    svd_queue().size = 0;
    PairCheckQueue& pairs = pair_check_queue();
    pairs.lanes = pairs.near = pairs.far = 0;
  }
};

// Stage 2 for a whole batch. Lane l's B is entry (r, c) at B[(r n + c) stride + l]; sigma and V
// come back in the same lane-major layout (kernels/include/bezinv/kernels/batch.hpp).
//
// Up to kLaneBatchedMaxDegree the lane-batched Jacobi kernel (one matrix per SIMD lane) is used;
// above it Eigen's tridiagonal QR, one matrix at a time, is faster: Jacobi costs ~n^3 per sweep
// for 6-9 sweeps (measured with bench/kernels_bench.cpp on AVX-512: batched Jacobi 101k vs Eigen
// 66k matrices/s at n = 15, 46k vs 37k at n = 20, 21k vs 31k at n = 24; AVX2 falls behind at 20).
constexpr int kLaneBatchedMaxDegree = 16;
// The kernel is compiled for exactly these sizes (one instantiation per size and instruction set).
static_assert(kLaneBatchedMaxDegree == kernels::kSymmetricSvdMaxSize,
              "kernels::kSymmetricSvdMaxSize must be the largest n the engine gives the lane-batched SVD");
// The other kernels get every degree (the SVD path's read-out and B) or every fast-path degree.
static_assert(kMaxDegree == kernels::kMaxBatchSize && kFastPathMaxDegree <= kernels::kMaxBatchSize,
              "kernels::kMaxBatchSize must be the largest degree the engine gives the kernels");

void batch_symmetric_svd(int n, std::size_t count, std::size_t stride, const double* B, double* sigma, double* V) {
  if (n <= kLaneBatchedMaxDegree) {
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

class StageClock {
 public:
  explicit StageClock(StageSeconds* stages) : stages_(stages) {
    if (stages_) last_ = std::chrono::steady_clock::now();
  }
  void lap(double StageSeconds::*stage) {
    if (!stages_) return;
    const auto now = std::chrono::steady_clock::now();
    stages_->*stage += std::chrono::duration<double>(now - last_).count();
    last_ = now;
  }

 private:
  StageSeconds* stages_;
  std::chrono::steady_clock::time_point last_;
};

// How many singular values, from the smallest, are at most kSecondNullDirectionRatio sigma_1
// (sigma in decreasing order, n of them).
int numerical_nullity(const double* sigma, int n) {
  int k = 0;
  while (k < n && sigma[n - 1 - k] <= kSecondNullDirectionRatio * sigma[0]) ++k;
  return k;
}

// max_ij |B0| + |u0 Bx| + |v0 By| + |u0 v0 Bxy|: the size of B's terms before they cancel.
double bezout_term_size(const InversionPlan& plan, double u0, double v0) {
  double size = 0.0;
  const int nn = plan.degree * plan.degree;
  for (int i = 0; i < nn; ++i)
    size = std::max(size, std::abs(plan.B0[i]) + std::abs(u0 * plan.Bx[i]) + std::abs(v0 * plan.By[i]) +
                              (plan.common_denominator ? 0.0 : std::abs(u0 * v0 * plan.Bxy[i])));
  return size;
}

// Whether B(u0, v0), whose largest singular value is sigma_1, vanishes (kVanishingBezoutRatio):
// decided first against a bound of the terms' size from the plan's largest entries, which settles
// every point of a curve that is not a line without a pass over B.
bool bezout_vanishes(const InversionPlan& plan, double u0, double v0, double sigma_1) {
  const auto& m = plan.bezout_max_entries;
  const double bound = m[0] + std::abs(u0) * m[1] + std::abs(v0) * m[2] + std::abs(u0 * v0) * m[3];
  if (sigma_1 > kVanishingBezoutRatio * bound) return false;
  return !(sigma_1 > kVanishingBezoutRatio * bezout_term_size(plan, u0, v0));
}

// The real roots of a Bernstein polynomial r of degree n >= 1 (into t, room for n): the t with
// beta(t) orthogonal to r's coefficients, i.e. in the n-dimensional space r^perp, found as from
// any null space (parameters_from_null_space).
int bernstein_roots(std::span<const double> r, std::span<double> t) {
  const int size = static_cast<int>(r.size());
  if (size == 2) {  // linear: r0 (1 - t) + r1 t
    if (r[0] == r[1]) return 0;
    t[0] = r[0] / (r[0] - r[1]);
    return 1;
  }
  Eigen::Map<const Eigen::VectorXd> coefficients(r.data(), size);
  if (!(coefficients.norm() > 0.0)) return 0;
  const Eigen::MatrixXd column = coefficients;
  const Eigen::HouseholderQR<Eigen::MatrixXd> qr(column);
  const Eigen::MatrixXd q = qr.householderQ();  // column 0 along r, the others span r^perp
  return parameters_from_null_space(std::span<const double>(q.data() + size, static_cast<std::size_t>(size) * (size - 1)),
                                    size - 1, t);
}

// Whether P0 is reached at t1 and t2 by separate branches of the curve: somewhere between them
// the curve leaves the tolerance of P0 (sampled at kBranchSamples interior parameters; a branch
// that passes slowly, or a cusp within the tolerance, stays inside).
bool separate_branches(const InversionPlan& plan, double u0, double v0, double t1, double t2, double tolerance) {
  for (int k = 1; k <= kBranchSamples; ++k) {
    const double t = t1 + (t2 - t1) * k / (kBranchSamples + 1);
    if (!(detail::distance(plan, u0, v0, t) <= tolerance)) return true;
  }
  return false;
}

// Stage 5 for one lane: everything after the main candidate. sigma (n values) and V (vector k at
// V[k n + r]) are this lane's, gathered.
void decide(const InversionPlan& plan, double u0, double v0, const Candidate& main, const double* sigma,
            const double* V, const InvertOptions& options, PointResult& r) {
  const int n = plan.degree;
  const double tolerance = normalized_tolerance(plan, options);
  std::array<Candidate, kMaxDegree + 4> candidates;
  int count = 0;
  if (std::isfinite(main.t) || main.path != Path::none) candidates[count++] = main;
  auto add = [&](double t, Path path) {
    if (count < static_cast<int>(candidates.size()))
      candidates[count++] = settle(plan, u0, v0, t, path, tolerance, options.refine);
  };

  const bool have_svd = n >= 2 && sigma[0] > 0 && std::isfinite(sigma[0]);
  if (have_svd) {
    r.sigma_min = sigma[n - 1] / sigma[0];
    r.sigma_next = sigma[n - 2] / sigma[0];
  }
  const bool look_for_second = have_svd && n >= 3 && r.sigma_next <= kSecondNullDirectionRatio;
  const PointPolynomials pq = point_polynomials(plan, u0, v0);
  const bool drop = n >= 2 && detail::degree_drops(plan, u0, v0);
  // B vanishes (a straight line through the point): its singular values are rounding, and say
  // nothing of how many parameters there are.
  const bool vanishes = n >= 2 && bezout_vanishes(plan, u0, v0, sigma[0]);
  const bool settled = count > 0 && candidates[0].on_segment && !look_for_second && !drop && !vanishes;
  if (!settled) {
    if (drop) add(sylvester_parameter(pq), Path::sylvester);
    if (vanishes) {
      // B vanishes: p and q are proportional, the curve is a straight line through the point
      // (traced at degree n), and each real root of p (or q) is a parameter.
      std::array<double, kMaxDegree> t;
      const double p_size = power_leading_bound(pq.p_span()), q_size = power_leading_bound(pq.q_span());
      const int roots = bernstein_roots(p_size >= q_size ? pq.p_span() : pq.q_span(), t);
      for (int i = 0; i < roots; ++i) add(t[i], Path::bezout_pair);
    } else if (have_svd && n >= 3) {
      // Nullity 2 (self-intersection, or a root driven towards infinity): both parameters from
      // the span of the two last singular vectors. Nullity k > 2 (several parameters over C, or
      // an ill-conditioned B): every real one from the span of the k last.
      const int k = std::min(numerical_nullity(sigma, n), std::min(kMaxNullSpaceDimension, n - 1));
      std::array<double, kMaxDegree> t;
      const int roots =
          k <= 2 ? parameters_from_null_space(std::span<const double>(V + (n - 1) * n, n),
                                              std::span<const double>(V + (n - 2) * n, n), t.data())
                 : parameters_from_null_space(std::span<const double>(V + (n - k) * n, static_cast<std::size_t>(k) * n),
                                              k, t);
      for (int i = 0; i < roots; ++i) add(t[i], Path::bezout_pair);
    }
  }

  // On the segment at two distinct parameters of separate branches: a double point. Two
  // parameters of one branch (the curve between them stays within the tolerance: it passes
  // slowly, or turns at a cusp near the point) are one answer, the nearer.
  const Candidate* first = nullptr;
  const Candidate* second = nullptr;
  for (int i = 0; i < count; ++i) {
    const Candidate& c = candidates[i];
    if (!c.on_segment) continue;
    if (!first) { first = &c; continue; }
    if (std::abs(c.t - first->t) <= kDistinctParameterGap) continue;
    if (!separate_branches(plan, u0, v0, first->t, c.t, tolerance)) {
      if (c.distance < first->distance) first = &c;
      continue;
    }
    if (!second || c.distance < second->distance) second = &c;
  }
  if (second && !separate_branches(plan, u0, v0, first->t, second->t, tolerance)) second = nullptr;
  auto report = [&](const Candidate& c, Status status) {
    r.t = c.t;
    r.residual = c.distance * plan.scale;
    r.path = c.path;
    r.status = status;
  };
  if (first && second) {
    const Candidate& lo = first->t < second->t ? *first : *second;
    const Candidate& hi = first->t < second->t ? *second : *first;
    report(lo, Status::double_point);
    r.t2 = hi.t;
    r.path = Path::bezout_pair;
    return;
  }
  if (first) return report(*first, Status::ok);
  for (int i = 0; i < count; ++i)
    if (candidates[i].on_curve) {
      // The extension passes within the tolerance; the segment may too, at a parameter no
      // candidate led to (a huge end weight holds the segment near P(0) over a range of t that
      // B's null vector does not single out). On the segment wins.
      if (options.refine) {
        Candidate nearest;
        nearest.t = detail::nearest_parameter_on_segment(plan, u0, v0, std::clamp(candidates[i].t, 0.0, 1.0));
        nearest.distance = detail::distance(plan, u0, v0, nearest.t);
        nearest.path = Path::nearest;
        if (nearest.distance <= tolerance) return report(nearest, Status::ok);
      }
      return report(candidates[i], Status::outside_segment);
    }

  // Off the curve (or every algebraic candidate failed): the nearest point of the segment.
  if (!options.refine && count > 0 && std::isfinite(candidates[0].t))
    return report(candidates[0], Status::off_curve);  // --no-refine keeps the algebraic t
  double hint = -1.0;
  for (int i = 0; i < count; ++i)
    if (std::isfinite(candidates[i].t)) { hint = std::clamp(candidates[i].t, 0.0, 1.0); break; }
  Candidate nearest;
  nearest.t = detail::nearest_parameter_on_segment(plan, u0, v0, hint);
  nearest.distance = detail::distance(plan, u0, v0, nearest.t);
  nearest.path = Path::nearest;
  if (!std::isfinite(nearest.distance)) {
    r.status = Status::failed;
    r.reason = "no finite parameter found";
    return;
  }
  // The algebra can miss a point that is on the segment (e.g. a coordinate constant along a
  // curve with separate denominators makes p vanish identically); the distance decides.
  report(nearest, nearest.distance <= tolerance ? Status::ok : Status::off_curve);
}

// The fast path's look for a second parameter (as decide() does with the SVD's two last singular
// vectors): the parameters whose Bernstein vector lies in span{z, second} (batch lane l's kernel
// vectors) are queued in this thread's PairCheckQueue with the lane, for refinement along the
// segment. Returns false, queueing nothing, when the lane has no root to check (only z's own).
// Only a parameter on the segment matters here, so every root is refined along the segment (from
// the nearer end if it lies outside), which is the part of settle() that can end on the segment.
// settle()'s walk along the extension from a root far outside took most of the time of this check
// (with it the check cost 57% of the pipeline at degree 8, measured); the SVD path still does
// both, and tests/engine/invert_property_test.cpp checks that the two paths give the same statuses.
// The parameters whose Bernstein vector lies in span{z, second} of batch lane l (at most two; how
// many, as parameters_from_null_space).
int null_space_roots(int n, const BatchWorkspace& w, std::size_t l, double roots[2]) {
  std::array<double, kMaxDegree> z, second;
  for (int r = 0; r < n; ++r) {
    z[r] = w.z[r * kBatchLanes + l];
    second[r] = w.second[r * kBatchLanes + l];
  }
  return parameters_from_null_space(std::span<const double>(z.data(), n), std::span<const double>(second.data(), n),
                                    roots);
}

bool queue_second_parameters(int n, const BatchWorkspace& w, std::size_t l, const Candidate& c, PointResult* target) {
  double roots[2];
  const int count = null_space_roots(n, w, l, roots);
  PairCheckQueue& q = pair_check_queue();
  const std::size_t lane = q.lanes;
  bool queued = false;
  for (int i = 0; i < count; ++i) {
    const double start = std::clamp(roots[i], 0.0, 1.0);  // NaN stays NaN: not settled, refined to NaN
    const double from_t = std::abs(start - c.t);
    if (from_t <= kSameRoot) continue;  // z's own root (see kSameRoot)
    const std::size_t k = from_t <= kNearRoot ? q.near++ : q.root_t.size() - 1 - q.far++;
    q.root_t[k] = start;
    q.root_u[k] = w.u[l];
    q.root_v[k] = w.v[l];
    q.root_lane[k] = static_cast<std::uint8_t>(lane);
    queued = true;
  }
  if (!queued) return false;
  q.u[lane] = w.u[l];
  q.v[lane] = w.v[l];
  q.t[lane] = c.t;
  q.distance[lane] = c.distance;
  q.sigma_min[lane] = w.estimate[l];
  q.sigma_next[lane] = w.estimate[kBatchLanes + l];
  q.target[lane] = target;
  ++q.lanes;
  return true;
}

// The fast path's answer: ok (or off_curve, see off_curve_certified), path bezout_lu, the sigma
// columns from the kernel's estimates.
void answer_fast(const InversionPlan& plan, double t, double distance, double sigma_min, double sigma_next,
                 PointResult& r, Status status = Status::ok) {
  r.t = t;
  r.residual = distance * plan.scale;
  r.status = status;
  r.path = Path::bezout_lu;
  r.sigma_min = sigma_min;
  r.sigma_next = sigma_next;
}

// Whether the fast path may answer lane l off_curve at its refined parameter, as the SVD path
// would after its search for the nearest point of the segment. The lane's refinement ended inside
// (0, 1) farther than the tolerance from P0, at a stationary point of the distance (checked: the
// refinement may also stop on its iteration cap), and:
//   - the SVD path would have no other candidate on the curve: no degree drop (the caller); and
//     where it would look for a second parameter (the sigma_{n-1} estimate below
//     kFastPathGapRatio, as for the on-curve lanes) none of the roots can end within the
//     tolerance (extension_roots_clear), so it would go on to the nearest-point search;
//   - that search can only find t (detail::nearest_on_segment): the isolation certificate with the
//     lane's own distance for the tolerance says that no point of the segment outside t's
//     neighbourhood is as near as P(t), and that inside it the distance has t for its only
//     stationary point, falling towards it on both sides (engine/src/isolation.hpp), so no end
//     of the segment there is nearer either.
// Both paths then give the same t up to the last bits of the refinement, and the same status.
// Stationary: cos(P(t) - P0, P'(t)) <= kStationaryCosine. The stationary point tau* the search
// would find is then within 2 cos d |P'| / v^2 of t (f' = 2 cos d |P'| at t, and f'' >= v^2 on
// the neighbourhood below isolation_unique), ~1e-13 for d = 1e-5 of the curve's size; Newton's
// last step leaves cos at the rounding of P(t) - P0, ~1e-16 / d.
constexpr double kStationaryCosine = 1e-8;
// A root of span{z, second} this close to an end of the segment may fall on the other side of it
// for the SVD's slightly different vectors, and be walked along the extension there.
constexpr double kRootNearEnd = 1e-6;

// For an off-curve lane certified as above, the second-parameter candidates the SVD path would
// settle: the roots of span{z, second} (as queue_second_parameters; the SVD path's come from its
// two last singular vectors). A root inside the segment is walked along it, and the certificate
// says no such walk ends within the lane's own distance, more than the tolerance, of P0. A root
// outside is walked along the extension, which no box covers: walked here too, as settle() does.
// Refused (the SVD path decides) when there are not two real roots (a complex pair or a root at
// infinity: the SVD's may be real), or a root is near an end. Refusing every lane with a root
// outside the segment instead (most have one) lost most of the gain: bezinv profile at noise
// 1e-5, degrees 8 / 15 / 20, 881k / 267k / 128k points/s with the walks, 428k / 156k / 53k
// without. No test point has yet needed them: with the walks skipped, 475,200 rows of
// InvertProperty.OffTheCurveTheFastPathAnswersOnlyWhereItsBranchIsTheNearest (20 times its
// curves, tolerances 1e-6 to 0.2) still agreed with the SVD path. They stay because the
// certificate says nothing about the extension, and the SVD path walks it.
bool extension_roots_clear(const InversionPlan& plan, const BatchWorkspace& w, std::size_t l, double tolerance) {
  double roots[2];
  if (null_space_roots(plan.degree, w, l, roots) != 2) return false;
  for (double root : roots) {
    if (std::abs(root) <= kRootNearEnd || std::abs(root - 1.0) <= kRootNearEnd) return false;
    if (root > 0.0 && root < 1.0) continue;
    if (settle(plan, w.u[l], w.v[l], root, Path::bezout_pair, tolerance, true).on_curve) return false;
  }
  return true;
}

// The two halves of the conditions above: what the curve's geometry says (off_curve_nearest), and
// what needs the kernel's gap (off_curve_alone, which also reads the second vector).
bool off_curve_nearest(const InversionPlan& plan, const BatchWorkspace& w, std::size_t l, const Candidate& c) {
  if (c.on_curve || !(c.t > 0.0 && c.t < 1.0) || !std::isfinite(c.distance)) return false;
  if (!detail::nearest_on_segment(plan, w.u[l], w.v[l], c.t, c.distance)) return false;
  const detail::CurveJet jet = detail::curve_jet(plan, c.t);
  const double along = (jet.x - w.u[l]) * jet.dx + (jet.y - w.v[l]) * jet.dy;
  return std::abs(along) <= kStationaryCosine * c.distance * std::hypot(jet.dx, jet.dy);
}

bool off_curve_alone(const InversionPlan& plan, const BatchWorkspace& w, std::size_t l, double tolerance) {
  return plan.degree < 3 || w.estimate[kBatchLanes + l] >= kFastPathGapRatio ||
         extension_roots_clear(plan, w, l, tolerance);
}

// The fast path's decision for lane l, refined to c, with the kernel's gap: answered here (ok, or
// off_curve where off_curve_nearest and off_curve_alone hold), after the second-parameter check,
// or left to the SVD path (still active). `asked`: the curve's geometry was asked already (the gap
// pass): on the segment the isolation certificate refused the lane, off it off_curve_nearest held.
void decide_with_gap(const InversionPlan& plan, BatchWorkspace& w, std::size_t l, const Candidate& c,
                     double tolerance, bool asked, PointResult& result) {
  const int n = plan.degree;
  const std::size_t stride = kBatchLanes;
  if (!c.on_segment) {
    if ((asked || off_curve_nearest(plan, w, l, c)) && off_curve_alone(plan, w, l, tolerance)) {
      w.active[l] = 0;
      answer_fast(plan, c.t, c.distance, w.estimate[l], w.estimate[stride + l], result, Status::off_curve);
    }
    return;
  }
  // Answered now, or after the second-parameter check (flush_pair_check_queue): either way the
  // lane leaves the batch.
  w.active[l] = 0;
  if ((w.estimate[stride + l] >= kFastPathGapRatio || n < 3) ||
      (!asked && detail::isolated(plan, w.u[l], w.v[l], c.t, c.distance, tolerance)) ||
      !queue_second_parameters(n, w, l, c, &result))
    answer_fast(plan, c.t, c.distance, w.estimate[l], w.estimate[stride + l], result);
}

// Stages 2-5 for the m lanes the fast path left (all lanes without it), compacted: lane k's B is
// entry (r, c) at B[(r n + c) kBatchLanes + k], its point (u[k], v[k]), its answer *target[k].
void svd_path(const InversionPlan& plan, const double* B, const double* u, const double* v,
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

// Runs the lanes waiting in this thread's queue (see SvdQueue).
void flush_svd_queue(const InversionPlan& plan, const InvertOptions& options, StageSeconds* stages) {
  SvdQueue& queue = svd_queue();
  if (queue.size == 0) return;
  StageClock clock(stages);
  const std::size_t m = queue.size;
  queue.size = 0;
  svd_path(plan, queue.B.data(), queue.u.data(), queue.v.data(), queue.target.data(), m, options,
           batch_workspace(), clock);
}

// A finite point so far from the curve that its normalized coordinates or its Bezout matrix
// overflow: off_curve at the point of the segment nearest to it. From that far (over 1e150 times
// the curve's size) that is, to within the size over the distance, the point of the segment
// farthest along the point's direction from the centre: the nearest point to a stand-in on that
// ray at kFarStandIn (normalized units), where nothing overflows.
void answer_far_point(const InversionPlan& plan, const Point& point, PointResult& r) {
  constexpr double kFarStandIn = 1e8;
  // The direction from the centre, in coordinates scaled by a power of two so nothing overflows.
  const int e = std::max(std::ilogb(std::max(std::abs(point.x), std::abs(point.y))),
                         std::ilogb(std::max({std::abs(plan.centre[0]), std::abs(plan.centre[1]), 1.0})));
  const double dx = std::ldexp(point.x, -e) - std::ldexp(plan.centre[0], -e);
  const double dy = std::ldexp(point.y, -e) - std::ldexp(plan.centre[1], -e);
  const double a = plan.cos_rotation * dx - plan.sin_rotation * dy, b = plan.sin_rotation * dx + plan.cos_rotation * dy;
  const double length = std::hypot(a, b);
  r = PointResult{};
  r.status = Status::off_curve;
  r.path = Path::nearest;
  r.t = detail::nearest_parameter_on_segment(plan, kFarStandIn * a / length, kFarStandIn * b / length, -1.0);
  // |P(t) - P0| in input units, halved first so the differences do not overflow (inf only when
  // the distance itself exceeds the largest double).
  const auto p = plan.curve.point(r.t);
  r.residual = 2 * std::hypot(0.5 * p[0] - 0.5 * point.x, 0.5 * p[1] - 0.5 * point.y);
}

// A lane whose Bezout matrix overflowed (poison[l] not 0: an entry is not finite) is a point too
// far to form B for: answered off_curve by answer_far_point, it leaves the pipeline.
void mark_overflowing_b(const InversionPlan& plan, const Point* points, const double* poison, std::size_t count,
                        BatchWorkspace& w, PointResult* results) {
  for (std::size_t l = 0; l < count; ++l)
    if (w.active[l] && !(poison[l] == 0.0)) {
      answer_far_point(plan, points[l], results[l]);
      w.active[l] = 0;
    }
}

// The kernels' Bxy: null for one denominator, where Bxy = Bez(W, W) = 0 and B is affine in (u, v),
// so that they skip the term (a third of forming B) and give bezout_at's bits, which skips it too.
const double* bilinear_coefficients(const InversionPlan& plan) {
  return plan.common_denominator ? nullptr : plan.Bxy.data();
}

// B of the points (u[k], v[k]), k < m, into lanes 0..m-1 of B (stride kBatchLanes), as stage 1
// forms it, for lanes gathered from a batch (pass 2, the SVD path, the second-parameter check);
// their B did not overflow (such a lane left the pipeline when its B was first formed).
void form_compacted_b(const InversionPlan& plan, const double* u, const double* v, std::size_t m, double* B) {
  std::array<double, kBatchLanes> poison;
  kernels::active_implementation().bezout_matrix(plan.degree, m, kBatchLanes, plan.B0.data(), plan.Bx.data(),
                                                 plan.By.data(), bilinear_coefficients(plan), u, v, B, poison.data());
}

// Runs the second-parameter check for the lanes waiting in this thread's PairCheckQueue: a lane is
// answered on the fast path unless one of its roots refines onto the segment, within the
// tolerance, at a parameter distinct from its t; such a lane goes to the SVD path (double points
// are always answered there), through the SVD queue.
void flush_pair_check_queue(const InversionPlan& plan, const InvertOptions& options, StageSeconds* stages) {
  PairCheckQueue& q = pair_check_queue();
  if (q.lanes == 0) return;
  StageClock clock(stages);
  const double tolerance = normalized_tolerance(plan, options);
  const kernels::RationalCurve curve = detail::kernel_curve(plan);
  const std::size_t slots = q.root_t.size();
  for (const std::size_t first : {std::size_t{0}, slots - q.far}) {
    const std::size_t size = first == 0 ? q.near : q.far;
    kernels::active_implementation().rational_newton(curve, detail::kNewtonSettings, size, q.root_u.data() + first,
                                                     q.root_v.data() + first, q.root_t.data() + first,
                                                     q.root_distance.data() + first);
  }
  std::fill_n(q.second_found.begin(), q.lanes, std::uint8_t{0});
  for (std::size_t k = 0; k < slots; ++k) {
    if (k == q.near) k = slots - q.far;
    if (k == slots) break;
    const std::size_t lane = q.root_lane[k];
    detail::Refined r{q.root_t[k], q.root_distance[k]};
    if (std::isnan(r.distance)) r = detail::refine_parameter(plan, q.root_u[k], q.root_v[k], q.root_t[k], true);
    if (r.distance <= tolerance && std::abs(r.t - q.t[lane]) > kDistinctParameterGap) q.second_found[lane] = 1;
  }
  clock.lap(&StageSeconds::refine);
  const std::size_t lanes = q.lanes;
  q.lanes = q.near = q.far = 0;
  // The lanes with a second parameter go to the SVD path through its queue, with their B formed
  // again as invert_batch_lanes forms it (the same kernel, so the same bits) in the batch
  // workspace, which is free between batches; kBatchLanes of them at a time.
  const int n = plan.degree, nn = n * n;
  SvdQueue& svd = svd_queue();
  std::array<double, kBatchLanes> u, v;
  std::array<PointResult*, kBatchLanes> target;
  for (std::size_t k = 0; k < lanes;) {
    std::size_t m = 0;
    for (; k < lanes && m < kBatchLanes; ++k) {
      if (!q.second_found[k]) {
        answer_fast(plan, q.t[k], q.distance[k], q.sigma_min[k], q.sigma_next[k], *q.target[k]);
        continue;
      }
      u[m] = q.u[k];
      v[m] = q.v[k];
      target[m++] = q.target[k];
    }
    if (m == 0) continue;
    BatchWorkspace& w = batch_workspace();
    form_compacted_b(plan, u.data(), v.data(), m, w.B.data());
    for (std::size_t j = 0; j < m; ++j) {
      if (svd.size == kBatchLanes) flush_svd_queue(plan, options, stages);  // uses w, but not w.B
      svd.push(nn, w.B.data(), j, u[j], v[j], target[j]);
    }
  }
  clock.lap(&StageSeconds::decide);
}

// Both queues, in this order (the pair check may hand lanes to the SVD path).
void flush_queues(const InversionPlan& plan, const InvertOptions& options, StageSeconds* stages) {
  flush_pair_check_queue(plan, options, stages);
  flush_svd_queue(plan, options, stages);
}

// One batch (count <= kBatchLanes) of points of one curve through the five stages (but for the
// lanes left waiting in this thread's queues).
void invert_batch_lanes(const InversionPlan& plan, const Point* points, PointResult* results, std::size_t count,
                        const InvertOptions& options, StageSeconds* stages) {
  BatchWorkspace& w = batch_workspace();
  const int n = plan.degree, nn = n * n;
  const std::size_t stride = kBatchLanes;
  const double tolerance = normalized_tolerance(plan, options);
  StageClock clock(stages);

  // 1. form B. Lanes that are already answered (bad input, unusable curve) are given B = identity
  // so the kernel sees only finite, harmless matrices.
  for (std::size_t l = 0; l < count; ++l) {  // the arithmetic alone, so that it vectorizes
    const auto uv = plan.normalize(points[l].x, points[l].y);
    w.u[l] = uv[0];
    w.v[l] = uv[1];
  }
  for (std::size_t l = 0; l < count; ++l) {
    PointResult& r = results[l];
    r = PointResult{};
    w.active[l] = 0;
    if (!std::isfinite(points[l].x) || !std::isfinite(points[l].y)) {
      r.status = Status::invalid_input;
      r.reason = "non-finite coordinate";
    } else if (!plan.usable) {
      r.status = Status::failed;
      r.reason = plan.reason;
    } else if (!std::isfinite(w.u[l]) || !std::isfinite(w.v[l])) {
      answer_far_point(plan, points[l], r);
    } else {
      w.active[l] = 1;
    }
    if (!w.active[l]) w.u[l] = w.v[l] = 0.0;
  }
  // On the fast path's two passes from degree kFormedBMinDegree the seed kernel forms each lane's
  // B from the plan itself, in registers (bezout_null_vector_seed, the same bits as
  // bezout_matrix): there a batch's B no longer fits in L1, and reading it back was most of the
  // seed's time. The rare lanes that go on to pass 2 or the SVD path get their B formed then,
  // compacted (form_compacted_b).
  // Not on a straight line: B vanishes at its points, and the kernel's estimates, relative to
  // ||B||, would read rounding as evidence.
  const bool fast_path = options.fast_path && options.refine && n >= 2 && n <= kFastPathMaxDegree && !plan.straight_line;
  const bool formed_b = fast_path && n >= kFormedBMinDegree;
  if (n >= 2 && !formed_b) {
    // The lower triangle only: B is symmetric and the kernels read nothing else (batch.hpp).
    // An entry that overflowed makes its lane's sum of entry * 0 NaN (inf * 0). A kernel, so that
    // it runs in the CPU's widest vectors (this file is compiled for baseline x86-64): the stage
    // went 2x faster at degree 8 and 3x at degree 15 (bezinv profile, 1 thread, AVX-512).
    std::array<double, kBatchLanes> poison;
    kernels::active_implementation().bezout_matrix(n, count, stride, plan.B0.data(), plan.Bx.data(), plan.By.data(),
                                                   bilinear_coefficients(plan), w.u.data(), w.v.data(), w.B.data(),
                                                   poison.data());
    mark_overflowing_b(plan, points, poison.data(), count, w, results);
    for (std::size_t l = 0; l < count; ++l) {
      if (!w.active[l])
        for (int i = 0; i < nn; ++i) w.B[i * stride + l] = (i % (n + 1) == 0) ? 1.0 : 0.0;
    }
  }
  clock.lap(&StageSeconds::form_b);

  // 2-4 on the fast path (refinement on, degree >= 2): a null vector by inverse iteration, read
  // out, refined, in two passes from degree 3 (below). With the gap (degree 2, and pass 2), a lane
  // is answered here only when the SVD path could not answer it differently: the kernel's
  // evidence says z is a converged, simple null vector (defect), there is no degree drop, and the
  // refined point is on the segment within the tolerance. Where the sigma_{n-1} estimate does not
  // clear kSecondNullDirectionRatio by the margin kFastPathGapRatio the SVD path would look for a
  // second parameter: so does the fast path, in the span of z and the kernel's second vector, and
  // a lane that finds one goes to the SVD path (double points are always answered there), as does
  // a lane whose estimate is below kFastPathMinGap. Every other lane goes on to the SVD path
  // below, which decides as before.
  // With refinement off the output is the paper's algebraic t, so it always comes from the SVD.
  //
  // Two passes (degree >= 3). The full kernel spends 8 of its 11 solves on the sigma_{n-1}
  // estimate, and its factorization on per-lane row swaps; on the curve, the isolation certificate
  // settles what the estimate is for: that P0 has no second parameter on the segment within the
  // tolerance (engine/src/isolation.hpp), so that the SVD path, whose double_point needs one, would
  // answer ok at the same t. So:
  //   1. the seed kernel (null_vector_seed: L D L^T without pivoting, two inverse iterations, no
  //      gap) for every lane, read out and refined; a lane refined onto the segment that the
  //      certificate covers is answered here, with sigma_next = NaN (no gap decided it). How good
  //      its seed was does not matter: the answer is checked on its own.
  //   2. the lanes whose refined point is one the SVD path could answer with, but which the
  //      geometry alone does not settle: on the segment within the tolerance but not certified
  //      (the second-parameter check then looks for another), or off the curve and proved the
  //      nearest point of the segment (off_curve_nearest, then off_curve_alone). They are gathered
  //      and run through the full kernel (pivoted LU, the gap and the second vector), and go on
  //      as with the gap from the start (decide_with_gap), keeping their refined point.
  //   Every other lane goes to the SVD path, as before: a degree drop, a seed that did not settle
  //   (off the curve B is regular, and z converges at the rate sigma_n / sigma_{n-1} with either
  //   factorization), a point on the extension, or off the curve and not proved the nearest.
  //   (Sending those through pass 2 too, to be read out again from the pivoted z, was 2-10%
  //   slower at noise 1e-4 than this, BM_Engine_refined_noisy, for lanes that nearly all end on
  //   the SVD path anyway.)
  // Off the curve the two passes cost 5-10% at noise 1e-5 of the curve's size against the single
  // pass (the seed is spent on lanes that need the gap); within the tolerance they gain 1.7-1.9x
  // from degree 8 up, on the curve 1.1-2.3x (BENCHMARKS.md, sixth session).
  // Degree 2 keeps the full kernel alone: two solves of a 2 x 2 system, and an exact gap.
  if (fast_path) {
    const kernels::Implementation& kernel = kernels::active_implementation();
    const bool two_passes = n >= 3;
    if (formed_b) {
      std::array<double, kBatchLanes> poison;
      kernel.bezout_null_vector_seed(n, count, stride, plan.B0.data(), plan.Bx.data(), plan.By.data(),
                                     bilinear_coefficients(plan), w.u.data(), w.v.data(), w.z.data(), w.defect.data(),
                                     w.estimate.data(), poison.data());
      mark_overflowing_b(plan, points, poison.data(), count, w, results);
    } else if (two_passes) {
      kernel.null_vector_seed(n, count, stride, w.B.data(), w.z.data(), w.defect.data(), w.estimate.data());
    } else {
      kernel.null_vector(n, count, stride, w.B.data(), w.z.data(), w.defect.data(), w.estimate.data(),
                         w.second.data());
    }
    clock.lap(&StageSeconds::kernel);
    kernel.bernstein_parameter(n, count, stride, w.z.data(), w.t_algebraic.data());
    for (std::size_t l = 0; l < count; ++l)
      if (!w.active[l] || !(w.defect[l] <= kFastPathMaxDefect) ||
          (!two_passes && !(w.estimate[stride + l] >= kFastPathMinGap)))
        w.t_algebraic[l] = PointResult::nan;
    clock.lap(&StageSeconds::read_out);
    // Refinement, lane-batched: the kernel runs refine.cpp's safeguarded Newton for every lane whose
    // t_algebraic is in [0,1] and gives settle()'s numbers bit for bit. It leaves the rest to
    // settle(), as it does a lane that ends at an end of the segment off the curve (settle() then
    // also looks along the extension).
    std::copy_n(w.t_algebraic.begin(), count, w.t_refined.begin());
    const kernels::RationalCurve curve = detail::kernel_curve(plan);
    kernel.rational_newton(curve, detail::kNewtonSettings, count, w.u.data(), w.v.data(), w.t_refined.data(),
                           w.distance.data());
    detail::degree_drops_batch(plan, w.u.data(), w.v.data(), count, w.drops.data());
    if (two_passes) {
      // The common case of pass 1, for the whole batch before the lane-by-lane decisions below: a
      // lane refined onto the segment within the tolerance (the kernel clamps to [0, 1]) that the
      // certificate's first test settles. The loop below would answer it the same way, at a call
      // of settle's bookkeeping and of isolated() per lane (11% of the pipeline at degree 3, perf).
      detail::isolated_by_far_boxes(plan, w.t_refined.data(), w.distance.data(), tolerance, count,
                                    w.certified.data());
      for (std::size_t l = 0; l < count; ++l)
        if (w.certified[l] && w.active[l] && !w.drops[l] && std::isfinite(w.t_algebraic[l]) &&
            w.distance[l] <= tolerance) {
          w.active[l] = 0;
          answer_fast(plan, w.t_refined[l], w.distance[l], w.estimate[l], PointResult::nan, results[l]);
        }
    }
    std::size_t waiting = 0;  // lanes of pass 2
    for (std::size_t l = 0; l < count; ++l) {
      if (!w.active[l] || w.drops[l]) continue;
      Candidate& c = w.main[l];
      const bool refined = std::isfinite(w.t_algebraic[l]);
      if (refined) {
        const bool at_end = w.t_refined[l] == 0.0 || w.t_refined[l] == 1.0;
        if (std::isfinite(w.distance[l]) && !(at_end && !(w.distance[l] <= tolerance))) {
          c = Candidate{};
          c.t = w.t_refined[l];
          c.distance = w.distance[l];
          c.path = Path::bezout_lu;
          classify(c, tolerance);
        } else {
          c = settle(plan, w.u[l], w.v[l], w.t_algebraic[l], Path::bezout_lu, tolerance, true);
        }
      }
      if (!two_passes) {
        if (refined) decide_with_gap(plan, w, l, c, tolerance, false, results[l]);
        continue;
      }
      if (!refined) continue;  // z did not settle: the SVD path
      if (c.on_segment && detail::isolated(plan, w.u[l], w.v[l], c.t, c.distance, tolerance)) {
        w.active[l] = 0;
        answer_fast(plan, c.t, c.distance, w.estimate[l], PointResult::nan, results[l]);
      } else if (c.on_segment || off_curve_nearest(plan, w, l, c)) {
        w.gap_lane_of[waiting++] = static_cast<std::uint8_t>(l);
      }
    }
    clock.lap(&StageSeconds::refine);
    if (waiting > 0) {
      // Pass 2: the full kernel for the waiting lanes, compacted, its results put back in their lanes.
      {
        std::array<double, kBatchLanes> u, v;
        for (std::size_t k = 0; k < waiting; ++k) u[k] = w.u[w.gap_lane_of[k]], v[k] = w.v[w.gap_lane_of[k]];
        form_compacted_b(plan, u.data(), v.data(), waiting, w.gap_B.data());
      }
      kernel.null_vector(n, waiting, stride, w.gap_B.data(), w.gap_z.data(), w.gap_defect.data(),
                         w.gap_estimate.data(), w.gap_second.data());
      for (std::size_t k = 0; k < waiting; ++k) {
        const std::size_t l = w.gap_lane_of[k];
        for (int r = 0; r < n; ++r) {
          w.z[r * stride + l] = w.gap_z[r * stride + k];
          w.second[r * stride + l] = w.gap_second[r * stride + k];
        }
        w.defect[l] = w.gap_defect[k];
        w.estimate[l] = w.gap_estimate[k];
        w.estimate[stride + l] = w.gap_estimate[stride + k];
      }
      clock.lap(&StageSeconds::kernel);
      for (std::size_t k = 0; k < waiting; ++k) {
        const std::size_t l = w.gap_lane_of[k];
        if (w.defect[l] <= kFastPathMaxDefect && w.estimate[stride + l] >= kFastPathMinGap)
          decide_with_gap(plan, w, l, w.main[l], tolerance, true, results[l]);
      }
      clock.lap(&StageSeconds::refine);
    }
  }

  // The SVD path for the lanes still undecided, compacted to the front of the batch (in order, so
  // moving lane lane_of[k] >= k down to k never overwrites a lane still to be moved).
  std::size_t m = 0;
  for (std::size_t l = 0; l < count; ++l) {
    if (!w.active[l]) continue;
    if (m != l) {
      if (!formed_b)
        for (int i = 0; i < nn; ++i) w.B[i * stride + m] = w.B[i * stride + l];
      w.u[m] = w.u[l];
      w.v[m] = w.v[l];
    }
    w.lane_of[m++] = static_cast<std::uint8_t>(l);
  }
  if (formed_b && m > 0) form_compacted_b(plan, w.u.data(), w.v.data(), m, w.B.data());

  if (m == 0) {
    clock.lap(&StageSeconds::decide);  // the routing above is the decide stage's
    return;
  }
  SvdQueue& queue = svd_queue();
  if (m >= kSvdGroupLanes || queue.size + m > kBatchLanes) {  // enough for a group: here and now
    std::array<PointResult*, kBatchLanes> target;
    for (std::size_t k = 0; k < m; ++k) target[k] = &results[w.lane_of[k]];
    svd_path(plan, w.B.data(), w.u.data(), w.v.data(), target.data(), m, options, w, clock);
    return;
  }
  for (std::size_t k = 0; k < m; ++k) queue.push(nn, w.B.data(), k, w.u[k], w.v[k], &results[w.lane_of[k]]);
  clock.lap(&StageSeconds::decide);
  if (queue.size >= kSvdGroupLanes) flush_svd_queue(plan, options, stages);
}

// One batch, with this thread's pair-check queue around it: flushed first if the batch's lanes
// might not fit in it, and after once enough roots wait to fill a SIMD group (both outside
// invert_batch_lanes, whose workspace the SVD path also uses).
void invert_batch(const InversionPlan& plan, const Point* points, PointResult* results, std::size_t count,
                  const InvertOptions& options, StageSeconds* stages) {
  PairCheckQueue& pairs = pair_check_queue();
  if (pairs.lanes + count > kPairCheckLanes) flush_pair_check_queue(plan, options, stages);
  invert_batch_lanes(plan, points, results, count, options, stages);
  if (pairs.near + pairs.far >= kPairCheckFlushRoots) {
    flush_pair_check_queue(plan, options, stages);
    if (svd_queue().size >= kSvdGroupLanes) flush_svd_queue(plan, options, stages);
  }
}

// All points of one curve: batches in parallel.
void invert_curve(const InversionPlan& plan, std::span<const Point> points, std::span<PointResult> results,
                  const InvertOptions& options, StageSeconds* stages);

}  // namespace

std::string_view active_kernel_name() {
  // The lane-batched implementation (degrees <= kLaneBatchedMaxDegree; Eigen per matrix above).
  return kernels::active_implementation().name;
}

PointResult invert_point(const InversionPlan& plan, Point point, const InvertOptions& options) {
  PointResult r;
  const QueueScope scope;
  invert_batch(plan, &point, &r, 1, options, nullptr);
  flush_queues(plan, options, nullptr);
  return r;
}

namespace {

// One arena per thread count, made on first use and kept: creating an arena per call cost ~70 us,
// a third of a 1024-point call at degree 3 (bench/baselines_bench.cpp, 2 threads). Arenas may be
// entered from several threads at once.
tbb::task_arena& arena_for(int threads) {
  static std::mutex mutex;
  static std::map<int, std::unique_ptr<tbb::task_arena>> arenas;
  const std::lock_guard<std::mutex> lock(mutex);
  std::unique_ptr<tbb::task_arena>& arena = arenas[threads];
  // A prvalue: binding task_arena::automatic itself to make_unique's reference would odr-use it.
  const int concurrency = threads > 0 ? threads : int{tbb::task_arena::automatic};
  if (!arena) arena = std::make_unique<tbb::task_arena>(concurrency);
  return *arena;
}

// Runs of one curve shorter than this are inverted in parallel with each other rather than in
// their batches (invert with many plans).
constexpr std::size_t kShortRun = 8 * kBatchLanes;

// body(begin, end) for every batch, then end_of_range() after each range of batches a thread runs.
template <typename Body, typename EndOfRange>
void for_each_batch(std::size_t count, const InvertOptions& options, Body&& body, EndOfRange&& end_of_range) {
  const std::size_t batches = (count + kBatchLanes - 1) / kBatchLanes;
  auto run = [&](const tbb::blocked_range<std::size_t>& range) {
    const QueueScope scope;
    for (std::size_t b = range.begin(); b != range.end(); ++b)
      body(b * kBatchLanes, std::min(count, (b + 1) * kBatchLanes));
    end_of_range();
  };
  if (options.threads == 1 || batches <= 1) {
    run(tbb::blocked_range<std::size_t>(0, batches));
    return;
  }
  arena_for(options.threads).execute([&] { tbb::parallel_for(tbb::blocked_range<std::size_t>(0, batches, 4), run); });
}

void invert_curve(const InversionPlan& plan, std::span<const Point> points, std::span<PointResult> results,
                  const InvertOptions& options, StageSeconds* stages) {
  // Stage times are summed per thread, then added up (seconds of work, not wall time). The
  // per-thread clocks only when asked for: made on every call, they cost more than a run of a few
  // points of a file of many curves.
  std::optional<tbb::enumerable_thread_specific<StageSeconds>> per_thread;
  if (stages) per_thread.emplace();
  auto local = [&]() -> StageSeconds* { return per_thread ? &per_thread->local() : nullptr; };
  for_each_batch(
      points.size(), options,
      [&](std::size_t begin, std::size_t end) {
        invert_batch(plan, points.data() + begin, results.data() + begin, end - begin, options, local());
      },
      [&] { flush_queues(plan, options, local()); });
  if (per_thread)
    for (const StageSeconds& s : *per_thread) {
      stages->form_b += s.form_b; stages->kernel += s.kernel; stages->read_out += s.read_out;
      stages->refine += s.refine; stages->decide += s.decide;
    }
}

}  // namespace

void invert(const InversionPlan& plan, std::span<const Point> points, std::span<PointResult> results,
            const InvertOptions& options, StageSeconds* stages) {
  invert_curve(plan, points, results, options, stages);
}

void invert(std::span<const InversionPlan> plans, std::span<const int> curve_of, std::span<const Point> points,
            std::span<PointResult> results, const InvertOptions& options) {
  // Batches must hold points of one curve: runs of consecutive points of the same curve are
  // inverted in place (the common case: files grouped by curve); a point whose curve differs from
  // both neighbours forms a run of one. Rejected rows (curve_of < 0) keep what the caller set.
  // A long run is parallel in its batches; the short ones (many curves of few points each) are
  // parallel among themselves instead, each on one thread: run by run, a file of 20,000 cubics
  // of 10 points each went at a third of the speed of one long run (2 threads), every run
  // shorter than a batch.
  struct Run { std::size_t begin, end; };
  std::vector<Run> short_runs;
  std::size_t begin = 0;
  const std::size_t count = points.size();
  auto invert_run = [&](const Run& run, const InvertOptions& run_options) {
    invert_curve(plans[curve_of[run.begin]], points.subspan(run.begin, run.end - run.begin),
                 results.subspan(run.begin, run.end - run.begin), run_options, nullptr);
  };
  while (begin < count) {
    std::size_t end = begin + 1;
    while (end < count && curve_of[end] == curve_of[begin]) ++end;
    if (curve_of[begin] >= 0) {
      if (end - begin >= kShortRun || options.threads == 1)
        invert_run({begin, end}, options);
      else
        short_runs.push_back({begin, end});
    }
    begin = end;
  }
  if (short_runs.empty()) return;
  InvertOptions one_thread = options;
  one_thread.threads = 1;
  arena_for(options.threads).execute([&] {
    tbb::parallel_for(tbb::blocked_range<std::size_t>(0, short_runs.size(), 16), [&](const auto& range) {
      for (std::size_t r = range.begin(); r != range.end(); ++r) invert_run(short_runs[r], one_thread);
    });
  });
}

}  // namespace bezinv
