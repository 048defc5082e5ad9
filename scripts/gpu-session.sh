#!/usr/bin/env bash
# gpu-session.sh - one prepared pass on a lent GPU machine (docs/BENCHMARKS.md "On an NVIDIA GPU"): the benchmark
# programs, then the GPU kernels' CPU-reference parity tests, each under its own time limit, within one deadline.
#   scripts/gpu-session.sh BUNDLE OUTDIR [DEADLINE_S]     (DEADLINE_S default 420)
# PARTS="tests fused_ab" (environment) picks and orders the parts; default "tests fused_ab recycle_ab benches".
# BUNDLE is a folder made by `BUNDLE_TESTS=1 scripts/bundle-bench.sh` (its run script sets the library path). Every
# program's output goes to OUTDIR/session.log; CSV and JSON files beside it. Run from the repository root (display
# configs are read from configs/ and bench/configs/). Steps are ordered by what matters most, so a short lease
# still yields the first ones; a step that outlives its limit is ended and the log says so.
set -uo pipefail
bundle="${1:?usage: gpu-session.sh BUNDLE OUTDIR [DEADLINE_S]}"
out="${2:?usage: gpu-session.sh BUNDLE OUTDIR [DEADLINE_S]}"
deadline="${3:-420}"
mkdir -p "$out"
log="$out/session.log"
run="$bundle/run"
assets="$bundle/assets"

# step LIMIT_S NAME PROGRAM ARGS...: runs one program for at most LIMIT_S seconds and what is left of the deadline.
step() {
  local limit="$1" name="$2"; shift 2
  local left=$((deadline - SECONDS))
  if ((left < 10)); then echo "=== $name: skipped, deadline reached" >>"$log"; return; fi
  ((limit > left)) && limit=$left
  echo "=== $name (limit ${limit} s, at ${SECONDS} s): $*" >>"$log"
  local t0=$SECONDS
  timeout --signal=KILL "$limit" "$run" "$@" >>"$log" 2>&1
  local rc=$?
  echo "=== $name: exit $rc after $((SECONDS - t0)) s" >>"$log"
}

{
  echo "date: $(date -u +%FT%TZ)"
  echo "cpu: $(grep -m1 'model name' /proc/cpuinfo | cut -d: -f2-) x $(nproc)"
  echo "isa: $(grep -m1 -o -w 'avx512f' /proc/cpuinfo || echo 'no avx512f'), $(grep -m1 -o -w 'avx2' /proc/cpuinfo)"
  nvidia-smi --query-gpu=name,driver_version,memory.total,clocks.max.sm --format=csv 2>&1
} >"$log"

bunny="$assets/bunny.obj"
meshes="$bunny,$assets/armadillo.off,$assets/refined_elephant.off"
tests() {
  for t in ht_gpu_tests ht_gpu_accumulation_tests ht_gpu_reuse_tests ht_gpu_two_level_tests ht_frame_pin_tests \
           ht_simulated_view_render_tests AccuracyEmbreeDiffTest AccuracyWatertightTest AccuracyRaycastTest \
           AccuracyDeterminismTest AccuracyOffsetRayGlslTest AccuracySelfIntersectionTest; do
    [[ -x "$bundle/bin/$t" ]] && step 90 "$t" "$t" --gtest_brief=1
  done
}
# Exact (the default: no contraction, exact divisions) against --fused-math, alternating, two pairs.
fused_ab() {
  for pair in 1 2; do
    step 30 "primary-exact-$pair" holotrace-bench-primary --mesh "$bunny"
    step 30 "primary-fused-$pair" holotrace-bench-primary --mesh "$bunny" --fused-math
  done
  step 40 traversal-exact holotrace-bench-traversal --meshes "$meshes" --cost-stride 64
  step 40 traversal-fused holotrace-bench-traversal --meshes "$meshes" --cost-stride 64 --fused-math
  step 30 edits-exact holotrace-bench-edits --runs 5 --node glow-sphere
  step 30 edits-fused holotrace-bench-edits --runs 5 --node glow-sphere --fused-math
}
# Frames that recycle their host buffer (the default) against a new buffer per frame: the time outside the GPU
# stages that the H200 run left unexplained (docs/BENCHMARKS.md "Host buffers of a frame loop").
recycle_ab() {
  for pair in 1 2; do
    step 30 "edits-recycled-$pair" holotrace-bench-edits --runs 5 --node glow-sphere --displays builtin:portrait
    step 30 "edits-fresh-$pair" holotrace-bench-edits --runs 5 --node glow-sphere --displays builtin:portrait \
      --fresh-buffers
  done
}
benches() {
  step 60 primary holotrace-bench-primary --mesh "$bunny" --json "$out/primary.json"
  step 120 traversal holotrace-bench-traversal --meshes "$meshes" --json "$out/traversal.json"
  # (--alternate-walks: the moved-instance walks of a partial re-render on and off in the same run, REUSE.md §4)
  step 60 edits-green holotrace-bench-edits --runs 8 --node green-sphere --alternate-walks
  # (--alternate-bounce-hits: the cached bounce hits on and off; the red box is seen through the glass sphere)
  step 60 edits-red holotrace-bench-edits --runs 8 --node red-box --alternate-bounce-hits
  step 45 edits-glow holotrace-bench-edits --runs 5 --node glow-sphere
  step 60 bvh2-gpu holotrace-bench-bvh2 --gpu --runs 5 --meshes "$meshes"
  step 30 skipping holotrace-bench-skipping --scenes "builtin:plain,$bunny,builtin:showcase"
  step 20 raygen holotrace-bench-raygen
  step 20 encode holotrace-bench-encode  # the frame encoding's threads on the device's 16 vCPUs
  step 150 quality holotrace-bench-quality --runs 5 --csv "$out/quality.csv" --summary-csv "$out/quality_summary.csv"
  # (--no-convex-skip: rays walk the convex node they leave, BVH.md §9.6; compare with edits-green's full frame)
  step 45 edits-green-walk-convex holotrace-bench-edits --runs 5 --node green-sphere --no-convex-skip
}
# PARTS: which of tests, fused_ab, recycle_ab, benches run, in the order given (default all four, most needed first).
for part in ${PARTS:-tests fused_ab recycle_ab benches}; do "$part"; done
echo "gpu-session.sh: done at ${SECONDS} s" >>"$log"
