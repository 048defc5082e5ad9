// traversal_options.cpp - see traversal_options.h.
#include "bench/traversal_options.h"

#include <algorithm>
#include <array>
#include <sstream>
#include <thread>

#include "cli/arguments.h"
#include "common/error.h"

namespace ht::bench {
namespace {

const char* const kCommand = "holotrace-bench-traversal";

const std::array<cli::OptionSpec, 11> kSpecs = {{
    {"--meshes", "", "LIST",
     "comma-separated meshes/scenes (default: bunny, assets/armadillo.off, "
     "assets/refined_elephant.off; scripts/fetch-meshes.sh)"},
    {"--size", "", "N", "N x N primary rays per mesh (default 1024)"},
    {"--runs", "", "N", "timed runs per tracer and ray set, interleaved, after one warm-up (default 5)"},
    {"--cost-stride", "", "N", "CPU traversal-cost counter uses every Nth ray (default 4)"},
    {"--seed", "", "N", "seed of the diffuse bounce directions (default 1)"},
    {"--quick", "", "", "smoke test: --size 128 --runs 3 (overridden by explicit --size/--runs)"},
    {"--device", "", "N", "Vulkan device index (default: automatic)"},
    {"--threads", "", "N", "Embree / CPU threads (default: all cores)"},
    {"--csv", "", "PREFIX", "write PREFIX_throughput.csv, PREFIX_bvh.csv and PREFIX_cost.csv"},
    {"--json", "", "PATH", "write every figure as JSON to PATH"},
    {"--fused-math", "", "", "let the driver fuse multiplies and adds (VulkanContext::Options::fusedFloatMath)"},
}};

const char* const kHelp =
    "Traversal throughput and BVH quality, holotrace vs Embree 3, on the same rays per mesh:\n"
    "  primary (closest), shadow (any hit, to a point light), diffuse (cosine bounce), mirror (reflection);\n"
    "  secondary rays start at the primary hits, offset with ht_offset_ray.\n"
    "Tracers: holotrace GPU kernel (Renderer::traceClosest/traceOccluded, GPU timestamp ms), Embree\n"
    "rtcIntersect1/rtcOccluded1 and rtcIntersect8/rtcOccluded8 on packets of 8 consecutive rays (wall ms).\n"
    "BVH quality: our binned-SAH builder vs Embree rtcBuildBVH (MEDIUM, binary, leaves <= 4, C_trav = C_int = 1):\n"
    "build ms, SAH cost, and node + triangle tests per ray from one CPU traversal of each tree.\n";

std::vector<std::string> splitList(const std::string& text) {
  std::vector<std::string> items;
  std::stringstream stream(text);
  for (std::string item; std::getline(stream, item, ',');) {
    if (item.empty()) throw UsageError(cli::usageMessage(kCommand, "--meshes has an empty entry"));
    items.push_back(item);
  }
  return items;
}

}  // namespace

std::optional<TraversalOptions> parseTraversalOptions(std::span<const std::string> args, std::string* helpText) {
  if (cli::wantsHelp(args)) {
    *helpText =
        std::string("Usage: ") + kCommand + " [options]\n\n" + kHelp + "\nOptions:\n" + cli::formatOptions(kSpecs);
    return std::nullopt;
  }
  const cli::ParsedArguments parsed = cli::parseArguments(kCommand, kSpecs, args);
  TraversalOptions o;
  o.meshes = splitList(parsed.textOr(
      "--meshes", "/usr/share/glmark2/models/bunny.obj,assets/armadillo.off,assets/refined_elephant.off"));
  const bool quick = parsed.has("--quick");
  o.size = parsed.unsignedValue("--size", 8, 8192).value_or(quick ? 128 : o.size);
  o.runs = parsed.unsignedValue("--runs", 1, 1000).value_or(quick ? 3 : o.runs);
  o.costStride = parsed.unsignedValue("--cost-stride", 1, 1u << 20).value_or(o.costStride);
  o.seed = parsed.unsignedValue("--seed", 0, 0xFFFFFFFFu).value_or(o.seed);
  if (auto device = parsed.unsignedValue("--device", 0, 255)) o.deviceIndex = int(*device);
  o.threads = parsed.unsignedValue("--threads", 1, 1024).value_or(std::max(1u, std::thread::hardware_concurrency()));
  o.csvPrefix = parsed.text("--csv");
  o.fusedFloatMath = parsed.has("--fused-math");
  o.jsonPath = parsed.text("--json");
  return o;
}

}  // namespace ht::bench
