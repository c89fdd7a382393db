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
source scripts/generator.sh
configure=$(cmake $(generator_args "$build") -S . -B "$build" -DCMAKE_BUILD_TYPE=Release -DBEZINV_SANITIZE=OFF -DBEZINV_BUILD_BENCH=ON -DBEZINV_BUILD_BASELINES=ON -DBEZINV_KERNEL_TARGETS=all)
if ! grep -q "bezinv baselines: OpenCASCADE ON, SISL ON" <<<"$configure"; then
  echo "bench: CMake did not find OpenCASCADE and SISL:" >&2
  grep "bezinv baselines" <<<"$configure" >&2 || true
  exit 1
fi
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

runs, noisy = {}, {}
for b in baselines["benchmarks"]:
    if "_noisy/" in b["name"] or "_mixed/" in b["name"]:  # name/degree/noise exponent
        name, degree, exponent = b["name"].rsplit("/", 2)
        noisy[(name, int(degree), int(exponent))] = b
        continue
    name, degree = b["name"].removesuffix("/real_time").rsplit("/", 1)  # UseRealTime adds /real_time
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
occt, sisl, paper, eigen = "BM_OCCT_ProjectPointOnCurve", "BM_SISL_ClosestPoint", "BM_Paper_recurrence_JacobiSVD", "BM_Eigen_SelfAdjoint_per_point"
one, two = "BM_Bezinv_refined", "BM_Bezinv_refined_2threads"
def ratio(a, b):
    return f"{a / b:.2f}×" if a == a and b == b and b > 0 else "-"
print(f"\nload average {baselines['context'].get('load_avg')}; points/s (1 thread unless noted); ratios are bezinv on 1 thread over the baseline")
print("| n | OCCT | SISL | paper's way | Eigen per point | bezinv 1 thread | bezinv 2 threads | ÷ OCCT | ÷ SISL | ÷ paper | ÷ Eigen | 2 threads ÷ 1 | fast path | agree OCCT / SISL / bezinv |")
print("|---|---|---|---|---|---|---|---|---|---|---|---|---|---|")
for n in sorted({n for (_, n) in runs}):
    o, s_, p_, e_, b1, b2 = (rate(x, n) for x in (occt, sisl, paper, eigen, one, two))
    fp = runs.get((one, n), {}).get("fast_path", float("nan"))
    print(f"| {n} | {si(o)} | {si(s_)} | {si(p_) if p_ == p_ else '-'} | {si(e_) if e_ == e_ else '-'} | {si(b1)} | {si(b2)} | "
          f"{ratio(b1, o)} | {ratio(b1, s_)} | {ratio(b1, p_)} | {ratio(b1, e_)} | {ratio(b2, b1)} | {100 * fp:.1f}% | "
          f"{agree(occt, n)} / {agree(sisl, n)} / {agree(one, n)} |")
print("\nOff the curve: points moved by Gaussian noise of sigma = noise x the diagonal per coordinate; 1 thread;")
print("agree: the answer's point at least as near as the point the noisy one was made from")
print("| n | noise | OCCT | SISL | bezinv | ÷ OCCT | ÷ SISL | fast path | by distance | agree OCCT / SISL / bezinv |")
print("|---|---|---|---|---|---|---|---|---|---|")
names = ("BM_OCCT_ProjectPointOnCurve_noisy", "BM_SISL_ClosestPoint_noisy", "BM_Bezinv_refined_noisy")
for n, e in sorted({(n, e) for (name, n, e) in noisy if name.endswith("_noisy")}, key=lambda k: (k[0], -k[1])):
    o, s_, b1 = (noisy.get((x, n, e), {}).get("items_per_second", float("nan")) for x in names)
    fp = noisy.get((names[2], n, e), {}).get("fast_path", float("nan"))
    bd = noisy.get((names[2], n, e), {}).get("by_distance", float("nan"))
    ag = " / ".join(f"{100 * noisy[(x, n, e)]['agree']:.2f}%" if (x, n, e) in noisy else "-" for x in names)
    print(f"| {n} | 1e-{e} | {si(o)} | {si(s_)} | {si(b1)} | {ratio(b1, o)} | {ratio(b1, s_)} | {100 * fp:.1f}% | "
          f"{100 * bd:.1f}% | {ag} |")
print("\nMixed batches: every other point on the curve, the others at the noise; 1 thread. 'apart' is the rate")
print("the two kinds would give inverted separately, half the points each: 2 / (1/on + 1/off)")
print("| n | noise | on the curve | off it | mixed | apart | mixed ÷ apart |")
print("|---|---|---|---|---|---|---|")
for n, e in sorted({(n, e) for (name, n, e) in noisy if name.endswith("_mixed")}, key=lambda k: (k[0], -k[1])):
    on, off = rate(one, n), noisy.get((names[2], n, e), {}).get("items_per_second", float("nan"))
    mixed = noisy.get(("BM_Bezinv_refined_mixed", n, e), {}).get("items_per_second", float("nan"))
    apart = 2 / (1 / on + 1 / off) if on == on and off == off else float("nan")
    print(f"| {n} | 1e-{e} | {si(on)} | {si(off)} | {si(mixed)} | {si(apart)} | {ratio(mixed, apart)} |")
print(f"\nfull results: {build}/bench-results.json")
EOF
