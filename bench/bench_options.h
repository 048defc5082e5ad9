// bench_options.h - options of holotrace-bench-primary.
#pragma once
#include <cstdint>
#include <optional>
#include <span>
#include <string>

namespace ht::bench {

struct BenchOptions {
  std::uint32_t runs = 7;                                    // timed runs per tracer (after one warm-up)
  std::uint32_t size = 1024;                                 // image is size x size primary rays
  std::string mesh = "/usr/share/glmark2/models/bunny.obj";  // anything ht::loadScene reads
  int deviceIndex = -1;                                      // Vulkan device, -1 = automatic
  bool fusedFloatMath = false;                               // --fused-math
  unsigned threads = 0;                                      // Embree threads, 0 = all cores
  std::optional<std::string> jsonPath;                       // write the result as JSON here
};

// Returns nullopt after printing help (--help); throws UsageError for bad options.
std::optional<BenchOptions> parseBenchOptions(std::span<const std::string> args, std::string* helpText);

}  // namespace ht::bench
