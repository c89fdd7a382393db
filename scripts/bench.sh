#!/usr/bin/env bash
# Runs every benchmark: bezinv's own suites (bench/invert_bench.cpp) and bezinv against
# OpenCASCADE and SISL (bench/baselines_bench.cpp), then prints the baselines table of BENCHMARKS.md.
# Installs what it needs (scripts/setup.sh, then the baseline libraries, Debian packages only).
#
#   bash scripts/bench.sh                      # build/ , results in build/bench-results.json
#   BEZINV_BUILD_DIR=build-bench bash scripts/bench.sh
#
# The JSON holds both binaries' runs: their "benchmarks" lists concatenated, the context (machine,
# load average, date) of the baselines run.
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/setup.sh

baselines=(libocct-modeling-algorithms-dev libocct-modeling-data-dev libocct-foundation-dev libsisl-dev python3)
missing=()
for p in "${baselines[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done
if [ ${#missing[@]} -gt 0 ]; then
  sudo=""
  [ "$(id -u)" -ne 0 ] && sudo="sudo"
  echo "bench: installing ${missing[*]}" >&2
  $sudo apt-get update -qq
  DEBIAN_FRONTEND=noninteractive $sudo apt-get install -y -qq --no-install-recommends "${missing[@]}" >/dev/null
fi

build="${BEZINV_BUILD_DIR:-build}"
cmake -S . -B "$build" -DCMAKE_BUILD_TYPE=Release -DBEZINV_SANITIZE=OFF -DBEZINV_BUILD_BENCH=ON -DBEZINV_BUILD_BASELINES=ON >/dev/null
# Fails here if CMake did not find OpenCASCADE or SISL (no bezinv_bench_baselines target).
cmake --build "$build" -j"$(nproc)" --target bezinv_bench bezinv_bench_baselines

uptime
flags=(--benchmark_min_time=0.5 --benchmark_out_format=json)
"$build/bench/bezinv_bench" "${flags[@]}" --benchmark_out="$build/bench-results-engine.json"
# SISL s1953 recurses deeper than the default 8 MiB stack on some degree-20 points (see the bench).
( ulimit -s unlimited && "$build/bench/bezinv_bench_baselines" "${flags[@]}" --benchmark_out="$build/bench-results-baselines.json" )

python3 - "$build" <<'EOF'
import json, sys
build = sys.argv[1]
engine = json.load(open(f"{build}/bench-results-engine.json"))
baselines = json.load(open(f"{build}/bench-results-baselines.json"))
merged = dict(baselines, benchmarks=engine["benchmarks"] + baselines["benchmarks"])
json.dump(merged, open(f"{build}/bench-results.json", "w"), indent=2)

runs = {}
for b in baselines["benchmarks"]:
    name, degree = b["name"].rsplit("/", 1)
    runs[(name, int(degree))] = b
def rate(name, n):
    b = runs.get((name, n))
    return b["items_per_second"] if b else float("nan")
def agree(name, n):
    b = runs.get((name, n))
    return f"{100 * b['agree']:.2f}%" if b else "-"
def si(x):
    for unit, scale in (("M", 1e6), ("k", 1e3)):
        if x >= scale: return f"{x / scale:.3g}{unit}/s"
    return f"{x:.3g}/s"
occt, sisl, ours = "BM_OCCT_ProjectPointOnCurve", "BM_SISL_ClosestPoint", "BM_Bezinv_refined"
print(f"\nload average {baselines['context'].get('load_avg')}, points/s per CPU second, 1 thread each")
print("| degree | OCCT | SISL | bezinv | bezinv ÷ OCCT | bezinv ÷ SISL | agree OCCT | agree SISL | agree bezinv |")
print("|---|---|---|---|---|---|---|---|---|")
for n in sorted({n for (_, n) in runs}):
    o, s, e = rate(occt, n), rate(sisl, n), rate(ours, n)
    print(f"| {n} | {si(o)} | {si(s)} | {si(e)} | {e / o:.2f}× | {e / s:.2f}× | "
          f"{agree(occt, n)} | {agree(sisl, n)} | {agree(ours, n)} |")
print(f"\nfull results: {build}/bench-results.json")
EOF
