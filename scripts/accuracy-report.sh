#!/usr/bin/env bash
# accuracy-report.sh - build bench/accuracy_report and regenerate docs/ACCURACY.md with the big runs of the
# accuracy suite (>= 10M watertight rays per closed mesh; about 10 minutes on 2 cores with lavapipe).
#   scripts/accuracy-report.sh [--rays-per-mesh N] [--differential-rays N] [--device N]
# BUILD_DIR (default build-accuracy) is configured in Release if it does not exist.
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
build="${BUILD_DIR:-$root/build-accuracy}"
if [[ ! -f "$build/build.ninja" ]]; then
  cmake -S "$root" -B "$build" -G Ninja -DCMAKE_BUILD_TYPE=Release
fi
cmake --build "$build" --target holotrace-accuracy-report -j "$(nproc)"
if [[ -z "${VK_ICD_FILENAMES:-}" && -f /usr/share/vulkan/icd.d/lvp_icd.x86_64.json ]] && ! command -v nvidia-smi >/dev/null; then
  export VK_ICD_FILENAMES=/usr/share/vulkan/icd.d/lvp_icd.x86_64.json  # no GPU: lavapipe, as in CI
fi
cd "$root"
"$build/bench/accuracy_report/holotrace-accuracy-report" --output docs/ACCURACY.md "$@"
