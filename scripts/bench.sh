#!/usr/bin/env bash
# Rebuilds the benchmark programs and regenerates every benchmark CSV / JSON / PNG (docs/BENCHMARKS.md, issue 5):
#   holotrace-bench-traversal  primary/shadow/diffuse/mirror Mrays/s vs Embree 1- and 8-wide, BVH quality vs rtcBuildBVH
#   holotrace-bench-skipping   per-pass times, specialised pipeline vs forceAllFeatures
#   holotrace-bench-quality    ms/frame vs error, direct lenticular path vs quilt path, Portrait and 16" Gen3; direct
#                              path of an HPO projector array and an integral panel against a 256-spp reference
# Usage: scripts/bench.sh [--quick] [--build-dir DIR] [--out DIR] [--help]
#   --quick        CI smoke: tiny sizes and spp, a 384x512 test display; writes to out/bench-quick (seconds)
#   --build-dir D  CMake build folder (default build; configured Release without the service if missing)
#   --out DIR      output folder (default docs/bench, or out/bench-quick with --quick)
# Full run: about 15 min on 2 vCPUs with lavapipe. Uses $VK_ICD_FILENAMES as set (lavapipe:
# VK_ICD_FILENAMES=/usr/share/vulkan/icd.d/lvp_icd.x86_64.json). Needs gnuplot-nox and libcgal-demo
# (scripts/install-deps.sh) for the plots and meshes.
set -euo pipefail
root="$(cd "$(dirname "$0")/.." && pwd)"
quick=0; build="$root/build"; out=""
while [[ $# -gt 0 ]]; do
  case "$1" in
    --quick) quick=1 ;;
    --build-dir) build="$(realpath -m "${2:?--build-dir needs a folder}")"; shift ;;
    --out) out="$(realpath -m "${2:?--out needs a folder}")"; shift ;;
    -h|--help) sed -n '2,12p' "$0" | sed 's/^# \{0,1\}//'; exit 0 ;;
    *) echo "bench.sh: unknown option '$1' (try --help)" >&2; exit 2 ;;
  esac
  shift
done
[[ -n "$out" ]] || out="$root/$([[ $quick == 1 ]] && echo out/bench-quick || echo docs/bench)"
command -v gnuplot >/dev/null || { echo "bench.sh: gnuplot not found (apt-get install gnuplot-nox)" >&2; exit 1; }
cd "$root"
start=$(date +%s)

if [[ ! -f "$build/build.ninja" ]]; then
  cmake -S "$root" -B "$build" -G Ninja -DCMAKE_BUILD_TYPE=Release -DHOLOTRACE_BUILD_SERVICE=OFF
fi
ninja -C "$build" holotrace-bench-traversal holotrace-bench-quality holotrace-bench-skipping
"$root/scripts/fetch-meshes.sh"
mkdir -p "$out"
bin="$build/bench"

if [[ $quick == 1 ]]; then
  "$bin/holotrace-bench-traversal" --quick --csv "$out/traversal" --json "$out/traversal.json"
  "$bin/holotrace-bench-skipping" --quick --csv "$out/skipping.csv" --json "$out/skipping.json"
  "$bin/holotrace-bench-quality" --quick --displays bench/configs/quick-portrait.json --quilt-size 840x840 \
    --csv "$out/quality.csv" --summary-csv "$out/quality_summary.csv" --json "$out/quality.json"
else
  "$bin/holotrace-bench-traversal" --csv "$out/traversal" --json "$out/traversal.json" | tee "$out/traversal.txt"
  "$bin/holotrace-bench-skipping" --csv "$out/skipping.csv" --json "$out/skipping.json" | tee "$out/skipping.txt"
  "$bin/holotrace-bench-quality" --csv "$out/quality.csv" --summary-csv "$out/quality_summary.csv" \
    --json "$out/quality.json" | tee "$out/quality.txt"
  # The HPO projector array and the integral panel (reduced copies of the shipped ones, bench/configs/): direct path
  # only, against a 256-spp reference.
  "$bin/holotrace-bench-quality" --displays bench/configs/quality-hpo-14.json,bench/configs/quality-integral-960.json \
    --ref-spp 256 --spp 1,2,4,8,16,32 --csv "$out/quality_models.csv" --json "$out/quality_models.json" \
    | tee "$out/quality_models.txt"
fi
"$root/bench/plots/plot-bench.sh" "$out"
echo "bench.sh: wrote $out in $(( $(date +%s) - start )) s"
