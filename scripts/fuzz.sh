#!/usr/bin/env bash
# Builds the libFuzzer targets (tests/fuzz; clang, ASan + UBSan, the engine with
# -fsanitize=fuzzer-no-link) in build-fuzz and runs each from its seed corpus (README "Fuzzing").
#
#   bash scripts/fuzz.sh            # each target for 10 s, as ctest tests (label fuzz)
#   BEZINV_FUZZ_SECONDS=600 bash scripts/fuzz.sh
#
# Not part of scripts/test.sh: the instrumented clang tree is a third build of the whole engine.
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/setup.sh
source scripts/generator.sh
seconds="${BEZINV_FUZZ_SECONDS:-10}"
cmake $(generator_args build-fuzz) -S . -B build-fuzz -DCMAKE_CXX_COMPILER=clang++ -DCMAKE_BUILD_TYPE=Debug \
  -DCMAKE_CXX_FLAGS_DEBUG="-O1 -g1" -DBEZINV_SANITIZE=ON -DBEZINV_FUZZ=ON -DBEZINV_BUILD_TESTS=OFF \
  -DBEZINV_BUILD_BENCH=OFF -DBEZINV_INSTALL=OFF -DBEZINV_KERNEL_TARGETS=native -DBEZINV_FUZZ_SECONDS="$seconds" >/dev/null
cmake --build build-fuzz -j"$(nproc)" --target fuzz_curves_json fuzz_points_csv fuzz_points_npy fuzz_invert
(cd build-fuzz && ctest --output-on-failure --no-tests=error -L fuzz --timeout $((seconds + 120)))
