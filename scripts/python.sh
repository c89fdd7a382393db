#!/usr/bin/env bash
# Builds the Python module into build/python (README "Python"): installs what it needs from
# Debian (scripts/setup.sh, then numpy, pybind11, pytest, dask), configures the Release tree with
# -DBEZINV_PYTHON=ON and builds the module and the command.
#
#   bash scripts/python.sh && PYTHONPATH=build/python /usr/bin/python3 -c 'import bezinv'
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/setup.sh
source scripts/generator.sh
cmake $(generator_args build) -S . -B build -DCMAKE_BUILD_TYPE=Release -DBEZINV_PYTHON=ON >/dev/null
cmake --build build -j"$(nproc)" --target bezinv_python bezinv
echo "python: import bezinv with PYTHONPATH=$(pwd)/build/python /usr/bin/python3" >&2
