// bench_simview_main.cpp - holotrace-bench-simview: direct per-subpixel rays vs the quilt path, as a viewer sees them.
// One scene on a lenticular display, rendered directly and through the display's quilt cameras (interleaved with the
// vendor lerp and the centred lerp, camera_models/quilt_interleave.h); both panels are seen by the simulated viewer
// (camera_models/simulated_view.h) from --eyes positions across the view cone, and each simulated view is compared
// with a pinhole render of the scene from that eye (a ray table from the eye through every output pixel's point on
// the focal rectangle, rendered at the same spp). PSNR and SSIM on display-referred values (bench/image_metrics.h).
// All renders are deterministic (fixed seed), so one run gives the table; times are informational.
#include <array>
#include <chrono>
#include <cstdio>
#include <iostream>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "bench/bench_main.h"
#include "bench/image_metrics.h"
#include "camera_models/display_config.h"
#include "camera_models/lenticular_params.h"
#include "camera_models/quilt_interleave.h"
#include "camera_models/ray_table.h"
#include "camera_models/simulated_view.h"
#include "cli/arguments.h"
#include "common/error.h"
#include "common/parallel_chunks.h"
#include "gpu/display_camera.h"
#include "gpu/renderer.h"
#include "gpu/vulkan_context.h"
#include "scene/scene.h"

namespace ht::bench {
namespace {

const char* const kCommand = "holotrace-bench-simview";

struct SimviewOptions {
  std::string display = "builtin:portrait";
  std::string scene = "builtin:plain";
  std::uint32_t spp = 4, eyes = 9;
  int deviceIndex = -1;
};

const std::array<cli::OptionSpec, 5> kSpecs = {{
    {"--display", "", "SPEC", "lenticular display (default builtin:portrait)"},
    {"--scene", "", "SPEC", "scene (default builtin:plain)"},
    {"--spp", "", "N", "samples per subpixel / quilt pixel / reference pixel (default 4)"},
    {"--eyes", "", "N", "eye positions across the view cone (default 9)"},
    {"--device", "", "N", "Vulkan device index (default: automatic)"},
}};

std::optional<SimviewOptions> parse(std::span<const std::string> args, std::string* help) {
  if (cli::wantsHelp(args)) {
    *help = std::string("Usage: ") + kCommand + " [options]\n\nPSNR/SSIM of simulated views of the direct and the " +
            "quilt-interleaved panel against pinhole renders from each eye.\n\nOptions:\n" + cli::formatOptions(kSpecs);
    return std::nullopt;
  }
  const cli::ParsedArguments parsed = cli::parseArguments(kCommand, kSpecs, args);
  SimviewOptions o;
  o.display = parsed.textOr("--display", o.display);
  o.scene = parsed.textOr("--scene", o.scene);
  o.spp = parsed.unsignedValue("--spp", 1, 1024).value_or(o.spp);
  o.eyes = parsed.unsignedValue("--eyes", 1, 64).value_or(o.eyes);
  if (auto device = parsed.unsignedValue("--device", 0, 255)) o.deviceIndex = int(*device);
  return o;
}

double secondsSince(std::chrono::steady_clock::time_point start) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

// The ray table of a pinhole at `eye` (display-local) through the centre of every panel pixel on the focal rectangle.
std::shared_ptr<RayTable> eyeTable(const gpu_shared::LenticularParams& p, glm::dvec3 eye) {
  auto table = std::make_shared<RayTable>();
  table->width = std::uint32_t(p.panel.x);
  table->height = std::uint32_t(p.panel.y);
  const glm::dmat4 toWorld(p.localToWorld);
  const glm::dvec3 eyeWorld(toWorld * glm::dvec4(eye, 1.0));
  const double size = p.camera.y, aspect = p.camera.z;
  for (std::uint32_t y = 0; y < table->height; ++y) {
    for (std::uint32_t x = 0; x < table->width; ++x) {
      const glm::dvec3 local(((x + 0.5) / table->width - 0.5) * aspect * size, ((y + 0.5) / table->height - 0.5) * size,
                             0.0);
      const glm::dvec3 world(toWorld * glm::dvec4(local, 1.0));
      table->origins.push_back(glm::vec3(eyeWorld));
      table->directions.push_back(glm::vec3(glm::normalize(world - eyeWorld)));
    }
  }
  return table;
}

int run(const SimviewOptions& o) {
  const auto start = std::chrono::steady_clock::now();
  const DisplayConfig display = resolveDisplay(o.display);
  const Scene scene = loadScene(o.scene);
  gpu::VulkanContext context({o.deviceIndex, false});
  gpu::Renderer renderer(context, scene);
  gpu::RenderSettings settings;
  settings.spp = o.spp;

  const gpu::DisplayCamera direct = gpu::makeDisplayCamera(display, scene.bounds());
  const auto& params = std::get<gpu_shared::LenticularParams>(direct.camera);
  const std::vector<float> directPanel = renderer.render(direct.camera, settings).rgba;
  const gpu::DisplayCamera quiltCamera = gpu::makeDisplayCamera(display, scene.bounds(), gpu::CameraPath::Quilt);
  const gpu::RenderResult quilt = renderer.render(quiltCamera.camera, settings);
  const QuiltViews views = viewStackViews(quilt.width, quilt.height, quilt.views, quilt.rgba);
  const unsigned threads = hardwareThreads();
  const std::vector<float> vendorPanel = interleaveQuilt(views, params, QuiltViewFilter::VendorLerp, threads);
  const std::vector<float> centredPanel = interleaveQuilt(views, params, QuiltViewFilter::CentredLerp, threads);
  std::fprintf(stderr, "rendered direct + quilt %ux%u x %u views in %.1f s\n", quilt.width, quilt.height, quilt.views,
               secondsSince(start));

  const auto w = std::uint32_t(params.panel.x), h = std::uint32_t(params.panel.y);
  std::printf(
      "| eye | x / D | direct PSNR | quilt vendor lerp PSNR | quilt centred lerp PSNR | direct SSIM | "
      "vendor SSIM | centred SSIM |\n|---|---|---|---|---|---|---|---|\n");
  std::uint32_t index = 0;
  for (const glm::dvec3& eye : lenticularViewConeEyes(params, o.eyes)) {
    const auto table = eyeTable(params, eye);
    const gpu::RayTableCamera camera{makeRayTableParams(parseDisplayConfig(
                                                            R"({"name": "eye", "model": "ray-table", "rayTable":
                                                            {"file": "eye.exr"}, "camera": {"target": [0, 0, 0]}})",
                                                            "eye.json", ""),
                                                        *table, scene.bounds()),
                                     table};
    const std::vector<float> reference = renderer.render(camera, settings).rgba;
    auto seen = [&](const std::vector<float>& panel) {
      return compareImages(simulateLenticularView(params, panel, eye, threads).rgba, reference, w, h);
    };
    const ImageMetrics d = seen(directPanel), v = seen(vendorPanel), c = seen(centredPanel);
    std::printf("| %u | %+.3f | %.2f | %.2f | %.2f | %.4f | %.4f | %.4f |\n", index++, eye.x / eye.z, d.psnrDb,
                v.psnrDb, c.psnrDb, d.ssim, v.ssim, c.ssim);
    std::fflush(stdout);
  }
  std::fprintf(stderr, "total %.1f s\n", secondsSince(start));
  return 0;
}

}  // namespace
}  // namespace ht::bench

int main(int argc, char** argv) {
  return ht::bench::benchMain(argc, argv, ht::bench::kCommand, ht::bench::parse, ht::bench::run);
}
