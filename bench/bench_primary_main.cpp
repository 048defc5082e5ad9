// bench_primary_main.cpp - holotrace-bench-primary: holotrace's GPU traversal vs Embree 3 on the same
// pinhole primary rays (docs/BVH.md §8 6(d): lavapipe target >= 20 % of Embree on the same machine).
//
// Both tracers are warmed up once (lavapipe JIT-compiles at the first dispatch, docs/TOOLCHAIN.md P7), then run
// interleaved --runs times; the median of each is reported. GPU time = timestamp time of the trace
// dispatches (TraceStats::gpuMs); Embree time = wall time of the threaded rtcIntersect1/rtcOccluded1 loop.
#include <algorithm>
#include <iostream>
#include <string>
#include <vector>

#include "bench/bench_main.h"
#include "bench/bench_options.h"
#include "bench/bench_result.h"
#include "bench/embree_tracer.h"
#include "bench/primary_ray_batch.h"
#include "common/error.h"
#include "gpu/renderer.h"
#include "gpu/vulkan_context.h"
#include "scene/scene.h"

namespace ht::bench {
namespace {

void fillBvhFigures(BenchResult& result, const bvh::BuildReport& report) {
  result.bvhBuildMs = report.buildMs;
  result.bvhSahCost = report.sahCost;
  result.bvhNodes = report.nodeCount;
  result.bvhMaxDepth = report.maxDepth;
}

// One timed closest-hit run of each tracer; keeps the latest hits for the comparison.
void runClosest(gpu::Renderer& renderer, const EmbreeTracer& embree, const RayBatch& batch, unsigned threads,
                QueryResult& q) {
  gpu::TraceStats stats;
  const auto gpuHits = renderer.traceClosest(batch.rays, &stats);
  q.gpu.ms.push_back(stats.gpuMs);
  q.gpuMaxSteps = std::max(q.gpuMaxSteps, stats.maxSteps);
  double wallMs = 0.0;
  const auto embreeHits = embree.traceClosest(batch.rays, batch.width, threads, &wallMs);
  q.embree.ms.push_back(wallMs);
  q.hits = compareClosest(gpuHits, embreeHits);
}

void runOccluded(gpu::Renderer& renderer, const EmbreeTracer& embree, const RayBatch& batch, unsigned threads,
                 QueryResult& q) {
  gpu::TraceStats stats;
  const auto gpuOccluded = renderer.traceOccluded(batch.rays, &stats);
  q.gpu.ms.push_back(stats.gpuMs);
  q.gpuMaxSteps = std::max(q.gpuMaxSteps, stats.maxSteps);
  double wallMs = 0.0;
  const auto embreeOccluded = embree.traceOccluded(batch.rays, batch.width, threads, &wallMs);
  q.embree.ms.push_back(wallMs);
  q.hits = compareOccluded(gpuOccluded, embreeOccluded);
}

void warmUp(gpu::Renderer& renderer, const EmbreeTracer& embree, const RayBatch& batch, unsigned threads) {
  double ignoredMs = 0.0;
  renderer.traceClosest(batch.rays);
  renderer.traceOccluded(batch.rays);
  embree.traceClosest(batch.rays, batch.width, threads, &ignoredMs);
  embree.traceOccluded(batch.rays, batch.width, threads, &ignoredMs);
}

int runBenchmark(const BenchOptions& options) {
  const Scene scene = loadScene(options.mesh);
  const RayBatch batch = makePinholeRays(scene.bounds(), options.size);
  gpu::VulkanContext context({options.deviceIndex, false, false, options.fusedFloatMath});
  gpu::Renderer renderer(context, scene);
  const EmbreeTracer embree(scene);

  BenchResult result;
  result.mesh = options.mesh;
  result.triangles = scene.triangleCount();
  result.width = batch.width;
  result.height = batch.height;
  result.runs = options.runs;
  result.embreeThreads = options.threads;
  result.device = context.device().name + " (" + context.device().type + ")";
  fillBvhFigures(result, renderer.bvhReport());
  result.embreeBuildMs = embree.buildMs();
  result.embreeVersion = EmbreeTracer::version();

  std::cout << "holotrace-bench-primary: warming up (lavapipe compiles kernels at the first dispatch)...\n";
  warmUp(renderer, embree, batch, options.threads);
  for (std::uint32_t run = 0; run < options.runs; ++run) {
    runClosest(renderer, embree, batch, options.threads, result.closest);
    runOccluded(renderer, embree, batch, options.threads, result.occluded);
  }
  printResult(std::cout, result);
  if (options.jsonPath) {
    writeResultJson(*options.jsonPath, result);
    std::cout << "wrote " << *options.jsonPath << "\n";
  }
  return result.hitsAgree() ? 0 : 1;
}

}  // namespace
}  // namespace ht::bench

int main(int argc, char** argv) {
  return ht::bench::benchMain(
      argc, argv, "holotrace-bench-primary",
      [](const std::vector<std::string>& a, std::string* help) { return ht::bench::parseBenchOptions(a, help); },
      [](const auto& options) { return ht::bench::runBenchmark(options); });
}
