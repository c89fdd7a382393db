#!/usr/bin/env bash
# Installs what bezinv needs to build, test and benchmark, from Debian packages only.
# Safe to run again: apt-get skips what is already there.
set -euo pipefail
packages=(g++ cmake make ninja-build git pkg-config
          libeigen3-dev libtbb-dev nlohmann-json3-dev libcli11-dev
          libgtest-dev libgmock-dev libbenchmark-dev libgmp-dev libmpfr-dev
          libhwy-dev python3
          python3-dev pybind11-dev python3-numpy python3-pytest  # the Python module and its tests
          python3-dask python3-distributed                       # bezinv.dask and its LocalCluster test
          clang libclang-rt-dev  # the libFuzzer targets (scripts/fuzz.sh)
          chromium-headless-shell)  # the stress report rendered in a real browser (tests/cli/cli_stress_test.cpp)
missing=()
for p in "${packages[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done
if [ ${#missing[@]} -gt 0 ]; then
  sudo=""
  [ "$(id -u)" -ne 0 ] && sudo="sudo"
  echo "setup: installing ${missing[*]}" >&2
  $sudo apt-get update -qq
  DEBIAN_FRONTEND=noninteractive $sudo apt-get install -y -qq --no-install-recommends "${missing[@]}" >/dev/null
fi
