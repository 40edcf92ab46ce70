#!/usr/bin/env bash
# Quick start, step 1 of 2: installs the Debian packages Talus needs, builds
# it in build/, and runs the default scene (a rock block sliding into water)
# with its output in out/, then renders a preview picture of the last frame.
set -euo pipefail
cd "$(dirname "$0")/.."

bash tools/setup.sh
cmake -S . -B build -DCMAKE_BUILD_TYPE=Release > build-configure.log || { cat build-configure.log; exit 1; }
echo "talus quickstart: building (2 cores: a few minutes the first time) ..."
cmake --build build -j "$(nproc)" > build.log 2>&1 || { tail -40 build.log; echo "talus quickstart: the build failed (build.log)"; exit 1; }
build/bin/talus run --out out/default
python=/usr/bin/python3   # Debian's, with numpy/matplotlib/h5py
[ -x "$python" ] || python=python3
if "$python" -c "import h5py, matplotlib" 2>/dev/null; then
  "$python" tools/preview.py out/default/block_impact.h5part -o out/default/preview.png &&
    echo "talus quickstart: picture of the last frame in out/default/preview.png"
fi
