#!/usr/bin/env bash
# Installs a built bezinv into a temporary prefix, builds examples/ against that package only
# (find_package(bezinv CONFIG)), runs it on a tiny CURVES.json and checks the statuses it prints.
# Fails if the package is broken: a header or library not installed, a dependency the config file
# does not re-find, a target that does not link.
#
#   check_install.sh CMAKE BUILD_DIR SOURCE_DIR CXX_COMPILER BUILD_TYPE [CXX_FLAGS]
# CXX_FLAGS: extra compile and link flags for the example (the sanitizer build passes its own, as
# its static libraries need the sanitizer runtimes at link time).
set -euo pipefail
cmake="$1" build="$2" source="$3" cxx="$4" build_type="$5" flags="${6:-}"

work="$(mktemp -d)"
trap 'rm -rf "$work"' EXIT

"$cmake" --install "$build" --prefix "$work/prefix" >/dev/null
for f in include/bezinv/io.hpp include/bezinv/invert.hpp lib/cmake/bezinv/bezinv-config.cmake \
         lib/cmake/bezinv/bezinv-config-version.cmake bin/bezinv; do
  [ -e "$work/prefix/$f" ] || { echo "check_install: $f was not installed" >&2; exit 1; }
done

# The prefix is the only place bezinv can come from: the build tree is not on any path.
"$cmake" -S "$source/examples" -B "$work/build" -DCMAKE_PREFIX_PATH="$work/prefix" \
  -DCMAKE_CXX_COMPILER="$cxx" -DCMAKE_BUILD_TYPE="$build_type" \
  -DCMAKE_CXX_FLAGS="$flags" -DCMAKE_EXE_LINKER_FLAGS="$flags" >"$work/configure.log" 2>&1 \
  || { cat "$work/configure.log" >&2; exit 1; }
"$cmake" --build "$work/build" >"$work/build.log" 2>&1 || { cat "$work/build.log" >&2; exit 1; }
if grep -q "warning:" "$work/build.log"; then
  cat "$work/build.log" >&2
  echo "check_install: the example compiled with warnings" >&2
  exit 1
fi

# A quarter circle, exactly, as a rational quadratic.
cat >"$work/curves.json" <<'JSON'
{"curves": [{"id": "arc", "kind": "rational_bezier",
             "points": [[1, 0], [1, 1], [0, 1]], "weights": [1, 0.7071067811865476, 1]}]}
JSON
"$work/build/invert_points" "$work/curves.json" | tee "$work/out.txt"

# Four points made on the curve, then one off it, in that order.
statuses="$(sed -n 's/.*status = \([a-z_]*\).*/\1/p' "$work/out.txt" | tr '\n' ' ')"
if [ "$statuses" != "ok ok ok ok off_curve " ]; then
  echo "check_install: expected statuses 'ok ok ok ok off_curve', got '$statuses'" >&2
  exit 1
fi
# And the on-curve points get their parameters back.
ts="$(sed -n 's/.*t = \([^ ]*\) .*/\1/p' "$work/out.txt" | head -4 | tr '\n' ' ')"
if ! awk -v got="$ts" 'BEGIN { n = split(got, t, " "); split("0 0.25 0.5 1", want, " ");
                              if (n != 4) exit 1;
                              for (i = 1; i <= 4; i++) { d = t[i] - want[i]; if (d < -1e-9 || d > 1e-9) exit 1 } }'; then
  echo "check_install: expected t = 0 0.25 0.5 1 for the on-curve points, got '$ts'" >&2
  exit 1
fi
echo "check_install: the installed package builds and runs the example"
