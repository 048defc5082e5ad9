// bench_traversal_main.cpp - holotrace-bench-traversal: traversal throughput (primary, shadow, diffuse, mirror rays)
// of holotrace's GPU kernel vs Embree 3 single-ray and 8-wide packet queries, and BVH quality of our builder vs
// Embree's rtcBuildBVH (SAH cost, node + triangle tests per ray). See traversal_options.cpp for the method.
//
// Per ray set every tracer is warmed up once (lavapipe JIT-compiles at the first dispatch), then the tracers run
// interleaved --runs times; each run's ratio is taken within the run and the medians are reported.
#include <chrono>
#include <ctime>
#include <iostream>
#include <string>
#include <vector>

#include "bench/bench_main.h"
#include "bench/bvh_cost_counter.h"
#include "bench/embree_bvh_build.h"
#include "bench/embree_tracer.h"
#include "bench/ray_sets.h"
#include "bench/traversal_options.h"
#include "bench/traversal_result.h"
#include "common/error.h"
#include "gpu/renderer.h"
#include "gpu/vulkan_context.h"
#include "scene/scene.h"

namespace ht::bench {
namespace {

using Api = EmbreeTracer::Api;

struct Tracers {
  gpu::Renderer& gpu;
  const EmbreeTracer& embree;
  unsigned threads;
};

// One timed run of the three tracers on the set; records times, the in-run ratios and the hit comparison.
void runOnce(const Tracers& t, const RaySet& set, SetThroughput& out) {
  gpu::TraceStats stats;
  double ms1 = 0.0, ms8 = 0.0;
  if (set.query == RayQuery::Closest) {
    const auto g = t.gpu.traceClosest(set.rays, &stats);
    const auto e1 = t.embree.traceClosestFlat(set.rays, Api::Single, t.threads, &ms1);
    const auto e8 = t.embree.traceClosestFlat(set.rays, Api::Packet8, t.threads, &ms8);
    out.vsEmbree1 = compareClosest(g, e1);
    out.vsEmbree8 = compareClosest(g, e8);
  } else {
    const auto g = t.gpu.traceOccluded(set.rays, &stats);
    const auto e1 = t.embree.traceOccludedFlat(set.rays, Api::Single, t.threads, &ms1);
    const auto e8 = t.embree.traceOccludedFlat(set.rays, Api::Packet8, t.threads, &ms8);
    out.vsEmbree1 = compareOccluded(g, e1);
    out.vsEmbree8 = compareOccluded(g, e8);
  }
  out.gpu.ms.push_back(stats.gpuMs);
  out.embree1.ms.push_back(ms1);
  out.embree8.ms.push_back(ms8);
  out.ratio1.push_back(stats.gpuMs > 0 ? ms1 / stats.gpuMs : 0.0);
  out.ratio8.push_back(stats.gpuMs > 0 ? ms8 / stats.gpuMs : 0.0);
  out.gpuMaxSteps = std::max(out.gpuMaxSteps, stats.maxSteps);
}

SetThroughput measureSet(const Tracers& t, const RaySet& set, std::uint32_t runs) {
  SetThroughput out;
  out.set = set.name;
  out.query = set.query == RayQuery::Closest ? "closest" : "occluded";
  out.rays = set.rays.size();
  runOnce(t, set, out);  // warm-up, discarded
  out = SetThroughput{out.set, out.query, out.rays, {}, {}, {}, {}, {}, {}, {}, 0};
  for (std::uint32_t run = 0; run < runs; ++run) runOnce(t, set, out);
  return out;
}

std::vector<RaySet> makeRaySets(const Scene& scene, const EmbreeTracer& embree, const TraversalOptions& o) {
  std::vector<RaySet> sets;
  sets.push_back(makeTiledPrimaryRays(scene.bounds(), o.size));
  double ignoredMs = 0.0;
  const auto hits = embree.traceClosestFlat(sets[0].rays, Api::Single, o.threads, &ignoredMs);
  for (RaySet& s : makeSecondaryRays(scene, sets[0].rays, hits, o.seed)) sets.push_back(std::move(s));
  return sets;
}

std::vector<gpu_shared::HtRay> everyNth(const std::vector<gpu_shared::HtRay>& rays, std::uint32_t stride) {
  std::vector<gpu_shared::HtRay> out;
  for (std::size_t i = 0; i < rays.size(); i += stride) out.push_back(rays[i]);
  return out;
}

void fillTree(TreeFigures& fig, const bvh::Bvh2& tree, const Scene& scene, const std::vector<RaySet>& sets,
              const TraversalOptions& o) {
  fig.sahCost = tree.report.sahCost;
  fig.nodes = tree.report.nodeCount;
  fig.leaves = tree.report.leafCount;
  fig.maxDepth = tree.report.maxDepth;
  for (const RaySet& set : sets) {
    fig.costs.push_back(countTraversalCost(tree, scene.positions, scene.triangles, everyNth(set.rays, o.costStride),
                                           set.query == RayQuery::Occluded, o.threads));
    // The middle 1/costStride of the set, contiguous: consecutive rays are the kernel's SIMD lanes.
    const std::size_t block = set.rays.size() / std::max<std::size_t>(o.costStride, 1) / 8 * 8;
    const std::span<const gpu_shared::HtRay> middle(set.rays.data() + (set.rays.size() - block) / 2, block);
    fig.lanes.push_back(
        countTraversalCost(tree, scene.positions, scene.triangles, middle, set.query == RayQuery::Occluded, o.threads));
  }
}

// Our builder and Embree's on the same triangles, --runs builds each (interleaved); the last trees are counted.
void measureBvhQuality(MeshResult& m, const Scene& scene, const std::vector<RaySet>& sets, const TraversalOptions& o) {
  bvh::BuildOptions options;
  options.threads = o.threads;
  bvh::Bvh2 ours;
  EmbreeBvhBuild theirs;
  for (std::uint32_t run = 0; run < o.runs; ++run) {
    ours = bvh::buildBinnedSah(scene.positions, scene.triangles, options);
    theirs = buildEmbreeBvh(scene.positions, scene.triangles, options.maxLeafSize);
    m.ours.buildMs.ms.push_back(ours.report.buildMs);
    m.embree.buildMs.ms.push_back(theirs.buildMs);
  }
  fillTree(m.ours, ours, scene, sets, o);
  fillTree(m.embree, theirs.tree, scene, sets, o);
}

MeshResult measureMesh(gpu::VulkanContext& context, const std::string& mesh, const TraversalOptions& o) {
  const Scene scene = loadScene(mesh);
  gpu::Renderer renderer(context, scene);
  const EmbreeTracer embree(scene);
  MeshResult m;
  m.mesh = mesh;
  m.triangles = scene.triangleCount();
  const std::vector<RaySet> sets = makeRaySets(scene, embree, o);
  std::cout << "holotrace-bench-traversal: " << mesh << " (" << m.triangles << " triangles)..." << std::endl;
  const Tracers tracers{renderer, embree, o.threads};
  for (const RaySet& set : sets) m.sets.push_back(measureSet(tracers, set, o.runs));
  measureBvhQuality(m, scene, sets, o);
  return m;
}

std::string utcNow() {
  const std::time_t now = std::time(nullptr);
  char text[32];
  std::strftime(text, sizeof text, "%Y-%m-%d %H:%M UTC", std::gmtime(&now));
  return text;
}

int runBenchmark(const TraversalOptions& o) {
  gpu::VulkanContext context({o.deviceIndex, false, false, o.fusedFloatMath});
  TraversalReport report;
  report.device = context.device().name + " (" + context.device().type + ")";
  report.embreeVersion = EmbreeTracer::version();
  report.date = utcNow();
  report.size = o.size;
  report.runs = o.runs;
  report.costStride = o.costStride;
  report.threads = o.threads;
  for (const std::string& mesh : o.meshes) report.meshes.push_back(measureMesh(context, mesh, o));
  printTraversalReport(std::cout, report);
  if (o.csvPrefix) writeTraversalCsv(*o.csvPrefix, report);
  if (o.jsonPath) writeTraversalJson(*o.jsonPath, report);
  return 0;
}

}  // namespace
}  // namespace ht::bench

int main(int argc, char** argv) {
  return ht::bench::benchMain(
      argc, argv, "holotrace-bench-traversal",
      [](const std::vector<std::string>& a, std::string* help) { return ht::bench::parseTraversalOptions(a, help); },
      [](const auto& options) { return ht::bench::runBenchmark(options); });
}
