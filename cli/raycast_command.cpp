#include "cli/raycast_command.h"

#include <array>
#include <chrono>

#include "cli/arguments.h"
#include "cli/cli_app.h"
#include "cli/rays_file.h"
#include "common/error.h"
#include "frame_io/atomic_output_file.h"
#include "gpu/renderer.h"
#include "gpu/vulkan_context.h"
#include "scene/scene.h"

namespace ht::cli {
namespace {

const std::array<OptionSpec, 5> kOptions = {{
    {"--scene", "", "SPEC", "scene: builtin:NAME, .gltf/.glb, .obj/.off (required)"},
    {"--rays", "", "PATH", "rays file: binary (.bin, any other extension) or .csv (required)"},
    {"--output", "-o", "PATH", "hits file, binary or .csv by extension (required)"},
    {"--any", "", "", "any-hit (occlusion) instead of closest hit"},
    {"--device", "", "N", "Vulkan device index (see `holotrace info`)"},
}};

std::string required(const ParsedArguments& args, const std::string& name) {
  auto value = args.text(name);
  if (!value || value->empty()) throw UsageError(usageMessage(args.command(), "missing " + name));
  return *value;
}

double msSince(std::chrono::steady_clock::time_point t0) {
  return std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
}

}  // namespace

std::string raycastHelp() {
  return "Usage: holotrace raycast --scene SPEC --rays RAYS -o HITS [--any] [--device N]\n\n"
         "Traces a batch of rays against the scene's BVH on the Vulkan device and writes one record per ray.\n"
         "Binary rays: 16-byte header \"HTRY\", u32 version 1, u64 count; per ray origin xyz, tmin, dir xyz, tmax\n"
         "(float32, little-endian). Binary hits: \"HTHT\", u16 version 1, u16 kind (0 closest, 1 any), u64 count;\n"
         "per ray t, triangle id (0xFFFFFFFF = miss), u, v (closest) or a u32 0/1 (any). CSV by the .csv\n"
         "extension: \"ox,oy,oz,tmin,dx,dy,dz,tmax\" in, \"t,triangle,u,v\" or \"occluded\" out.\n\nOptions:\n" +
         formatOptions(kOptions);
}

int runRaycast(std::span<const std::string> argv, std::ostream& out) {
  const ParsedArguments args = parseArguments("holotrace raycast", kOptions, argv);
  const std::string sceneSpec = required(args, "--scene");
  const std::string raysPath = required(args, "--rays");
  const std::string hitsPath = required(args, "--output");
  const auto device = args.unsignedValue("--device", 0, 255);
  frame_io::prepareOutputDirectory(hitsPath);  // fail before the work, not after it

  const auto rays = readRaysFile(raysPath);
  const Scene scene = loadScene(sceneSpec);
  gpu::VulkanContext context({device ? static_cast<int>(*device) : -1, false});
  gpu::Renderer renderer(context, scene);
  out << "scene: " << scene.name << ", " << scene.triangleCount() << " triangles; device " << context.device().name
      << "\n";
  const auto t0 = std::chrono::steady_clock::now();
  gpu::TraceStats stats;
  if (args.has("--any")) {
    const auto occluded = renderer.traceOccluded(rays, &stats);
    writeOcclusionFile(hitsPath, occluded);
  } else {
    const auto hits = renderer.traceClosest(rays, &stats);
    writeHitsFile(hitsPath, hits);
  }
  out << "traced " << rays.size() << (args.has("--any") ? " any-hit" : " closest-hit") << " rays in " << msSince(t0)
      << " ms (GPU " << stats.gpuMs << " ms) -> " << hitsPath << "\n";
  return kExitOk;
}

}  // namespace ht::cli
