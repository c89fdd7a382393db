// What this core can do at best, in the widest vectors it has (Highway's dynamic dispatch, as the
// kernels choose theirs): the ceilings against which BENCHMARKS.md reads the kernels' figures.
//   BM_Machine_Fma   a * x + c on 12 independent vectors: the FMA units' throughput
//   BM_Machine_Div   1.0000001 / x on 8 independent vectors: the divider's throughput
//   BM_Machine_Sqrt  sqrt(x) on 8 independent vectors
// items_per_second = lane operations per second (a vector of 8 doubles counts 8).
//   BM_Machine_Write / BM_Machine_Copy  memset / memcpy of 256 MiB: bytes_per_second of memory
//   BM_Machine_PointsToResults/T  the pipeline's memory traffic and nothing else: read a Point,
//                    write a PointResult (16 + 56 bytes), on T threads: the ceiling of any in-memory
//                    inversion that returns the whole record; items_per_second = points
//   BM_Machine_PointsToFreshResults/T/H  the same into memory the process has not touched before
//                    (mapped anew each iteration, as a new output buffer is), in 4 KiB pages (H = 0)
//                    or asking for 2 MiB pages (H = 1, madvise): what the first touch of each
//                    result row costs on top
#undef HWY_TARGET_INCLUDE
#define HWY_TARGET_INCLUDE "machine_bench.cpp"
#include <hwy/foreach_target.h>  // re-includes this file once per target
#include <hwy/highway.h>

#include <cstdint>

HWY_BEFORE_NAMESPACE();
namespace bezinv_bench::HWY_NAMESPACE {
namespace hn = hwy::HWY_NAMESPACE;

// Returns the lane operations done; `sink` keeps the results alive.
std::int64_t FmaChains(std::int64_t iterations, double* sink) {
  const hn::ScalableTag<double> d;
  const auto a = hn::Set(d, 0.9999999), c = hn::Set(d, 1e-9);
  auto x0 = hn::Set(d, 1.0), x1 = x0, x2 = x0, x3 = x0, x4 = x0, x5 = x0;
  auto x6 = x0, x7 = x0, x8 = x0, x9 = x0, x10 = x0, x11 = x0;
  for (std::int64_t k = 0; k < iterations; ++k) {
    x0 = hn::MulAdd(a, x0, c); x1 = hn::MulAdd(a, x1, c); x2 = hn::MulAdd(a, x2, c); x3 = hn::MulAdd(a, x3, c);
    x4 = hn::MulAdd(a, x4, c); x5 = hn::MulAdd(a, x5, c); x6 = hn::MulAdd(a, x6, c); x7 = hn::MulAdd(a, x7, c);
    x8 = hn::MulAdd(a, x8, c); x9 = hn::MulAdd(a, x9, c); x10 = hn::MulAdd(a, x10, c); x11 = hn::MulAdd(a, x11, c);
  }
  const auto sum = hn::Add(hn::Add(hn::Add(x0, x1), hn::Add(x2, x3)),
                           hn::Add(hn::Add(hn::Add(x4, x5), hn::Add(x6, x7)), hn::Add(hn::Add(x8, x9), hn::Add(x10, x11))));
  *sink += hn::GetLane(sum);
  return iterations * 12 * static_cast<std::int64_t>(hn::Lanes(d));
}

template <bool kDivide>
std::int64_t UnitChains(std::int64_t iterations, double* sink) {
  const hn::ScalableTag<double> d;
  const auto one = hn::Set(d, 1.0000001);
  auto x0 = hn::Set(d, 1.5), x1 = hn::Set(d, 2.5), x2 = hn::Set(d, 3.5), x3 = hn::Set(d, 4.5);
  auto x4 = hn::Set(d, 5.5), x5 = hn::Set(d, 6.5), x6 = hn::Set(d, 7.5), x7 = hn::Set(d, 8.5);
  auto step = [&](auto x) { return kDivide ? hn::Div(one, x) : hn::Sqrt(x); };
  for (std::int64_t k = 0; k < iterations; ++k) {
    x0 = step(x0); x1 = step(x1); x2 = step(x2); x3 = step(x3);
    x4 = step(x4); x5 = step(x5); x6 = step(x6); x7 = step(x7);
  }
  const auto sum = hn::Add(hn::Add(hn::Add(x0, x1), hn::Add(x2, x3)), hn::Add(hn::Add(x4, x5), hn::Add(x6, x7)));
  *sink += hn::GetLane(sum);
  return iterations * 8 * static_cast<std::int64_t>(hn::Lanes(d));
}
std::int64_t DivChains(std::int64_t iterations, double* sink) { return UnitChains<true>(iterations, sink); }
std::int64_t SqrtChains(std::int64_t iterations, double* sink) { return UnitChains<false>(iterations, sink); }

}  // namespace bezinv_bench::HWY_NAMESPACE
HWY_AFTER_NAMESPACE();

#if HWY_ONCE
#include <benchmark/benchmark.h>

#include <cstring>
#include <sys/mman.h>
#include <vector>

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>
#include <tbb/task_arena.h>

#include "bezinv/invert.hpp"

namespace bezinv_bench {
HWY_EXPORT(FmaChains);
HWY_EXPORT(DivChains);
HWY_EXPORT(SqrtChains);

namespace {

template <class F>
void run_chains(benchmark::State& state, F&& chains) {
  constexpr std::int64_t kIterations = 1 << 20;
  double sink = 0;
  std::int64_t operations = 0;
  for (auto _ : state) operations += chains(kIterations, &sink);
  benchmark::DoNotOptimize(sink);
  state.SetItemsProcessed(operations);
}

void BM_Machine_Fma(benchmark::State& state) { run_chains(state, HWY_DYNAMIC_DISPATCH(FmaChains)); }
void BM_Machine_Div(benchmark::State& state) { run_chains(state, HWY_DYNAMIC_DISPATCH(DivChains)); }
void BM_Machine_Sqrt(benchmark::State& state) { run_chains(state, HWY_DYNAMIC_DISPATCH(SqrtChains)); }

constexpr std::size_t kStreamBytes = std::size_t{256} << 20;

void BM_Machine_Write(benchmark::State& state) {
  std::vector<char> to(kStreamBytes, 1);
  int value = 0;
  for (auto _ : state) {
    std::memset(to.data(), ++value & 0x7f, to.size());
    benchmark::ClobberMemory();
  }
  state.SetBytesProcessed(static_cast<std::int64_t>(state.iterations() * kStreamBytes));
}

// Bytes read plus bytes written.
void BM_Machine_Copy(benchmark::State& state) {
  std::vector<char> from(kStreamBytes, 1), to(kStreamBytes, 2);
  for (auto _ : state) {
    std::memcpy(to.data(), from.data(), to.size());
    benchmark::ClobberMemory();
  }
  state.SetBytesProcessed(static_cast<std::int64_t>(2 * state.iterations() * kStreamBytes));
}

// A row per point, from the point and nothing else, in chunks of 2^16 over the arena's threads.
void write_rows(tbb::task_arena& arena, const std::vector<bezinv::Point>& points, bezinv::PointResult* results) {
  arena.execute([&] {
    tbb::parallel_for(tbb::blocked_range<std::size_t>(0, points.size(), 1 << 16), [&](const auto& range) {
      for (std::size_t i = range.begin(); i != range.end(); ++i) {
        bezinv::PointResult& r = results[i];
        r.t = points[i].x;
        r.residual = points[i].y;
        r.t2 = r.sigma_next = bezinv::PointResult::nan;
        r.sigma_min = points[i].x * points[i].y;
        r.status = bezinv::Status::ok;
        r.path = bezinv::Path::bezout_lu;
        r.reason = "";
      }
    });
  });
}

// 2^24 points (256 MiB in, 896 MiB out), on range(0) threads (a TBB arena, as the engine's).
void BM_Machine_PointsToResults(benchmark::State& state) {
  constexpr std::size_t kPoints = std::size_t{1} << 24;
  static std::vector<bezinv::Point> points(kPoints, bezinv::Point{0.25, 0.5});
  static std::vector<bezinv::PointResult> results(kPoints);
  tbb::task_arena arena(static_cast<int>(state.range(0)));
  for (auto _ : state) {
    write_rows(arena, points, results.data());
    benchmark::ClobberMemory();
  }
  state.SetItemsProcessed(static_cast<std::int64_t>(state.iterations() * kPoints));
}

// The rows of BM_Machine_PointsToResults written into pages mapped anew each iteration (2^22
// points, 224 MiB of rows; the mapping and its release timed too), on range(0) threads; range(1) = 1
// asks the kernel for transparent huge pages on them. On a virtual machine a page's first touch
// can cost more than the inversion of the points it holds (BENCHMARKS.md, "What limits each
// target"): an engine that writes into a buffer used before does not pay it.
void BM_Machine_PointsToFreshResults(benchmark::State& state) {
  constexpr std::size_t kPoints = std::size_t{1} << 22;
  constexpr std::size_t kBytes = kPoints * sizeof(bezinv::PointResult);
  static std::vector<bezinv::Point> points(kPoints, bezinv::Point{0.25, 0.5});
  tbb::task_arena arena(static_cast<int>(state.range(0)));
  for (auto _ : state) {
    void* mapped = mmap(nullptr, kBytes, PROT_READ | PROT_WRITE, MAP_PRIVATE | MAP_ANONYMOUS, -1, 0);
    if (mapped == MAP_FAILED) {
      state.SkipWithError("mmap failed");
      break;
    }
    if (state.range(1) == 1) madvise(mapped, kBytes, MADV_HUGEPAGE);
    auto* results = static_cast<bezinv::PointResult*>(mapped);
    write_rows(arena, points, results);
    benchmark::ClobberMemory();
    munmap(mapped, kBytes);
  }
  state.SetItemsProcessed(static_cast<std::int64_t>(state.iterations() * kPoints));
}

BENCHMARK(BM_Machine_Fma);
BENCHMARK(BM_Machine_Div);
BENCHMARK(BM_Machine_Sqrt);
BENCHMARK(BM_Machine_Write)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_Machine_Copy)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_Machine_PointsToResults)->Arg(1)->Arg(2)->UseRealTime()->Unit(benchmark::kMillisecond);
BENCHMARK(BM_Machine_PointsToFreshResults)
    ->Args({1, 0})
    ->Args({2, 0})
    ->Args({1, 1})
    ->Args({2, 1})
    ->UseRealTime()
    ->Unit(benchmark::kMillisecond);

}  // namespace
}  // namespace bezinv_bench
#endif  // HWY_ONCE
