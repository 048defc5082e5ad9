#!/usr/bin/env bash
# libFuzzer run (issue 4): configure + build the HOLOTRACE_FUZZ build (clang, ASan+UBSan, only ht_camera_models,
# ht_scene, ht_devices and tests/fuzz/), or, when $HOLOTRACE_FUZZ_BUILD_DIR is a configured clang sanitizer build
# (HOLOTRACE_SANITIZE=ON, as scripts/test.sh passes its ASan build), build the fuzz targets there; then fuzz each
# target for a fixed time starting from its seed corpus (tests/fuzz/corpus/<target>/; new inputs go to a scratch
# copy, the checked-in seeds are not changed).
# Exit status 1 on any crash, sanitizer report, leak, timeout or out-of-memory; reproducers are kept in
# $HOLOTRACE_FUZZ_BUILD_DIR (default build-fuzz)/artifacts/<target>/.
# fuzz_display_config also parses each input deeply nested and repeated to 1 MiB (tests/fuzz/fuzz_display_config.cpp),
# so nesting and length bugs are found although -max_len stays 64 KiB.
# Usage: bash scripts/fuzz.sh [seconds per target, default 30]
set -uo pipefail
ROOT="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
SECONDS_PER_TARGET="${1:-30}"
BUILD="${HOLOTRACE_FUZZ_BUILD_DIR:-$ROOT/build-fuzz}"
JOBS="${HOLOTRACE_JOBS:-2}"
TARGETS=(display_config scene_loader quilt_name hid_pages)
start=$(date +%s)

if ! command -v clang++ >/dev/null 2>&1; then
  echo "=== fuzz.sh: clang++ not found (Debian 12: apt-get install clang libclang-rt-14-dev)" >&2
  exit 1
fi
# -O1 -g1: the usual libFuzzer optimisation level; line numbers in reports.
configure=(cmake -S "$ROOT" -B "$BUILD" -G Ninja -DHOLOTRACE_FUZZ=ON -DCMAKE_BUILD_TYPE=RelWithDebInfo
           "-DCMAKE_CXX_FLAGS_RELWITHDEBINFO=-O1 -g1 -DNDEBUG")
if grep -q '^HOLOTRACE_SANITIZE:BOOL=ON' "$BUILD/CMakeCache.txt" 2>/dev/null; then
  configure=(true)  # the sanitizer build holds the fuzz targets already (tests/fuzz/CMakeLists.txt)
fi
echo "=== fuzz.sh: configure + build $BUILD"
if ! CC=clang CXX=clang++ "${configure[@]}" >/dev/null ||
   ! cmake --build "$BUILD" -j "$JOBS" --target "${TARGETS[@]/#/fuzz_}"; then
  echo "=== fuzz.sh: BUILD FAILED" >&2
  exit 1
fi

# Leaks are findings; UBSan stops at the first report (the build also uses -fno-sanitize-recover=undefined).
export ASAN_OPTIONS="${FUZZ_ASAN_OPTIONS:-detect_leaks=1:abort_on_error=1:symbolize=1}"
export UBSAN_OPTIONS="${FUZZ_UBSAN_OPTIONS:-print_stacktrace=1:halt_on_error=1}"
status=0
summary=()
for t in "${TARGETS[@]}"; do
  scratch="$BUILD/corpus/$t"; artifacts="$BUILD/artifacts/$t"; log="$BUILD/fuzz_$t.log"
  rm -rf "$artifacts"; mkdir -p "$scratch" "$artifacts"  # only this run's reproducers
  echo "=== fuzz.sh: fuzz_$t for ${SECONDS_PER_TARGET} s (log $log)"
  "$BUILD/tests/fuzz/fuzz_$t" "$scratch" "$ROOT/tests/fuzz/corpus/$t" -max_total_time="$SECONDS_PER_TARGET" \
      -timeout=10 -rss_limit_mb=2048 -max_len=65536 -print_final_stats=1 -artifact_prefix="$artifacts/" >"$log" 2>&1
  rc=$?
  runs=$(grep -o 'stat::number_of_executed_units: *[0-9]*' "$log" | grep -o '[0-9]*$' || true)
  cov=$(grep -o 'cov: [0-9]*' "$log" | tail -1 | grep -o '[0-9]*' || true)
  if ((rc == 0)); then
    summary+=("PASS  fuzz_$t  runs=${runs:-?} cov=${cov:-?}")
  else
    status=1
    finding=$(grep -m1 -E 'ERROR: (libFuzzer|AddressSanitizer|LeakSanitizer)|runtime error' "$log" | cut -c1-120 || true)
    summary+=("FAIL  fuzz_$t  rc=$rc ${finding:-see log}  reproducer: $(ls "$artifacts" | head -1)")
    tail -40 "$log" >&2
  fi
done

echo "=== fuzz.sh summary (${SECONDS_PER_TARGET} s per target)"
printf '  %s\n' "${summary[@]}"
echo "=== fuzz.sh: $( ((status == 0)) && echo 'no findings' || echo 'FINDINGS' ) in $(( $(date +%s) - start )) s"
exit "$status"
