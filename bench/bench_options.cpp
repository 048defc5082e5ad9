// bench_options.cpp - see bench_options.h.
#include "bench/bench_options.h"

#include <array>
#include <thread>

#include "cli/arguments.h"

namespace ht::bench {
namespace {

const char* const kCommand = "holotrace-bench-primary";

const std::array<cli::OptionSpec, 7> kSpecs = {{
    {"--runs", "", "N", "timed runs per tracer, interleaved, after one warm-up (default 7, at least 1)"},
    {"--size", "", "N", "trace N x N pinhole primary rays (default 1024)"},
    {"--mesh", "", "PATH", "mesh or scene to load (default /usr/share/glmark2/models/bunny.obj)"},
    {"--device", "", "N", "Vulkan device index (default: automatic, see `holotrace info`)"},
    {"--threads", "", "N", "Embree threads (default: all cores)"},
    {"--json", "", "PATH", "also write the result as JSON to PATH"},
    {"--fused-math", "", "", "let the driver fuse multiplies and adds (VulkanContext::Options::fusedFloatMath)"},
}};

}  // namespace

std::optional<BenchOptions> parseBenchOptions(std::span<const std::string> args, std::string* helpText) {
  if (cli::wantsHelp(args)) {
    *helpText = std::string("Usage: ") + kCommand +
                " [options]\n\nTraces the same pinhole primary rays with holotrace's GPU kernel "
                "(Renderer::traceClosest/traceOccluded,\nGPU timestamp time) and with Embree 3 "
                "rtcIntersect1/rtcOccluded1 (wall time, std::thread over tiles),\nand prints the median "
                "Mrays/s of both, their ratio and whether the hit counts agree.\n\nOptions:\n" +
                cli::formatOptions(kSpecs);
    return std::nullopt;
  }
  const cli::ParsedArguments parsed = cli::parseArguments(kCommand, kSpecs, args);
  BenchOptions options;
  options.runs = parsed.unsignedValue("--runs", 1, 1000).value_or(options.runs);
  options.size = parsed.unsignedValue("--size", 1, 8192).value_or(options.size);
  options.mesh = parsed.textOr("--mesh", options.mesh);
  if (auto device = parsed.unsignedValue("--device", 0, 255)) options.deviceIndex = int(*device);
  options.threads =
      parsed.unsignedValue("--threads", 1, 1024).value_or(std::max(1u, std::thread::hardware_concurrency()));
  options.jsonPath = parsed.text("--json");
  options.fusedFloatMath = parsed.has("--fused-math");
  return options;
}

}  // namespace ht::bench
