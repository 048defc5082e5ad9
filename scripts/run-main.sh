#!/usr/bin/env bash
# The main job: install the Debian packages, build holotrace (Release, Ninja, into build/), and render the
# default frame (Looking Glass Portrait panel, builtin:showcase scene) to out/portrait_showcase.{png,exr}.
# Usage (from anywhere, as root): bash scripts/run-main.sh [extra `holotrace render` options]
set -euo pipefail
ROOT="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
cd "$ROOT"
start_ns=$(date +%s%N)

bash scripts/install-deps.sh

JOBS="${HOLOTRACE_JOBS:-$(nproc)}"
cmake -S . -B build -G Ninja -DCMAKE_BUILD_TYPE=Release
cmake --build build --target holotrace -j "$JOBS"

# Defaults: --display builtin:portrait --scene builtin:showcase, outputs in out/ (see `holotrace render --help`).
build/cli/holotrace render "$@"

elapsed_ms=$(( ($(date +%s%N) - start_ns) / 1000000 ))
echo
echo "run-main.sh: outputs in $ROOT/out/:"
ls -l out/
printf 'run-main.sh: total %d.%01d s (install + configure + build + render)\n' $((elapsed_ms / 1000)) $((elapsed_ms % 1000 / 100))
