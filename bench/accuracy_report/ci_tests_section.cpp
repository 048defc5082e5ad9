// ci_tests_section.cpp - see ci_tests_section.h. Keep the figures in step with the tests' printed counts.
#include "ci_tests_section.h"

namespace ht::accuracy::report {

std::string ciTestsSection() {
  return R"(## Hostile input (CI tests, not re-measured here)

`tests/accuracy/hostile_input_test.cpp`: zero-area, collinear, point, NaN- and Inf-vertex triangles are dropped and counted by the CPU build and the GPU renderer; each of the 8 ray fields set to NaN, +Inf, -Inf misses with at most 1 traversal step (tmin = -Inf with tmax = +Inf is a valid ray); 100,000 coincident triangles trip the traversal step limit as a GpuError. Determinism of the panel path: `tests/accuracy/determinism_test.cpp`.

`tests/accuracy/oversized_input_test.cpp`: inputs that claim huge sizes are refused with a SceneError/ConfigError naming the file, line or field, and the largest single heap allocation made while refusing is checked to stay below 16 MiB (measured: 8 KiB, the file stream buffer): an OFF header of 10^9 vertices and faces, an OFF face of 10^9 corners, OBJ face indices +-10^9 and 10^23, glTF POSITION and index accessors of 3*10^9 elements (10^9 triangles; refused from the accessor counts before any geometry is read), a NORMAL accessor of 10^9 elements with and without a bufferView, a GLB header claiming 4 GiB, a sparse 2,000,000,001-byte scene file (refused from its size, not read), and 100,000 x 100,000 panels in a visual.json (`screenW`), a pinhole config (`pinhole.width`) and an integral config (`integral.panelWidth`); the limits are 32,768 pixels per side and 50M triangles per scene.

## Self-intersection (CI tests, not re-measured here)

`tests/accuracy/self_intersection_test.cpp`, secondary rays spawned with `ht_offset_ray` (bvh/offset_ray.h, Ray Tracing Gems ch. 6): a tilted 16x16-quad plane and an icosphere-s4 (5,120 triangles) at scales 1e-3, 1e-1, 1, 1e2, 1e4, 1e6, each at the origin and translated 1000 sizes away (up to 1e9); 20,000 primary hits per case, hit points by barycentric interpolation, on the CPU reference and on the GPU (`traceClosest` for primaries and mirror rays, `traceOccluded` for shadow rays). Measured 2026-11-22 (Release, lavapipe), summed over CPU and GPU: **0 acne** in 624,312 samples that must be lit (plane: light on the viewer's side; sphere: light in front of the face plane, cos > 1e-3), and **0 mirror rays** (960,000) that hit anything, in particular their own triangle. The control, the same rays spawned from the hit point itself, shows acne in 306,126 and mirror self-hits in 471,328 of them. CPU and GPU counts are identical in every case.

Finding: the offset trades acne for light leaking near silhouettes when an object is small against its distance from the origin. Of the 335,300 sphere samples lit from behind their face (should be shadowed), 16-22 per case see the light at the origin for scales 0.1 ... 1e6 (lights just below the grazing cut), but 1,290-1,476 per case (about 10 %) when the sphere sits 1000 radii from the origin, and 1,561 at scale 1e-3 at the origin. In the first case `int_scale` = 256 ULPs of the coordinates is 1.5 % of the radius, and a point lifted by h above a sphere of radius R sees lights up to about sqrt(2h/R) = 10 degrees below its horizon; in the second the `float_scale` step n/65536 is absolute, 1.5 % of a radius of 1e-3. Not asserted; counted in the test's output.

`tests/accuracy/offset_ray_glsl_test.cpp`: `ht_offset_ray` compiled as GLSL (gpu/shaders/offset_ray_probe.comp, run by gpu/kernel_probe.h) and as C++ agree in every bit on 200,227 inputs (600,681 components, magnitudes 1e-30 ... 1e30 of both signs with random unit normals, the branch boundary |p| = 1/32, zeros, denormals with zero normal, FLT_MAX). The `precise` qualifier is not what makes them equal: the near-zero branch multiplies by 1/65536, a power of two, so the product is exact and `p + n/65536` is rounded once with or without FMA contraction (the test checks fma == unfused on every input: 0 differ). A probe that takes the other branch at |p| = 1/32 is caught (16 mismatching components).

## Fuzzing (CI, `scripts/fuzz.sh`)

libFuzzer targets built with clang 14, `-fsanitize=fuzzer,address,undefined` (CMake option `HOLOTRACE_FUZZ`, build-fuzz/): `fuzz_display_config` (parseDisplayConfig and the visual.json parser), `fuzz_scene_loader` (loadScene on .gltf/.glb/.obj/.off written to a private folder, as the daemon does with uploads) and `fuzz_quilt_name` (parseQuiltName, plus a format/parse round-trip property). Seeds: tests/fuzz/corpus/; the normal builds replay them as `FuzzCorpus*Test`. `scripts/test.sh` runs each target 30 s; leaks, timeouts (10 s) and RSS above 2 GiB are failures. Found and fixed: `formatQuiltName` wrote aspects >= 1e63 in exponent form, which `parseQuiltName` refuses (reproducer: tests/fuzz/corpus/quilt_name/regression_huge_aspect_round_trip).

)";
}

}  // namespace ht::accuracy::report
