// bench_bvh2_main.cpp - holotrace-bench-bvh2: two-level vs flattened BVH on the CPU (docs/BVH.md §9,
// docs/BENCHMARKS.md "Two-level BVH").
//  1. Trace cost on static scenes: the same pinhole rays traced through the flattened BVH (order-free closest hit,
//     and the earlier tree-dependent ht_trace_closest for reference) and through the two-level BVH; median ms of --runs
//     runs, the two-level/flattened ratio per run (same run), mean traversal steps, and the layout chooseBvhLayout
//     picks.
//  2. Update time for one moved node in a large instanced scene (default ~2M triangles in 1,000 instances, and 27
//     instances of the bunny): full flattened rebuild vs top-level rebuild vs move update (refit of the moved
//     instance + top level); medians.
// Usage: holotrace-bench-bvh2 [--runs N (5)] [--size N (512)] [--meshes LIST] [--instances N (1000)] (--help)
#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstring>
#include <exception>
#include <functional>
#include <iostream>
#include <memory>
#include <optional>
#include <random>
#include <string>
#include <thread>
#include <vector>

#include <glm/gtc/matrix_transform.hpp>

#include "bench/bench_main.h"
#include "bench/timing_series.h"
#include "bvh/bvh_layout_choice.h"
#include "bvh/cpu_traversal.h"
#include "bvh/two_level_bvh.h"
#include "common/error.h"
#include "gpu/renderer.h"
#include "gpu/scene_bvh.h"
#include "gpu/vulkan_context.h"
#include "scene/scene.h"
#include "scene/scene_edits.h"

namespace ht::bench {
namespace {

using bvh::GpuBvh;
using bvh::TwoLevelBvh;
using gpu_shared::HtRay;
using Clock = std::chrono::steady_clock;

struct Options {
  bool gpu = false;  // also trace and update through the renderer on the Vulkan device (lavapipe here)
  uint32_t runs = 5;
  uint32_t size = 512;
  uint32_t instances = 1000;
  std::vector<std::string> meshes{"/usr/share/glmark2/models/bunny.obj", "assets/armadillo.off",
                                  "assets/refined_elephant.off", "builtin:showcase"};
};

uint32_t parseCount(const std::string& name, const std::string& value, uint32_t lo, uint32_t hi) {
  size_t used = 0;
  unsigned long n = 0;
  try {
    n = std::stoul(value, &used);
  } catch (const std::exception&) { used = 0; }
  if (used != value.size() || n < lo || n > hi) {
    throw UsageError("holotrace-bench-bvh2: " + name + " = '" + value + "': expected an integer in [" +
                     std::to_string(lo) + ", " + std::to_string(hi) + "]");
  }
  return static_cast<uint32_t>(n);
}

std::vector<std::string> splitList(const std::string& list) {
  std::vector<std::string> out;
  size_t start = 0;
  while (start <= list.size()) {
    const size_t end = std::min(list.find(',', start), list.size());
    if (end > start) out.push_back(list.substr(start, end - start));
    start = end + 1;
  }
  return out;
}

constexpr const char* kHelp =
    "Usage: holotrace-bench-bvh2 [--runs N (5)] [--size N (512)] [--meshes LIST] [--instances N (1000)] [--gpu]\n"
    "Two-level vs flattened BVH on the CPU: trace cost on static scenes (--meshes, each also as a\n"
    "grid of 27 instances) and the update time for one moved node in a ~2M-triangle scene of\n"
    "--instances instances. Medians of --runs runs; ratios are per run.\n"
    "--gpu: the same through gpu::Renderer on the Vulkan device: trace_closest time (GPU timestamps) of the\n"
    "flattened vs the two-level BVH, and the end-to-end update for one moved node (flattened rebuild + upload\n"
    "vs Renderer::moveNodes: refit + top level + partial upload).\n";

std::optional<Options> parseOptions(const std::vector<std::string>& args, std::string* help) {
  Options o;
  for (size_t i = 0; i < args.size(); ++i) {
    const std::string& a = args[i];
    if (a == "--help" || a == "-h") {
      *help = kHelp;
      return std::nullopt;
    }
    if (a == "--gpu") {
      o.gpu = true;
      continue;
    }
    if (i + 1 >= args.size()) throw UsageError("holotrace-bench-bvh2: option '" + a + "' needs a value (see --help)");
    const std::string& v = args[++i];
    if (a == "--runs")
      o.runs = parseCount(a, v, 1, 1000);
    else if (a == "--size")
      o.size = parseCount(a, v, 16, 4096);
    else if (a == "--instances")
      o.instances = parseCount(a, v, 1, 100000);
    else if (a == "--meshes")
      o.meshes = splitList(v);
    else
      throw UsageError("holotrace-bench-bvh2: unknown option '" + a + "' (see --help)");
  }
  return o;
}

double timeMs(const std::function<void()>& fn) {
  const auto start = Clock::now();
  fn();
  return std::chrono::duration<double, std::milli>(Clock::now() - start).count();
}

bvh::Aabb boundsOf(const Scene& scene) {
  const Bounds3 b = scene.bounds();
  return bvh::Aabb{b.lo, b.hi};
}

// size x size pinhole rays looking at the scene bounds from the +z side (as the traversal benchmark's view).
std::vector<HtRay> pinholeRays(const bvh::Aabb& box, uint32_t size) {
  const glm::vec3 centre = box.lo * 0.5f + box.hi * 0.5f;
  const float radius = glm::length(box.hi - box.lo) * 0.5f;
  const glm::vec3 eye = centre + glm::vec3(0.1f * radius, 0.15f * radius, 2.2f * radius);
  const glm::vec3 forward = glm::normalize(centre - eye);
  const glm::vec3 right = glm::normalize(glm::cross(forward, glm::vec3(0, 1, 0)));
  const glm::vec3 up = glm::cross(right, forward);
  const float half = std::tan(glm::radians(30.0f) * 0.5f);
  std::vector<HtRay> rays;
  rays.reserve(size_t{size} * size);
  for (uint32_t y = 0; y < size; ++y)
    for (uint32_t x = 0; x < size; ++x) {
      const float sx = ((x + 0.5f) / size * 2.0f - 1.0f) * half, sy = (1.0f - (y + 0.5f) / size * 2.0f) * half;
      rays.push_back(HtRay{eye, 0.0f, glm::normalize(forward + sx * right + sy * up), INFINITY});
    }
  return rays;
}

// `copies` placements of `mesh`'s geometry as movable nodes sharing mesh 0, on a cube grid with a random-free twist.
Scene instancedGrid(const Scene& mesh, uint32_t copies, const std::string& name) {
  Scene out;
  out.name = name;
  out.materials = mesh.materials.empty() ? std::vector<Material>{Material{}} : mesh.materials;
  const bvh::Aabb box = boundsOf(mesh);
  const glm::vec3 extent = box.hi - box.lo;
  const double pitch = 1.2 * std::max({extent.x, extent.y, extent.z});
  uint32_t side = 1;
  while (side * side * side < copies) ++side;
  for (uint32_t c = 0; c < copies; ++c) {
    const glm::dvec3 cell(c % side, (c / side) % side, c / (side * side));
    glm::dmat4 world = glm::translate(glm::dmat4(1.0), cell * pitch);
    world = glm::rotate(world, 0.37 * c, glm::dvec3(0.0, 1.0, 0.0));
    SceneNode node;
    node.name = "copy" + std::to_string(c);
    node.mesh = 0;
    node.world = world;
    node.firstVertex = static_cast<uint32_t>(out.positions.size());
    node.firstTriangle = static_cast<uint32_t>(out.triangles.size());
    node.vertexCount = static_cast<uint32_t>(mesh.positions.size());
    node.triangleCount = static_cast<uint32_t>(mesh.triangles.size());
    for (const glm::vec3& p : mesh.positions)
      out.positions.push_back(glm::vec3(world * glm::dvec4(glm::dvec3(p), 1.0)));
    for (const glm::uvec3& t : mesh.triangles) {
      out.triangles.push_back(t + glm::uvec3(node.firstVertex));
      out.triangleMaterial.push_back(0);
    }
    out.nodes.push_back(std::move(node));
  }
  return out;
}

// n small random triangles in a ball of radius 0.5 (fixed seed): an instance of a given triangle count.
Scene triangleClump(uint32_t n) {
  Scene s;
  std::mt19937 rng(12345);
  std::uniform_real_distribution<float> unit(-1.0f, 1.0f);
  for (uint32_t i = 0; i < n; ++i) {
    glm::vec3 a;
    do a = glm::vec3(unit(rng), unit(rng), unit(rng));
    while (glm::dot(a, a) > 1.0f);
    a *= 0.45f;
    const auto base = static_cast<uint32_t>(s.positions.size());
    s.positions.push_back(a);
    s.positions.push_back(a + 0.05f * glm::vec3(unit(rng), unit(rng), unit(rng)));
    s.positions.push_back(a + 0.05f * glm::vec3(unit(rng), unit(rng), unit(rng)));
    s.triangles.emplace_back(base, base + 1, base + 2);
  }
  return s;
}

// The tree-dependent closest hit the renderer used before the order-free one (bvh_traversal.h), for reference;
// rays split over all cores in contiguous parts, like the batch traces it is compared with.
void traceTreeDependentBatch(const GpuBvh& flat, const std::vector<HtRay>& rays) {
  const gpu_shared::BvhView view{flat.nodes.data(), flat.triangles.data()};
  std::vector<gpu_shared::HtTraceResult> results(rays.size());
  const size_t workers = std::max(1u, std::thread::hardware_concurrency());
  const size_t part = (rays.size() + workers - 1) / workers;
  std::vector<std::thread> pool;
  for (size_t w = 0; w < workers; ++w)
    pool.emplace_back([&, w] {
      for (size_t i = w * part; i < std::min(rays.size(), (w + 1) * part); ++i)
        results[i] = gpu_shared::ht_trace_closest(view, rays[i], gpu_shared::HT_TRAVERSAL_STEP_LIMIT);
    });
  for (std::thread& t : pool) t.join();
}

void traceCost(const Scene& scene, const Options& o) {
  const GpuBvh flat = bvh::buildGpuBvh(scene.positions, scene.triangles, bvh::BuildOptions{});
  const std::vector<bvh::InstanceRange> ranges = gpu::instanceRanges(scene);
  const TwoLevelBvh twoLevel(scene.positions, scene.triangles, ranges);
  const std::vector<HtRay> rays = pinholeRays(boundsOf(scene), o.size);
  TimingSeries legacy, ordered, twoLevelMs;
  std::vector<double> ratio;
  std::vector<gpu_shared::HtTraceResult> a, b;
  for (uint32_t run = 0; run <= o.runs; ++run) {  // run 0 warms up
    const double l = timeMs([&] { traceTreeDependentBatch(flat, rays); });
    const double f = timeMs([&] { a = bvh::traceClosestBatch(flat, rays); });
    const double t = timeMs([&] { b = bvh::traceClosestTwoLevelBatch(twoLevel, rays); });
    if (run == 0) continue;
    legacy.ms.push_back(l);
    ordered.ms.push_back(f);
    twoLevelMs.ms.push_back(t);
    ratio.push_back(t / f);
  }
  uint64_t mismatches = 0;
  double stepsF = 0.0, stepsT = 0.0;
  for (size_t i = 0; i < rays.size(); ++i) {
    mismatches += std::memcmp(&a[i].hit, &b[i].hit, sizeof(a[i].hit)) != 0;
    stepsF += a[i].steps;
    stepsT += b[i].steps;
  }
  const bvh::LayoutCosts costs = bvh::measureLayoutCosts(flat, twoLevel, bvh::layoutProbeRays(boundsOf(scene)));
  std::printf("%-34s %9zu %5zu %9.1f %9.1f %9.1f %7.3f %8.1f %8.1f %6llu  %s\n", scene.name.c_str(),
              scene.triangles.size(), twoLevel.instanceCount(), legacy.medianMs(), ordered.medianMs(),
              twoLevelMs.medianMs(), median(ratio), stepsF / rays.size(), stepsT / rays.size(),
              static_cast<unsigned long long>(mismatches), bvh::bvhLayoutName(bvh::chooseBvhLayout(false, costs)));
}

void updateTime(Scene scene, const Options& o) {
  const std::vector<bvh::InstanceRange> ranges = gpu::instanceRanges(scene);
  TimingSeries rebuild, top, move;
  double buildTwoLevelMs = timeMs([] {});
  std::unique_ptr<TwoLevelBvh> twoLevel;
  buildTwoLevelMs = timeMs([&] { twoLevel = std::make_unique<TwoLevelBvh>(scene.positions, scene.triangles, ranges); });
  for (uint32_t run = 0; run < o.runs; ++run)
    rebuild.ms.push_back(timeMs([&] { bvh::buildGpuBvh(scene.positions, scene.triangles, bvh::BuildOptions{}); }));
  const uint32_t topRuns = std::max(21u, o.runs);
  for (uint32_t run = 0; run < topRuns; ++run) top.ms.push_back(timeMs([&] { twoLevel->rebuildTopLevel(); }));
  // The moved node: the middle one, shifted back and forth along x (what UpdateScene does to the soup).
  const uint32_t node = static_cast<uint32_t>(scene.nodes.size() / 2);
  uint32_t instance = 0;
  const std::vector<SceneInstance> inst = scene.instances();
  for (uint32_t i = 0; i < inst.size(); ++i)
    if (inst[i].node == static_cast<int32_t>(node)) instance = i;
  const std::vector<uint32_t> moved{instance};
  std::vector<double> refit;
  for (uint32_t run = 0; run < topRuns; ++run) {
    const glm::dmat4 world = glm::translate(scene.nodes[node].world, glm::dvec3(run % 2 ? -0.25 : 0.25, 0.0, 0.0));
    setNodeWorldMatrix(scene, scene.nodes[node].name, world);
    move.ms.push_back(timeMs([&] { twoLevel->updateInstances(scene.positions, scene.triangles, moved); }));
    refit.push_back(twoLevel->timings().refitMs);
  }
  std::printf("%-34s %9zu %5zu %11.1f %11.1f %10.4f %10.3f %10.3f %9.0fx\n", scene.name.c_str(), scene.triangles.size(),
              twoLevel->instanceCount(), rebuild.medianMs(), buildTwoLevelMs, top.medianMs(), median(refit),
              move.medianMs(), rebuild.medianMs() / move.medianMs());
}

// The same pinhole rays through gpu::Renderer::traceClosest on the flattened and the two-level BVH (trace_closest
// GPU time), interleaved, after a warm-up; median ms, median of per-run ratios, rays whose hits differ in any bit.
void gpuTraceCost(gpu::VulkanContext& context, const Scene& scene, const Options& o) {
  gpu::Renderer flat(context, scene, gpu::buildSceneBvh(scene, {}, gpu::BvhLayoutPolicy::Flattened));
  gpu::Renderer twoLevel(context, scene, gpu::buildSceneBvh(scene, {}, gpu::BvhLayoutPolicy::TwoLevel));
  const std::vector<HtRay> rays = pinholeRays(boundsOf(scene), o.size);
  TimingSeries flatMs, twoLevelMs;
  std::vector<double> ratio;
  std::vector<gpu_shared::HtHit> a, b;
  for (uint32_t run = 0; run <= o.runs; ++run) {  // run 0 warms up (lavapipe compiles at the first dispatch)
    gpu::TraceStats f, t;
    a = flat.traceClosest(rays, &f);
    b = twoLevel.traceClosest(rays, &t);
    if (run == 0) continue;
    flatMs.ms.push_back(f.gpuMs);
    twoLevelMs.ms.push_back(t.gpuMs);
    ratio.push_back(t.gpuMs / f.gpuMs);
  }
  uint64_t mismatches = 0;
  for (size_t i = 0; i < rays.size(); ++i) mismatches += std::memcmp(&a[i], &b[i], sizeof(a[i])) != 0;
  std::printf("%-34s %9zu %5zu %10.1f %10.1f %7.3f %6llu\n", scene.name.c_str(), scene.triangles.size(),
              gpu::instanceRanges(scene).size(), flatMs.medianMs(), twoLevelMs.medianMs(), median(ratio),
              static_cast<unsigned long long>(mismatches));
}

// One node moved back and forth: a flattened renderer rebuilds and re-uploads (replaceScene), a two-level renderer
// takes Renderer::moveNodes; host wall time of each, with the two-level update's refit and top-level parts.
void gpuUpdateTime(gpu::VulkanContext& context, Scene scene, const Options& o) {
  gpu::Renderer flat(context, scene, gpu::buildSceneBvh(scene, {}, gpu::BvhLayoutPolicy::Flattened));
  gpu::Renderer twoLevel(context, scene, gpu::buildSceneBvh(scene, {}, gpu::BvhLayoutPolicy::TwoLevel));
  const uint32_t node = static_cast<uint32_t>(scene.nodes.size() / 2);
  const std::vector<uint32_t> moved{node};
  TimingSeries rebuild, move;
  std::vector<double> refit, top, upload;
  const uint32_t moveRuns = std::max(21u, o.runs);
  for (uint32_t run = 0; run < moveRuns; ++run) {
    const glm::dmat4 world = glm::translate(scene.nodes[node].world, glm::dvec3(run % 2 ? -0.25 : 0.25, 0.0, 0.0));
    setNodeWorldMatrix(scene, scene.nodes[node].name, world);
    twoLevel.moveNodes(scene, moved);
    move.ms.push_back(twoLevel.bvhStats().lastUpdateMs);
    refit.push_back(twoLevel.bvhStats().lastRefitMs);
    top.push_back(twoLevel.bvhStats().lastTopLevelMs);
    upload.push_back(twoLevel.bvhStats().lastUploadMs);
    if (run < o.runs) rebuild.ms.push_back(timeMs([&] { flat.replaceScene(scene, gpu::BvhLayoutPolicy::Flattened); }));
  }
  if (twoLevel.bvhStats().fullBuilds != 1) throw Error("holotrace-bench-bvh2: a two-level move rebuilt the BVH");
  std::printf("%-34s %9zu %5zu %12.1f %10.3f %10.3f %10.3f %12.3f %9.0fx\n", scene.name.c_str(), scene.triangles.size(),
              gpu::instanceRanges(scene).size(), rebuild.medianMs(), median(top), median(refit), median(upload),
              move.medianMs(), rebuild.medianMs() / move.medianMs());
}

void runGpu(const Options& o, const std::vector<Scene>& traceScenes, const std::vector<Scene>& updateScenes) {
  gpu::VulkanContext context(gpu::VulkanContext::Options{});
  std::printf(
      "\nGPU (%s): trace_closest time, static scenes (GPU timestamp ms; ratio = two-level / flattened, median "
      "of per-run ratios; diff = rays whose hits differ in any bit)\n",
      context.device().name.c_str());
  std::printf("%-34s %9s %5s %10s %10s %7s %6s\n", "scene", "tris", "inst", "flattened", "2-level", "ratio", "diff");
  for (const Scene& scene : traceScenes) gpuTraceCost(context, scene, o);
  std::printf(
      "\nGPU: update after moving one node, end to end in the renderer (host ms; rebuild = flattened build + "
      "upload; move = Renderer::moveNodes = refit + top + uploads)\n");
  std::printf("%-34s %9s %5s %12s %10s %10s %10s %12s %10s\n", "scene", "tris", "inst", "rebuild", "top", "refit",
              "upload", "move", "speedup");
  for (const Scene& scene : updateScenes) gpuUpdateTime(context, scene, o);
}

int run(const Options& o) {
  std::printf("holotrace-bench-bvh2: %u runs (medians), %ux%u pinhole rays, all cores\n\n", o.runs, o.size, o.size);
  std::printf(
      "Trace cost, static scenes (ms per ray batch; ordered = order-free closest hit; ratio = two-level / "
      "ordered flattened, median of per-run ratios)\n");
  std::printf("%-34s %9s %5s %9s %9s %9s %7s %8s %8s %6s  %s\n", "scene", "tris", "inst", "legacy", "ordered",
              "2-level", "ratio", "steps-f", "steps-2", "diff", "choice");
  Scene bigMesh;
  std::vector<Scene> traceScenes, updateScenes;
  for (const std::string& spec : o.meshes) {
    Scene scene;
    try {
      scene = loadScene(spec);
    } catch (const Error& e) {
      std::printf("%-34s skipped: %s\n", spec.c_str(), e.what());
      continue;
    }
    traceCost(scene, o);
    Scene grid = instancedGrid(scene, 27, spec + " x27");
    traceCost(grid, o);
    if (o.gpu) {
      traceScenes.push_back(scene);
      traceScenes.push_back(std::move(grid));
    }
    if (scene.triangles.size() > bigMesh.triangles.size()) bigMesh = std::move(scene);
  }
  std::printf(
      "\nUpdate after moving one node (ms; rebuild = flattened buildGpuBvh; top = top-level rebuild alone; "
      "refit = the moved instance's refit; move = refit + top)\n");
  std::printf("%-34s %9s %5s %11s %11s %10s %10s %10s %10s\n", "scene", "tris", "inst", "rebuild", "2-lvl build", "top",
              "refit", "move", "speedup");
  const uint32_t perInstance = std::max<uint32_t>(1, 2000000 / o.instances);
  Scene clumps = instancedGrid(triangleClump(perInstance), o.instances,
                               "clump(" + std::to_string(perInstance) + ") x" + std::to_string(o.instances));
  updateTime(clumps, o);
  if (o.gpu) updateScenes.push_back(std::move(clumps));
  if (!bigMesh.triangles.empty()) {
    const uint32_t copies = std::max<uint32_t>(1, static_cast<uint32_t>(2000000 / bigMesh.triangles.size()));
    updateTime(instancedGrid(bigMesh, copies, bigMesh.name + " x" + std::to_string(copies)), o);
  }
  if (o.gpu) runGpu(o, traceScenes, updateScenes);
  return 0;
}

}  // namespace
}  // namespace ht::bench

int main(int argc, char** argv) {
  return ht::bench::benchMain(argc, argv, "holotrace-bench-bvh2", ht::bench::parseOptions, ht::bench::run);
}
