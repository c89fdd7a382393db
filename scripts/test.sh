#!/usr/bin/env bash
# README command 2: set up, build, and run every test (the Python module's suite included) in one
# tree under AddressSanitizer + UndefinedBehaviorSanitizer (GCC), the fuzz targets for a few
# seconds each with a blind mutation driver (coverage-guided, with clang: scripts/fuzz.sh).
#
#   bash scripts/test.sh             # the sanitizer tree (build-sanitize)
#   bash scripts/test.sh --release   # then the Release tree too (build), where the property tests
#                                    # draw all their cases (tests/support/sanitizers.hpp)
#
# One tree rather than two halves the time this takes. The sanitizers see every code path of
# bezinv's that the Release tree runs (the test files and the Python bindings are compiled without
# them: tests/CMakeLists.txt says why), and the answers are the same bits at both optimization
# levels (no -ffast-math; no contraction into fused multiply-add where bits are compared).
set -euo pipefail
cd "$(dirname "$0")/.."
release=0
case "${1:-}" in
  "") ;;
  --release) release=1 ;;
  *) echo "usage: bash scripts/test.sh [--release]" >&2; exit 2 ;;
esac
bash scripts/setup.sh
source scripts/generator.sh
jobs="$(nproc)"

# Options are passed explicitly: a tree configured before keeps its cache (build/ may hold
# scripts/demo.sh's or scripts/bench.sh's). Kernels for scalar and the instruction sets this
# machine runs (a kernel it cannot run, it cannot test); the installed and benchmarked trees
# compile them all. No benchmarks: no test runs them. -O1 -g1: enough for the sanitizers, and
# quicker to compile than -O2 -g.
cmake $(generator_args build-sanitize) -S . -B build-sanitize -DCMAKE_BUILD_TYPE=Debug -DCMAKE_CXX_FLAGS_DEBUG="-O1 -g1" \
      -DBEZINV_SANITIZE=ON -DBEZINV_BUILD_TESTS=ON -DBEZINV_BUILD_BENCH=OFF -DBEZINV_KERNEL_TARGETS=native \
      -DBEZINV_PYTHON=ON >/dev/null
cmake --build build-sanitize -j"$jobs"
(cd build-sanitize && ASAN_OPTIONS=detect_leaks=1 UBSAN_OPTIONS=print_stacktrace=1 ctest --output-on-failure --no-tests=error -j"$jobs")

if [ "$release" = 1 ]; then
  cmake $(generator_args build) -S . -B build -DCMAKE_BUILD_TYPE=Release -DBEZINV_SANITIZE=OFF -DBEZINV_BUILD_TESTS=ON \
        -DBEZINV_BUILD_BENCH=OFF -DBEZINV_KERNEL_TARGETS=native -DBEZINV_PYTHON=ON >/dev/null
  cmake --build build -j"$jobs"
  (cd build && ctest --output-on-failure --no-tests=error -j"$jobs")
fi
