#!/usr/bin/env bash
# bundle-bench.sh - the benchmark programs, the CLI and the shared libraries they need beyond glibc and the Vulkan
# loader, in one folder that travels to a GPU machine (issue 5: "runnable on an NVIDIA GPU machine too"):
#   scripts/bundle-bench.sh [DIR]          (default .bench-bundle/, git-ignored; ~50 MiB)
# There: DIR/run holotrace-bench-traversal --meshes DIR/assets/bunny.obj ...   (sets LD_LIBRARY_PATH; the SPIR-V
# kernels are embedded in the binaries). The Vulkan loader (libvulkan.so.1) and the NVIDIA ICD come from the GPU
# machine: where the loader is missing, copy Debian's libvulkan1 library into DIR/lib as well.
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
out="${1:-$root/.bench-bundle}"
build="${BUILD_DIR:-$root/build}"
programs=(bench/holotrace-bench-primary bench/holotrace-bench-traversal bench/holotrace-bench-raygen
          bench/holotrace-bench-skipping bench/holotrace-bench-quality bench/holotrace-bench-edits
          bench/holotrace-bench-bvh2 bench/holotrace-bench-encode)
# Not the CLI nor holotrace-bench-stream: through OpenImageIO and gRPC they need ~300 libraries (430 MiB).
# BUNDLE_TESTS=1: also the GPU and accuracy test programs (GoogleTest linked in), to run the CPU-reference parity
# tests on the GPU machine's driver (scripts/gpu-session.sh).
if [[ "${BUNDLE_TESTS:-0}" == 1 ]]; then
  programs+=(tests/gpu/ht_gpu_tests tests/gpu/ht_gpu_accumulation_tests tests/gpu/ht_gpu_reuse_tests
             tests/gpu/ht_gpu_two_level_tests tests/gpu/ht_frame_pin_tests tests/gpu/ht_simulated_view_render_tests
             tests/accuracy/AccuracyEmbreeDiffTest tests/accuracy/AccuracyWatertightTest
             tests/accuracy/AccuracyRaycastTest tests/accuracy/AccuracyDeterminismTest
             tests/accuracy/AccuracyOffsetRayGlslTest tests/accuracy/AccuracySelfIntersectionTest)
fi
for p in "${programs[@]}"; do
  [[ -x "$build/$p" ]] || { echo "bundle-bench.sh: $build/$p missing: build first (cmake --build $build)" >&2; exit 1; }
done
rm -rf "$out"
mkdir -p "$out/bin" "$out/lib" "$out/assets"
for p in "${programs[@]}"; do cp "$build/$p" "$out/bin/"; done
# Symbols are not needed to run them, and the bundle must travel within the device tool's 64 MiB.
strip --strip-unneeded "$out"/bin/*
# Every resolved library except glibc's own (libc, libm, libpthread, libdl, librt, the dynamic loader) and the Vulkan
# loader, which must be the GPU machine's to find its driver.
for p in "$out"/bin/*; do
  ldd "$p" | awk '$3 ~ /^\// {print $3}'
done | sort -u | while read -r lib; do
  case "$(basename "$lib")" in
    libc.so*|libm.so*|libpthread.so*|libdl.so*|librt.so*|ld-linux*|libvulkan.so*) ;;
    *) cp -L "$lib" "$out/lib/"; strip --strip-unneeded "$out/lib/$(basename "$lib")" ;;
  esac
done
[[ -f /usr/share/glmark2/models/bunny.obj ]] && cp /usr/share/glmark2/models/bunny.obj "$out/assets/"
for m in "$root"/assets/*.off; do [[ -f "$m" ]] && cp "$m" "$out/assets/"; done
# The display configs the programs default to (configs/, bench/configs/): run from DIR's parent or pass DIR/configs/...
mkdir -p "$out/configs" "$out/bench/configs"
cp "$root"/configs/*.json "$out/configs/"
cp "$root"/bench/configs/*.json "$out/bench/configs/"
cat > "$out/run" <<'RUN'
#!/usr/bin/env bash
# run PROGRAM [ARGS...]: one of bin/ with the bundled libraries first on the search path.
here="$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)"
prog="$1"; shift
LD_LIBRARY_PATH="$here/lib${LD_LIBRARY_PATH:+:$LD_LIBRARY_PATH}" exec "$here/bin/$prog" "$@"
RUN
chmod +x "$out/run"
echo "bundle-bench.sh: $(du -sh "$out" | cut -f1) in $out ($(ls "$out/lib" | wc -l) libraries)"
