// traversal_options.h - options of holotrace-bench-traversal.
#pragma once
#include <cstdint>
#include <optional>
#include <span>
#include <string>
#include <vector>

namespace ht::bench {

struct TraversalOptions {
  std::vector<std::string> meshes;  // default: bunny + assets/armadillo.off + assets/refined_elephant.off
  std::uint32_t size = 1024;        // size x size primary rays per mesh
  std::uint32_t runs = 5;           // timed runs per tracer and ray set (interleaved), after one warm-up
  std::uint32_t costStride = 4;     // the CPU cost counter traces every Nth ray of each set
  std::uint32_t seed = 1;           // diffuse bounce directions
  int deviceIndex = -1;
  bool fusedFloatMath = false;           // --fused-math
  unsigned threads = 0;                  // Embree / CPU threads
  std::optional<std::string> csvPrefix;  // writes PREFIX_throughput.csv, PREFIX_bvh.csv, PREFIX_cost.csv
  std::optional<std::string> jsonPath;
};

// Returns nullopt after printing help (--help); throws UsageError for bad options.
std::optional<TraversalOptions> parseTraversalOptions(std::span<const std::string> args, std::string* helpText);

}  // namespace ht::bench
