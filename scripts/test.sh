#!/usr/bin/env bash
# README command 2: set up, build, and run every test -- once in Release, once under
# AddressSanitizer + UndefinedBehaviorSanitizer (both GCC). The fuzz targets: scripts/fuzz.sh.
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/setup.sh
source scripts/generator.sh
jobs="$(nproc)"

# Options are passed explicitly: build/ may hold a cache from scripts/demo.sh (tests off) or
# scripts/bench.sh (benchmarks on: no test runs them, and building them here only costs time).
# Kernels for scalar and the instruction sets this machine runs (a kernel it cannot run, it cannot
# test); the installed and benchmarked trees compile them all.
cmake $(generator_args build) -S . -B build -DCMAKE_BUILD_TYPE=Release -DBEZINV_SANITIZE=OFF -DBEZINV_BUILD_TESTS=ON -DBEZINV_BUILD_BENCH=OFF -DBEZINV_KERNEL_TARGETS=native -DBEZINV_PYTHON=ON >/dev/null
cmake --build build -j"$jobs"
(cd build && ctest --output-on-failure --no-tests=error -j"$jobs")

# -O1 -g1: enough for the sanitizers, and quicker to compile than -O2 -g.
# Kernels for scalar and this machine's instruction sets, as above.
cmake $(generator_args build-sanitize) -S . -B build-sanitize -DCMAKE_BUILD_TYPE=Debug -DCMAKE_CXX_FLAGS_DEBUG="-O1 -g1" -DBEZINV_SANITIZE=ON -DBEZINV_BUILD_TESTS=ON -DBEZINV_BUILD_BENCH=OFF -DBEZINV_KERNEL_TARGETS=native >/dev/null
cmake --build build-sanitize -j"$jobs"
(cd build-sanitize && ASAN_OPTIONS=detect_leaks=1 UBSAN_OPTIONS=print_stacktrace=1 ctest --output-on-failure --no-tests=error -j"$jobs")
