#!/usr/bin/env bash
# Quick start, step 2 of 2: builds (if needed) and runs the whole test suite:
# unit tests, validation cases at low resolution, the out-of-tree plugin
# check and the quick verification report. Extra arguments go to ctest
# (e.g. -L unit, -R Poiseuille).
set -euo pipefail
cd "$(dirname "$0")/.."

bash tools/setup.sh
cmake -S . -B build -DCMAKE_BUILD_TYPE=Release > build-configure.log || { cat build-configure.log; exit 1; }
cmake --build build -j "$(nproc)" > build.log 2>&1 || { tail -50 build.log; exit 1; }
# Tests run two at a time, each single-threaded unless it asks for threads.
cd build
OMP_NUM_THREADS=${OMP_NUM_THREADS:-1} ctest --output-on-failure -j "$(nproc)" --timeout 900 "$@"
