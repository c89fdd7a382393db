// The lane-batched kernels (kernels/batch.hpp) per implementation and size, against Eigen's
// fixed-size SelfAdjointEigenSolver one matrix at a time; Newton's method and the slope per
// implementation and degree. Each benchmark cycles over kDistinct
// matrices in batches of kBatch, so the inputs are not cache-hot (Ceres *_benchmark.cc style).
// items_per_second = matrices per second.
#include <benchmark/benchmark.h>

#include <Eigen/Eigenvalues>
#include <algorithm>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <memory>
#include <random>
#include <string>
#include <utility>
#include <vector>

#include "bezinv/kernels/batch.hpp"

namespace {

using namespace bezinv::kernels;

constexpr std::size_t kDistinct = 1024;  // matrices cycled over
constexpr std::size_t kBatch = 64;       // matrices per kernel call (a multiple of every width)

// kDistinct random symmetric n x n matrices with a singular value forced to 0 (the kernels'
// use case), stored as kDistinct / kBatch SoA batches.
struct Inputs {
  int n;
  std::vector<std::vector<double>> batches;
  std::vector<Eigen::MatrixXd> dense;

  explicit Inputs(int n_) : n(n_) {
    std::mt19937_64 rng(42 + n);
    std::normal_distribution<double> g;
    for (std::size_t i = 0; i < kDistinct; ++i) {
      Eigen::MatrixXd a(n, n);
      for (int r = 0; r < n; ++r)
        for (int c = 0; c < n; ++c) a(r, c) = g(rng);
      Eigen::MatrixXd q = Eigen::HouseholderQR<Eigen::MatrixXd>(a).householderQ() * Eigen::MatrixXd::Identity(n, n);
      Eigen::VectorXd s = Eigen::VectorXd::Random(n);
      s(n - 1) = 0;
      dense.push_back(q * s.asDiagonal() * q.transpose());
    }
    const std::size_t stride = batch_stride(kBatch);
    for (std::size_t b = 0; b < kDistinct / kBatch; ++b) {
      std::vector<double> soa(static_cast<std::size_t>(n) * n * stride);
      for (std::size_t l = 0; l < kBatch; ++l)
        for (int r = 0; r < n; ++r)
          for (int c = 0; c < n; ++c) soa[(r * n + c) * stride + l] = dense[b * kBatch + l](r, c);
      batches.push_back(std::move(soa));
    }
  }
};

const Inputs& inputs(int n) {
  static std::vector<std::unique_ptr<Inputs>> cache(kMaxBatchSize + 1);
  if (!cache[n]) cache[n] = std::make_unique<Inputs>(n);
  return *cache[n];
}

void BM_KernelSymmetricSvd(benchmark::State& state, const Implementation* impl, int n) {
  const Inputs& in = inputs(n);
  const std::size_t stride = batch_stride(kBatch);
  std::vector<double> sigma(n * stride), V(static_cast<std::size_t>(n) * n * stride);
  std::size_t b = 0;
  for (auto _ : state) {
    impl->symmetric_svd(n, kBatch, stride, in.batches[b].data(), sigma.data(), V.data());
    benchmark::DoNotOptimize(sigma.data());
    benchmark::ClobberMemory();
    b = (b + 1) % in.batches.size();
  }
  state.SetItemsProcessed(static_cast<std::int64_t>(state.iterations() * kBatch));
}

void BM_KernelNullVector(benchmark::State& state, const Implementation* impl, int n) {
  const Inputs& in = inputs(n);
  const std::size_t stride = batch_stride(kBatch);
  std::vector<double> z(n * stride), defect(stride), estimate(2 * stride);
  std::size_t b = 0;
  for (auto _ : state) {
    impl->null_vector(n, kBatch, stride, in.batches[b].data(), z.data(), defect.data(), estimate.data(), nullptr);
    benchmark::DoNotOptimize(z.data());
    benchmark::ClobberMemory();
    b = (b + 1) % in.batches.size();
  }
  state.SetItemsProcessed(static_cast<std::int64_t>(state.iterations() * kBatch));
}

// The seed: LDL^T without pivoting, no sigma_{n-1} estimate (what the engine runs first, see invert.cpp).
void BM_KernelNullVectorSeed(benchmark::State& state, const Implementation* impl, int n) {
  const Inputs& in = inputs(n);
  const std::size_t stride = batch_stride(kBatch);
  std::vector<double> z(n * stride), defect(stride), residual(stride);
  std::size_t b = 0;
  for (auto _ : state) {
    impl->null_vector_seed(n, kBatch, stride, in.batches[b].data(), z.data(), defect.data(), residual.data(), 1.0);
    benchmark::DoNotOptimize(z.data());
    benchmark::ClobberMemory();
    b = (b + 1) % in.batches.size();
  }
  state.SetItemsProcessed(static_cast<std::int64_t>(state.iterations() * kBatch));
}

// Form B: the Bezout matrices of kDistinct points from one set of coefficient matrices (what the
// engine does per batch), in batches of kBatch points. items_per_second = matrices per second.
void BM_KernelBezoutMatrix(benchmark::State& state, const Implementation* impl, int n) {
  std::mt19937_64 rng(7 + n);
  std::uniform_real_distribution<double> unit(-1.0, 1.0);
  const std::size_t nn = static_cast<std::size_t>(n) * n, stride = batch_stride(kBatch);
  std::vector<double> B0(nn), Bx(nn), By(nn), Bxy(nn), u(kDistinct), v(kDistinct);
  for (std::size_t i = 0; i < nn; ++i) B0[i] = unit(rng), Bx[i] = unit(rng), By[i] = unit(rng), Bxy[i] = unit(rng);
  for (std::size_t l = 0; l < kDistinct; ++l) u[l] = unit(rng), v[l] = unit(rng);
  std::vector<double> B(nn * stride), poison(kBatch);
  std::size_t first = 0;
  for (auto _ : state) {
    impl->bezout_matrix(n, kBatch, stride, B0.data(), Bx.data(), By.data(), Bxy.data(), u.data() + first,
                        v.data() + first, B.data(), poison.data());
    benchmark::DoNotOptimize(B.data());
    benchmark::ClobberMemory();
    first = (first + kBatch) % kDistinct;
  }
  state.SetItemsProcessed(static_cast<std::int64_t>(state.iterations() * kBatch));
}

// The engine's seed step from the points, two ways: bezout_matrix then null_vector_seed (B stored
// in the batch, read back), against bezout_null_vector_seed (B formed in registers, never stored).
// The same bits; items_per_second = points per second.
void BM_KernelBezoutSeed(benchmark::State& state, const Implementation* impl, int n, bool formed) {
  std::mt19937_64 rng(11 + n);
  std::uniform_real_distribution<double> unit(-1.0, 1.0);
  const std::size_t nn = static_cast<std::size_t>(n) * n, stride = batch_stride(kBatch);
  std::vector<double> B0(nn), Bx(nn), By(nn), u(kDistinct), v(kDistinct);
  for (int r = 0; r < n; ++r)
    for (int c = 0; c <= r; ++c) {
      const double b0 = unit(rng), bx = unit(rng), by = unit(rng);
      for (const std::size_t i : {static_cast<std::size_t>(r * n + c), static_cast<std::size_t>(c * n + r)})
        B0[i] = b0, Bx[i] = bx, By[i] = by;  // a common denominator: Bxy null, as the engine passes it
    }
  for (std::size_t l = 0; l < kDistinct; ++l) u[l] = unit(rng), v[l] = unit(rng);
  std::vector<double> B(nn * stride), z(static_cast<std::size_t>(n) * stride), defect(kBatch), residual(kBatch),
      poison(kBatch);
  std::size_t first = 0;
  for (auto _ : state) {
    if (formed) {
      impl->bezout_null_vector_seed(n, kBatch, stride, B0.data(), Bx.data(), By.data(), nullptr, u.data() + first,
                                    v.data() + first, z.data(), defect.data(), residual.data(), poison.data(), 1.0);
    } else {
      impl->bezout_matrix(n, kBatch, stride, B0.data(), Bx.data(), By.data(), nullptr, u.data() + first,
                          v.data() + first, B.data(), poison.data());
      impl->null_vector_seed(n, kBatch, stride, B.data(), z.data(), defect.data(), residual.data(), 1.0);
    }
    benchmark::DoNotOptimize(z.data());
    benchmark::ClobberMemory();
    first = (first + kBatch) % kDistinct;
  }
  state.SetItemsProcessed(static_cast<std::int64_t>(state.iterations() * kBatch));
}

// Newton's method and the slope on curves: kDistinct / kBatch random rational Bezier curves of
// degree n (control points in [-1, 1]^2, weights in [0.5, 2], one denominator), kBatch points per
// curve moved off it by up to 1e-2 in each coordinate, each started 1e-2 from its own t: the
// off-curve path's case. Horner's coefficients (RationalCurve::horner) as the engine's plan lays
// them out.
struct CurveInputs {
  int n;
  std::vector<std::vector<double>> x_num, x_den, y_num, y_den, horner;
  std::vector<std::vector<double>> u, v, t;

  explicit CurveInputs(int n_) : n(n_) {
    std::mt19937_64 rng(7 + n);
    std::uniform_real_distribution<double> coordinate(-1.0, 1.0), weight(0.5, 2.0), unit(0.0, 1.0);
    const auto binomial = [](int m, int i) {
      double b = 1;
      for (int k = 1; k <= i; ++k) b = b * (m - i + k) / k;
      return b;
    };
    const auto bernstein_sum = [&](const std::vector<double>& c, double t) {  // sum c_i C(n,i) (1-t)^(n-i) t^i
      double sum = 0;
      for (int i = 0; i <= n; ++i) sum += c[i] * binomial(n, i) * std::pow(1 - t, n - i) * std::pow(t, i);
      return sum;
    };
    for (std::size_t b = 0; b < kDistinct / kBatch; ++b) {
      std::vector<double> xn, w, yn;
      for (int i = 0; i <= n; ++i) {
        const double wi = weight(rng);
        xn.push_back(wi * coordinate(rng)), yn.push_back(wi * coordinate(rng)), w.push_back(wi);
      }
      std::vector<double> h;
      for (const std::vector<double>* c : {&xn, &w, &yn, &w}) {
        const std::vector<double>& p = *c;
        for (int i = 0; i <= n; ++i) h.push_back(p[i] * binomial(n, i));
        for (int i = 0; i < n; ++i) h.push_back(n * (p[i + 1] - p[i]) * binomial(n - 1, i));
        for (int i = 0; i + 1 < n; ++i) h.push_back(n * (n - 1.0) * (p[i + 2] - 2 * p[i + 1] + p[i]) * binomial(n - 2, i));
      }
      std::vector<double> us, vs, ts;
      for (std::size_t l = 0; l < kBatch; ++l) {
        const double at = unit(rng), den = bernstein_sum(w, at);
        us.push_back(bernstein_sum(xn, at) / den + 1e-2 * coordinate(rng));
        vs.push_back(bernstein_sum(yn, at) / den + 1e-2 * coordinate(rng));
        ts.push_back(std::clamp(at + 1e-2 * coordinate(rng), 0.0, 1.0));
      }
      x_num.push_back(xn), x_den.push_back(w), y_num.push_back(yn), y_den.push_back(w), horner.push_back(h);
      u.push_back(us), v.push_back(vs), t.push_back(ts);
    }
  }
  RationalCurve curve(std::size_t b, bool by_horner) const {
    return {n, x_num[b].data(), x_den[b].data(), y_num[b].data(), y_den[b].data(),
            by_horner ? horner[b].data() : nullptr};
  }
};

const CurveInputs& curve_inputs(int n) {
  static std::vector<std::unique_ptr<CurveInputs>> cache(kMaxBatchSize + 1);
  if (!cache[n]) cache[n] = std::make_unique<CurveInputs>(n);
  return *cache[n];
}

// items_per_second = points refined per second.
void BM_KernelRationalNewton(benchmark::State& state, const Implementation* impl, int n) {
  const CurveInputs& in = curve_inputs(n);
  const NewtonSettings settings{60, 0.125, 1e-6, 40, 1e-12};  // the engine's (tolerances.hpp)
  std::vector<double> t(kBatch), distance(kBatch);
  std::size_t b = 0;
  for (auto _ : state) {
    t = in.t[b];
    impl->rational_newton(in.curve(b, false), settings, kBatch, in.u[b].data(), in.v[b].data(), t.data(),
                          distance.data());
    benchmark::DoNotOptimize(distance.data());
    b = (b + 1) % in.t.size();
  }
  state.SetItemsProcessed(static_cast<std::int64_t>(state.iterations() * kBatch));
}

// items_per_second = points refined per second, by the off-curve path's kernel.
void BM_KernelNearestNewton(benchmark::State& state, const Implementation* impl, int n) {
  const CurveInputs& in = curve_inputs(n);
  const NearestNewtonSettings settings{60, 0.125, 1e-6, 40, 1e-9};  // the engine's (tolerances.hpp)
  std::vector<double> t(kBatch), distance(kBatch);
  std::size_t b = 0;
  for (auto _ : state) {
    t = in.t[b];
    impl->nearest_newton(in.curve(b, true), settings, kBatch, in.u[b].data(), in.v[b].data(), t.data(),
                         distance.data());
    benchmark::DoNotOptimize(distance.data());
    b = (b + 1) % in.t.size();
  }
  state.SetItemsProcessed(static_cast<std::int64_t>(state.iterations() * kBatch));
}

// The fused formula path (formula_newton) on points on graphs of functions, x(t) = x0 + w t and
// y(t) a quotient of degree n, whose linear formula t = (x - x0) / w is exact: kDistinct / kBatch
// curves, kBatch points each at random t, a frame that scales and shifts, a certificate of eight
// pieces whose floors pass every point (the engine's common case on the curve).
struct GraphInputs {
  int n;
  std::vector<std::vector<double>> x_num, x_den, y_num, y_den, xy, formula;
  explicit GraphInputs(int n_) : n(n_) {
    std::mt19937_64 rng(11 + n);
    std::uniform_real_distribution<double> coordinate(-1.0, 1.0), weight(0.5, 2.0), unit(0.0, 1.0);
    for (std::size_t b = 0; b < kDistinct / kBatch; ++b) {
      const double x0 = coordinate(rng), w = 1.5 + coordinate(rng);
      std::vector<double> xn, xd, yn, yd;
      for (int i = 0; i <= n; ++i) {
        const double wi = weight(rng);
        xn.push_back(x0 + w * i / n), xd.push_back(1.0), yn.push_back(wi * coordinate(rng)), yd.push_back(wi);
      }
      auto value = [&](const std::vector<double>& c, double t) {
        std::vector<double> f = c;
        for (int r = 1; r <= n; ++r)
          for (int i = 0; i <= n - r; ++i) f[i] = (1 - t) * f[i] + t * f[i + 1];
        return f[0];
      };
      std::vector<double> points;
      for (std::size_t l = 0; l < kBatch; ++l) {
        const double t = unit(rng);
        points.push_back(value(xn, t) / value(xd, t) * 2.0);  // the frame halves it back
        points.push_back(value(yn, t) / value(yd, t) * 2.0);
      }
      x_num.push_back(xn), x_den.push_back(xd), y_num.push_back(yn), y_den.push_back(yd), xy.push_back(points);
      formula.push_back({-x0 / w, 1.0 / w, 0.0, 1.0, 0.0, 0.0});  // N's three terms, then M's
    }
  }
};

// items_per_second = points settled (or left) per second.
void BM_KernelFormulaNewton(benchmark::State& state, const Implementation* impl, int n) {
  static std::vector<std::unique_ptr<GraphInputs>> cache(kFormulaNewtonMaxDegree + 1);
  if (!cache[n]) cache[n] = std::make_unique<GraphInputs>(n);
  const GraphInputs& in = *cache[n];
  const NewtonSettings settings{60, 0.125, 1e-6, 40, 1e-9, 1e-10};  // the formula path's (tolerances.hpp)
  const PointFrame frame{0.5, 0.0, 0.0, 1.0, 0.0};
  const std::vector<double> monotone(8, 1e-2), unique(8, 1e-12), far(8, 0.5);
  const PieceCertificate certificate{8, monotone.data(), 0.25, unique.data(), far.data(), 1e-8, 1e-12, 0.5};
  std::vector<double> t(kBatch), distance(kBatch), u(kBatch), v(kBatch), t_formula(kBatch);
  const FormulaStart start{u.data(), v.data(), t_formula.data()};
  std::size_t b = 0, settled = 0;
  for (auto _ : state) {
    const PlaneFormula formula{1, 0.0, 0.0, 1.0, 1.0, 1e6, 1e-6, in.formula[b].data(), in.formula[b].data() + 3};
    const RationalCurve curve{n, in.x_num[b].data(), in.x_den[b].data(), in.y_num[b].data(), in.y_den[b].data()};
    std::array<std::uint64_t, (kBatch + 63) / 64> left_bits{}, leaves_bits{};
    const FormulaLanes lanes{left_bits.data(), leaves_bits.data()};
    settled += impl->formula_newton(formula, curve, settings, frame, certificate, 1e-8, kBatch, in.xy[b].data(),
                                    t.data(), distance.data(), &start, &lanes);
    benchmark::DoNotOptimize(left_bits.data());
    benchmark::DoNotOptimize(leaves_bits.data());
    benchmark::DoNotOptimize(distance.data());
    b = (b + 1) % in.xy.size();
  }
  state.SetItemsProcessed(static_cast<std::int64_t>(state.iterations() * kBatch));
  state.counters["settled"] = static_cast<double>(settled) / static_cast<double>(state.iterations() * kBatch);
}

// items_per_second = parameters evaluated per second.
void BM_KernelRationalSlope(benchmark::State& state, const Implementation* impl, int n) {
  const CurveInputs& in = curve_inputs(n);
  std::vector<double> x(kBatch), y(kBatch), dx(kBatch), dy(kBatch);
  std::size_t b = 0;
  for (auto _ : state) {
    impl->rational_slope(in.curve(b, true), kBatch, in.t[b].data(), x.data(), y.data(), dx.data(), dy.data());
    benchmark::DoNotOptimize(dx.data());
    b = (b + 1) % in.t.size();
  }
  state.SetItemsProcessed(static_cast<std::int64_t>(state.iterations() * kBatch));
}

// The baseline: Eigen's fixed-size self-adjoint eigensolver, one matrix per call.
template <int N>
void BM_KernelEigenSelfAdjoint(benchmark::State& state) {
  const Inputs& in = inputs(N);
  std::vector<Eigen::Matrix<double, N, N>> fixed;
  for (const auto& m : in.dense) fixed.push_back(m);
  Eigen::SelfAdjointEigenSolver<Eigen::Matrix<double, N, N>> solver;
  std::size_t i = 0;
  for (auto _ : state) {
    solver.compute(fixed[i], Eigen::ComputeEigenvectors);
    benchmark::DoNotOptimize(solver.eigenvectors().data());
    i = (i + 1) % fixed.size();
  }
  state.SetItemsProcessed(static_cast<std::int64_t>(state.iterations()));
}

constexpr int kSizes[] = {3, 5, 8, 10, 12, 15, 20, 24};
constexpr int kSeedSizes[] = {3, 4, 5, 6, 7, 8, 9, 10, 12, 15, 20, 24};

// "<name>/<implementation>/n:<n>", appended piece by piece: GCC 12 gives a false -Wrestrict on
// chained std::string operator+.
std::string benchmark_name(const char* name, const Implementation* impl, int n) {
  std::string out = name;
  out += "/";
  out += impl->name;
  out += "/n:";
  out += std::to_string(n);
  return out;
}

bool takes(int n, int min_size, int max_size) { return n >= min_size && n <= max_size; }

// Each kernel at the sizes it is compiled for (bezinv/kernels/batch.hpp).
int register_kernels() {
  for (const Implementation* impl : available_implementations())
    for (int n : kSizes) {
      if (takes(n, kSymmetricSvdMinSize, kSymmetricSvdMaxSize))  // Eigen above, in the engine
        benchmark::RegisterBenchmark(benchmark_name("BM_KernelSymmetricSvd", impl, n).c_str(),
                                     BM_KernelSymmetricSvd, impl, n);
      if (takes(n, kNullVectorMinSize, kNullVectorMaxSize))
        benchmark::RegisterBenchmark(benchmark_name("BM_KernelNullVector", impl, n).c_str(), BM_KernelNullVector,
                                     impl, n);
      if (takes(n, kNullVectorSeedMinSize, kNullVectorSeedMaxSize))
        benchmark::RegisterBenchmark(benchmark_name("BM_KernelNullVectorSeed", impl, n).c_str(),
                                     BM_KernelNullVectorSeed, impl, n);
      if (takes(n, kBezoutMatrixMinSize, kBezoutMatrixMaxSize))
        benchmark::RegisterBenchmark(benchmark_name("BM_KernelBezoutMatrix", impl, n).c_str(),
                                     BM_KernelBezoutMatrix, impl, n);
    }
  // Newton's method with its jets by de Casteljau (the fast path's), the off-curve path's Newton
  // kernel on Horner's jets, and the slope, at the pipeline's benchmark degrees.
  for (const Implementation* impl : available_implementations())
    for (int n : {2, 3, 4, 5, 6, 8, 15, 20}) {
      benchmark::RegisterBenchmark(benchmark_name("BM_KernelRationalNewton_casteljau", impl, n).c_str(),
                                   BM_KernelRationalNewton, impl, n);
      benchmark::RegisterBenchmark(benchmark_name("BM_KernelNearestNewton", impl, n).c_str(), BM_KernelNearestNewton,
                                   impl, n);
      benchmark::RegisterBenchmark(benchmark_name("BM_KernelRationalSlope", impl, n).c_str(), BM_KernelRationalSlope,
                                   impl, n);
    }
  // The formula path of a conic or a cubic in one kernel.
  for (const Implementation* impl : available_implementations())
    for (int n = kFormulaNewtonMinDegree; n <= kFormulaNewtonMaxDegree; ++n)
      benchmark::RegisterBenchmark(benchmark_name("BM_KernelFormulaNewton", impl, n).c_str(), BM_KernelFormulaNewton,
                                   impl, n);
  // The seed, B stored or formed, at every size around the engine's switch between them
  // (kFormedBMinDegree in engine/src/invert.cpp), where each is compiled.
  for (const Implementation* impl : available_implementations())
    for (int n : kSeedSizes) {
      if (takes(n, kNullVectorSeedMinSize, kNullVectorSeedMaxSize))
        benchmark::RegisterBenchmark(benchmark_name("BM_KernelBezoutSeed_stored", impl, n).c_str(),
                                     BM_KernelBezoutSeed, impl, n, false);
      if (takes(n, kBezoutNullVectorSeedMinSize, kBezoutNullVectorSeedMaxSize))
        benchmark::RegisterBenchmark(benchmark_name("BM_KernelBezoutSeed_formed", impl, n).c_str(),
                                     BM_KernelBezoutSeed, impl, n, true);
    }
  return 0;
}
const int registered = register_kernels();

BENCHMARK_TEMPLATE(BM_KernelEigenSelfAdjoint, 3);
BENCHMARK_TEMPLATE(BM_KernelEigenSelfAdjoint, 5);
BENCHMARK_TEMPLATE(BM_KernelEigenSelfAdjoint, 8);
BENCHMARK_TEMPLATE(BM_KernelEigenSelfAdjoint, 15);
BENCHMARK_TEMPLATE(BM_KernelEigenSelfAdjoint, 20);
BENCHMARK_TEMPLATE(BM_KernelEigenSelfAdjoint, 24);

}  // namespace
