// traversal_result.h - what holotrace-bench-traversal measured per mesh, printed and written as CSV / JSON.
#pragma once
#include <cstdint>
#include <ostream>
#include <string>
#include <vector>

#include "bench/bvh_cost_counter.h"
#include "bench/hit_comparison.h"
#include "bench/timing_series.h"

namespace ht::bench {

struct SetThroughput {
  std::string set, query;  // "primary"/"shadow"/"diffuse"/"mirror", "closest"/"occluded"
  std::uint64_t rays = 0;
  TimingSeries gpu, embree1, embree8;  // ms per run
  std::vector<double> ratio1, ratio8;  // per run: Embree ms / GPU ms (= GPU Mrays/s / Embree Mrays/s, same run)
  HitComparison vsEmbree1, vsEmbree8;  // A = GPU, B = Embree (last run)
  std::uint32_t gpuMaxSteps = 0;
};

struct TreeFigures {
  TimingSeries buildMs;
  double sahCost = 0.0;
  std::uint32_t nodes = 0, leaves = 0, maxDepth = 0;
  std::vector<TraversalCost> costs;  // one per ray set, same order as MeshResult::sets
  std::vector<TraversalCost> lanes;  // the same counted on a contiguous block of each set (lane groups as dispatched)
};

struct MeshResult {
  std::string mesh;
  std::uint64_t triangles = 0;
  std::vector<SetThroughput> sets;
  TreeFigures ours, embree;
};

struct TraversalReport {
  std::string device, embreeVersion, date;
  std::uint32_t size = 0, runs = 0, costStride = 0;
  unsigned threads = 0;
  std::vector<MeshResult> meshes;
};

void printTraversalReport(std::ostream& out, const TraversalReport& report);
void writeTraversalCsv(const std::string& prefix, const TraversalReport& report);  // throws IoError
void writeTraversalJson(const std::string& path, const TraversalReport& report);   // throws IoError

}  // namespace ht::bench
