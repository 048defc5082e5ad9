// bench_raygen_main.cpp - holotrace-bench-raygen: ray generation alone, per camera model, on the chosen Vulkan device.
// For every shipped display (and the Portrait quilt cameras) the raygen kernel writes the primary rays of a fixed
// number of targets (GPU timestamp time of the raygen dispatches only, after a warm-up dispatch that JIT-compiles the
// kernel on lavapipe); medians of --runs runs at spp 1 and spp 4. Accuracy of the same rays: ht_gpu_tests
// GpuCameraRays.* (float GPU rays vs the double references).
//
// Usage: holotrace-bench-raygen [--runs N] [--targets N] [--device N]
#include <cstdio>
#include <exception>
#include <functional>
#include <iostream>
#include <string>
#include <vector>

#include "bench/timing_series.h"
#include "camera_models/display_config.h"
#include "common/error.h"
#include "gpu/display_camera.h"
#include "gpu/renderer.h"
#include "gpu/vulkan_context.h"
#include "scene/scene.h"

namespace ht::bench {
namespace {

struct RaygenOptions {
  std::uint32_t runs = 5;
  std::uint32_t targets = 1u << 20;
  int deviceIndex = -1;
};

std::uint32_t parseCount(const std::string& name, const std::string& value, std::uint32_t lo, std::uint32_t hi) {
  std::size_t used = 0;
  unsigned long n = 0;
  try {
    n = std::stoul(value, &used);
  } catch (const std::exception&) { used = 0; }
  if (used != value.size() || n < lo || n > hi) {
    throw UsageError("holotrace-bench-raygen: " + name + " = '" + value + "': expected an integer in [" +
                     std::to_string(lo) + ", " + std::to_string(hi) + "]");
  }
  return static_cast<std::uint32_t>(n);
}

RaygenOptions parseOptions(int argc, char** argv) {
  RaygenOptions o;
  for (int i = 1; i < argc; ++i) {
    const std::string a = argv[i];
    if (a == "--help" || a == "-h") {
      std::cout << "Usage: holotrace-bench-raygen [--runs N (5)] [--targets N (1048576)] [--device N]\n"
                   "Ray generation alone (no tracing) for every shipped display model: Mrays/s from GPU timestamps.\n";
      std::exit(0);
    }
    if (i + 1 >= argc) throw UsageError("holotrace-bench-raygen: option '" + a + "' needs a value (see --help)");
    const std::string v = argv[++i];
    if (a == "--runs")
      o.runs = parseCount(a, v, 1, 1000);
    else if (a == "--targets")
      o.targets = parseCount(a, v, 1024, 1u << 24);
    else if (a == "--device")
      o.deviceIndex = int(parseCount(a, v, 0, 255));
    else
      throw UsageError("holotrace-bench-raygen: unknown option '" + a + "' (see --help)");
  }
  return o;
}

// A 1920x1080 pinhole camera at 70 degrees, as a display config (no builtin display is a plain pinhole).
DisplayConfig pinholeCamera() {
  return parseDisplayConfig(R"({"name": "pinhole-1080p", "model": "pinhole",
      "pinhole": {"width": 1920, "height": 1080, "fovyDeg": 70}})",
                            "bench", "");
}

// Barrel distortion of a wide projector or camera lens (OpenCV convention; lens_distortion.h).
constexpr LensDistortionSettings kBarrelLens{-0.22, 0.05, 0.0, 0.0008, -0.0004};

struct Case {
  std::string label;
  std::function<DisplayConfig()> config;
  gpu::CameraPath path = gpu::CameraPath::Native;
};

Case builtinCase(const std::string& name, gpu::CameraPath path = gpu::CameraPath::Native) {
  return {name + (path == gpu::CameraPath::Quilt ? " --quilt" : ""), [name] { return builtinDisplay(name); }, path};
}

void runCase(gpu::Renderer& renderer, const Case& c, const RaygenOptions& o) {
  const DisplayConfig config = c.config();
  const gpu::DisplayCamera camera = gpu::makeDisplayCamera(config, Bounds3{}, c.path);
  const std::uint64_t frameTargets = camera.shape.targets();
  const auto targets = static_cast<std::uint32_t>(std::min<std::uint64_t>(o.targets, frameTargets));
  std::printf("%-30s %-16s", c.label.c_str(), std::string(displayModelName(config.model)).c_str());
  for (std::uint32_t spp : {1u, 4u}) {
    gpu::RenderSettings settings;
    settings.spp = spp;
    const std::uint64_t first = (frameTargets - targets) / 2;        // the middle of the frame
    renderer.generateRays(camera.camera, settings, first, targets);  // warm-up: JIT compile on lavapipe
    TimingSeries series;
    for (std::uint32_t r = 0; r < o.runs; ++r) {
      gpu::TraceStats stats;
      renderer.generateRays(camera.camera, settings, first, targets, &stats);
      series.ms.push_back(stats.gpuMs);
    }
    std::printf("  spp %u: %8.1f Mrays/s (%7.2f ms)", spp, series.medianMraysPerSecond(std::uint64_t(targets) * spp),
                series.medianMs());
  }
  std::printf("\n");
}

int run(int argc, char** argv) {
  const RaygenOptions o = parseOptions(argc, argv);
  gpu::VulkanContext context({o.deviceIndex, false});
  std::printf("device: %s\nray generation alone, %u targets from the middle of each frame, median of %u runs\n",
              context.device().name.c_str(), o.targets, o.runs);
  const Scene scene = loadScene("builtin:sphere");  // raygen traces nothing; the renderer still needs a scene
  gpu::Renderer renderer(context, scene);
  const std::vector<Case> cases = {builtinCase("portrait"),
                                   builtinCase("portrait", gpu::CameraPath::Quilt),
                                   builtinCase("gen3-16-landscape"),
                                   builtinCase("go"),
                                   builtinCase("holovizio-wall-70"),
                                   {"holovizio-wall-70 + lens",
                                    [] {
                                      DisplayConfig c = builtinDisplay("holovizio-wall-70");
                                      c.projectorArray->lens = ProjectorArrayConfig::Lens{
                                          1.1 * c.projectorArray->projectors[0].width, {}, kBarrelLens};
                                      return c;
                                    }},
                                   builtinCase("integral-15-4k"),
                                   builtinCase("capture-8x6"),
                                   builtinCase("capture-16x16"),
                                   builtinCase("oblique-9x9"),
                                   {"pinhole-1080p", pinholeCamera},
                                   {"pinhole-1080p + lens", [] {
                                      DisplayConfig c = pinholeCamera();
                                      c.pinhole.distortion = kBarrelLens;
                                      return c;
                                    }}};
  for (const Case& c : cases) runCase(renderer, c, o);
  return 0;
}

}  // namespace
}  // namespace ht::bench

int main(int argc, char** argv) {
  try {
    return ht::bench::run(argc, argv);
  } catch (const ht::UsageError& e) {
    std::cerr << e.what() << "\n";
    return 2;
  } catch (const std::exception& e) {
    std::cerr << "holotrace-bench-raygen: " << e.what() << "\n";
    return 1;
  }
}
