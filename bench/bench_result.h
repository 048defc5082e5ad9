// bench_result.h - everything holotrace-bench-primary measured, printed as text and written as JSON.
#pragma once
#include <cstdint>
#include <ostream>
#include <string>

#include "bench/hit_comparison.h"
#include "bench/timing_series.h"

namespace ht::bench {

// Hit counts must agree to within this fraction (0.01 %).
inline constexpr double kHitCountTolerance = 1e-4;

struct QueryResult {
  TimingSeries gpu, embree;  // GPU: timestamp ms of the trace dispatches; Embree: wall ms
  HitComparison hits;        // A = holotrace GPU, B = Embree (last timed run)
  std::uint32_t gpuMaxSteps = 0;
};

struct BenchResult {
  std::string mesh;
  std::uint64_t triangles = 0;
  std::uint32_t width = 0, height = 0;
  std::uint32_t runs = 0;
  unsigned embreeThreads = 0;
  std::string device;
  double bvhBuildMs = 0.0, bvhSahCost = 0.0;
  std::uint64_t bvhNodes = 0;
  std::uint32_t bvhMaxDepth = 0;
  double embreeBuildMs = 0.0;
  std::string embreeVersion;
  QueryResult closest, occluded;

  std::uint64_t rays() const { return std::uint64_t(width) * height; }
  bool hitsAgree() const;
};

void printResult(std::ostream& out, const BenchResult& result);
// Writes the JSON document to `path` (via a temporary file). Throws IoError.
void writeResultJson(const std::string& path, const BenchResult& result);

}  // namespace ht::bench
