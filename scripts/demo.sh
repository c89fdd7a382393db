#!/usr/bin/env bash
# README command 1: set up, build, and run the main job on the built-in default
# (1,000,000 points on the paper's degree-15 Example 2 curve and on a cubic).
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/setup.sh
source scripts/generator.sh
cmake $(generator_args build) -S . -B build -DCMAKE_BUILD_TYPE=Release -DBEZINV_SANITIZE=OFF >/dev/null
cmake --build build -j"$(nproc)" --target bezinv
./build/bezinv demo "$@"
