#!/usr/bin/env bash
# Checks that this tree's `bezinv invert` writes the same bytes as another revision's on a large,
# varied corpus (tests/corpus/make_corpus.py): every output column, CSV and .npy, 1 and 2 threads,
# each BEZINV_KERNEL this CPU runs, the options that change the computation, and the error
# messages and exit codes of whole-file failures. Use it around any change meant to keep behaviour.
#
#   bash scripts/same_answers.sh [--within-accuracy] [REV]              # REV: default HEAD
#   bash scripts/same_answers.sh [--within-accuracy] --base-binary PATH # an already built bezinv
#
# --within-accuracy: result files may differ in the last bits of their numbers, within the accuracy
# bound (tests/corpus/compare_results.py: the same statuses, paths and reasons, numbers within
# 1e-9), for a change of method meant to give the same answers to the promised accuracy; error
# messages and exit codes must still be identical.
#
# It builds REV's bezinv (Release, every kernel target) in build-answers/<hash>/ (kept, so a
# second run is quick) and this tree's in build-answers/this/. Exit 0 when every output is identical; otherwise
# it lists the runs that differ and the first differing rows.
set -euo pipefail
cd "$(dirname "$0")/.."
root="$(pwd)"
jobs="$(nproc)"

base_binary=""
rev="HEAD"
within_accuracy=0
if [ "${1:-}" = "--within-accuracy" ]; then
  within_accuracy=1
  shift
fi
if [ "${1:-}" = "--base-binary" ]; then
  base_binary="$(realpath "$2")"
elif [ $# -ge 1 ]; then
  rev="$1"
fi

bash scripts/setup.sh
source scripts/generator.sh
configure() {  # source dir, build dir
  cmake $(generator_args "$2") -S "$1" -B "$2" -DCMAKE_BUILD_TYPE=Release -DBEZINV_SANITIZE=OFF -DBEZINV_BUILD_TESTS=OFF \
        -DBEZINV_BUILD_BENCH=OFF -DBEZINV_KERNEL_TARGETS=all >/dev/null
  cmake --build "$2" -j"$jobs" --target bezinv >/dev/null
}

if [ -z "$base_binary" ]; then
  hash="$(git rev-parse --short=12 "$rev^{commit}")"
  base_dir="$root/build-answers/$hash"
  if [ ! -x "$base_dir/build/bezinv" ]; then
    echo "same_answers: building $rev ($hash) in $base_dir" >&2
    rm -rf "$base_dir/src" && mkdir -p "$base_dir/src"
    git archive "$hash" | tar -x -C "$base_dir/src"
    configure "$base_dir/src" "$base_dir/build"
  fi
  base_binary="$base_dir/build/bezinv"
fi
echo "same_answers: building this tree in build-answers/this" >&2
configure "$root" "$root/build-answers/this"
this_binary="$root/build-answers/this/bezinv"

work="$(mktemp -d)"
trap 'rm -rf "$work"' EXIT
corpus="$work/corpus"
python3 tests/corpus/make_corpus.py "$corpus"

# run DIR BINARY NAME KERNEL OUT_EXT [invert arguments]: writes DIR/NAME.OUT_EXT (the results),
# NAME.err (stderr) and NAME.rc (the exit code). CURVES (default curves.json) names the curves file.
run() {
  local out_dir="$1" binary="$2" name="$3" kernel="$4" out_ext="$5"
  shift 5
  (cd "$corpus" && BEZINV_KERNEL="$kernel" "$binary" invert --curves "${CURVES:-curves.json}" "$@" \
     --out "$out_dir/$name.$out_ext" >/dev/null 2>"$out_dir/$name.err"; echo $? >"$out_dir/$name.rc") || true
}

kernels=(scalar avx2 avx512)
run_all() {  # binary, output dir
  local binary="$1" dir="$2"
  mkdir -p "$dir"
  for threads in 1 2; do
    for kernel in "${kernels[@]}"; do
      local tag="t$threads-$kernel"
      run "$dir" "$binary" "csv-csv-$tag" "$kernel" csv --points points.csv --threads "$threads"
      run "$dir" "$binary" "npy-npy-$tag" "$kernel" npy --points points.npy --curve-index curve-index.npy --threads "$threads"
      run "$dir" "$binary" "csv-npy-$tag" "$kernel" npy --points points.csv --threads "$threads"
      run "$dir" "$binary" "npy-csv-$tag" "$kernel" csv --points points.npy --curve-index curve-index.npy --threads "$threads"
      run "$dir" "$binary" "no-refine-$tag" "$kernel" csv --points points.csv --threads "$threads" --no-refine
      run "$dir" "$binary" "svd-only-$tag" "$kernel" csv --points points.csv --threads "$threads" --svd-only
    done
  done
  run "$dir" "$binary" "tol-1e-3" avx2 csv --points points.csv --tol 1e-3
  run "$dir" "$binary" "tol-1e-12" avx2 csv --points points.csv --tol 1e-12
  run "$dir" "$binary" "small-chunks" avx2 csv --points points.csv --chunk-points 1000
  run "$dir" "$binary" "one-curve-npy" avx2 npy --points points.npy --curve bezier-15-0
  run "$dir" "$binary" "bad-row" avx2 csv --points bad-row.csv
  run "$dir" "$binary" "bad-number" avx2 csv --points bad-number.csv
  CURVES=bad-curves.json run "$dir" "$binary" "bad-curves" avx2 csv --points points.csv
  CURVES=bad-kind.json run "$dir" "$binary" "bad-kind" avx2 csv --points points.csv
}

run_all "$base_binary" "$work/base"
run_all "$this_binary" "$work/this"

# The binaries' paths appear in no output; the corpus path may (error messages name files), and it
# is the same for both runs.
different=0
count=0
within=0
for file in "$work/base"/*; do
  name="$(basename "$file")"
  count=$((count + 1))
  if [ ! -e "$work/this/$name" ]; then
    echo "same_answers: $name: written by $rev only" >&2; different=1; continue
  fi
  if ! cmp -s "$file" "$work/this/$name"; then
    if [ "$within_accuracy" -eq 1 ] && [[ "$name" == *.csv || "$name" == *.npy ]]; then
      if /usr/bin/python3 tests/corpus/compare_results.py "$file" "$work/this/$name" >"$work/compare.log"; then
        within=$((within + 1))
        continue
      fi
      different=1
      echo "same_answers: $name differs beyond the accuracy bound:" >&2
      head -12 "$work/compare.log" >&2
      continue
    fi
    different=1
    echo "same_answers: $name differs:" >&2
    case "$name" in
      *.csv|*.err|*.rc) diff "$file" "$work/this/$name" | head -6 >&2 || true ;;
      *) cmp "$file" "$work/this/$name" >&2 || true ;;
    esac
  fi
done
for file in "$work/this"/*; do
  [ -e "$work/base/$(basename "$file")" ] || { echo "same_answers: $(basename "$file"): written by this tree only" >&2; different=1; }
done
rows="$(($(wc -l <"$corpus/points.csv") - 1))"
if [ "$different" -ne 0 ]; then
  echo "same_answers: outputs differ from $rev (see above)" >&2
  exit 1
fi
if [ "$within" -gt 0 ]; then
  echo "same_answers: $count outputs ($rows points each run): $((count - within)) identical to $rev, $within within the accuracy bound"
else
  echo "same_answers: $count outputs ($rows points each run) identical to $rev"
fi
