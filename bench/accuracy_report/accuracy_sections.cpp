#include "accuracy_sections.h"

#include <chrono>
#include <cstdio>
#include <random>
#include <sstream>

#include "bvh/cpu_traversal.h"
#include "gpu/renderer.h"
#include "hit_agreement.h"
#include "interior_rays.h"
#include "leak_count.h"
#include "robust_embree.h"
#include "test_meshes.h"

namespace ht::accuracy::report {
namespace {

using gpu_shared::HtHit;
using gpu_shared::HtRay;

constexpr auto kKinds = static_cast<uint32_t>(RayKind::Count);

std::string rate(uint64_t misses, uint64_t rays) {
  char buf[64];
  std::snprintf(buf, sizeof(buf), "%llu (%.4f %%)", static_cast<unsigned long long>(misses),
                rays ? 100.0 * double(misses) / double(rays) : 0.0);
  return buf;
}

void add(LeakCounts& total, const LeakCounts& c) {
  total.rays += c.rays;
  total.cpuMisses += c.cpuMisses;
  total.cpuOverflows += c.cpuOverflows;
  total.gpuMisses += c.gpuMisses;
  total.embreeMisses += c.embreeMisses;
  total.mtEpsilonMisses += c.mtEpsilonMisses;
  total.mtNoEpsilonMisses += c.mtNoEpsilonMisses;
  total.trianglesDropped = std::max(total.trianglesDropped, c.trianglesDropped);
}

std::string leakRow(const std::string& label, const LeakCounts& c) {
  return "| " + label + " | " + std::to_string(c.rays) + " | " + rate(c.cpuMisses, c.rays) + " | " +
         rate(c.gpuMisses, c.rays) + " | " + rate(c.embreeMisses, c.rays) + " | " + rate(c.mtEpsilonMisses, c.rays) +
         " | " + rate(c.mtNoEpsilonMisses, c.rays) + " |\n";
}

const char* kLeakHeader =
    "| rays | holotrace CPU misses | holotrace GPU misses | Embree 3 robust misses | naive MT (eps 1e-6) "
    "misses | naive MT (no eps) misses |\n";

std::vector<HtRay> exteriorRays(const TestMesh& mesh, uint64_t count, uint32_t seed) {
  Bounds3 b;
  for (const glm::vec3& p : mesh.positions) b.extend(p);
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<float> unit(0.0f, 1.0f), sym(-1.0f, 1.0f);
  const float radius = glm::length(b.extent());
  std::vector<HtRay> rays;
  while (rays.size() < count) {
    const glm::vec3 s(sym(rng), sym(rng), sym(rng));
    if (glm::dot(s, s) < 1e-4f) continue;
    const glm::vec3 origin = b.center() + radius * glm::normalize(s);
    const glm::vec3 target = b.lo + glm::vec3(unit(rng), unit(rng), unit(rng)) * b.extent();
    rays.push_back(HtRay{origin, 0.0f, target - origin, 3.0e38f});
  }
  return rays;
}

std::string agreementRows(const std::string& label, const TestMesh& mesh, std::span<const HtRay> rays,
                          gpu::VulkanContext& context, std::string& listing) {
  const auto anchor = RobustEmbree(mesh.positions, mesh.triangles).traceClosest(rays);
  gpu::Renderer renderer(context, toScene(mesh));
  std::vector<HtHit> gpuHits;
  constexpr size_t kChunk = size_t(1) << 20;
  for (size_t first = 0; first < rays.size(); first += kChunk) {
    const auto part = renderer.traceClosest(rays.subspan(first, std::min(kChunk, rays.size() - first)));
    gpuHits.insert(gpuHits.end(), part.begin(), part.end());
  }
  const bvh::GpuBvh bvh = bvh::buildGpuBvh(mesh.positions, mesh.triangles, bvh::BuildOptions{});
  std::vector<HtHit> cpuHits;
  for (const auto& r : bvh::traceClosestBatch(bvh, rays)) cpuHits.push_back(r.hit);
  std::string rows;
  for (const auto& [side, ours] : {std::pair{"CPU", &cpuHits}, std::pair{"GPU", &gpuHits}}) {
    const Agreement a = compareHits(mesh.positions, mesh.triangles, rays, *ours, anchor, 10);
    char pct[32];
    std::snprintf(pct, sizeof(pct), "%.5f %%", a.agreementPercent());
    rows += "| " + label + " | " + side + " | " + std::to_string(a.rays) + " | " + pct + " | " +
            std::to_string(a.hitMissDisagreements) + " | " + std::to_string(a.tDisagreements) + " | " +
            std::to_string(a.byCause[0]) + " | " + std::to_string(a.byCause[1]) + " | " + std::to_string(a.interior()) +
            " |\n";
    for (const Disagreement& d : a.listed) listing += "- " + label + " " + side + ": " + describe(d) + "\n";
  }
  return rows;
}

}  // namespace

std::string watertightSection(gpu::VulkanContext& context, uint64_t raysPerMesh) {
  const auto placementList = placements();
  const uint64_t configsKinds = placementList.size() * kKinds;  // rounded up: at least raysPerMesh per mesh
  const uint64_t perConfigKind = std::max<uint64_t>(1, (raysPerMesh + configsKinds - 1) / configsKinds);
  std::ostringstream md;
  md << "### Per mesh and placement\n\n| mesh | placement " << kLeakHeader << "|---|---|---|---|---|---|---|---|\n";
  LeakCounts byKind[kKinds];
  LeakCounts all;
  for (const TestMesh& local : closedMeshes()) {
    for (const Placement& p : placementList) {
      const TestMesh mesh = placed(local, p.scale, p.offset);
      LeakCounts config;
      for (uint32_t k = 0; k < kKinds; ++k) {
        const auto rays = interiorRays(mesh, static_cast<RayKind>(k), static_cast<uint32_t>(perConfigKind), 1000 + k);
        const LeakCounts c = countLeaks(mesh, rays, LeakOptions{&context, true});
        add(config, c);
        add(byKind[k], c);
      }
      add(all, config);
      md << leakRow(mesh.name + " | " + p.name, config);
      std::fprintf(stderr, "watertight %s %s: %llu rays, cpu %llu gpu %llu embree %llu\n", mesh.name.c_str(),
                   p.name.c_str(), (unsigned long long)config.rays, (unsigned long long)config.cpuMisses,
                   (unsigned long long)config.gpuMisses, (unsigned long long)config.embreeMisses);
    }
  }
  md << leakRow("**all** | **all**", all);
  md << "\n### Per ray kind (all meshes and placements)\n\n| kind " << kLeakHeader << "|---|---|---|---|---|---|---|\n";
  for (uint32_t k = 0; k < kKinds; ++k) md << leakRow(rayKindName(static_cast<RayKind>(k)), byKind[k]);
  md << "\nCPU traversal step-limit overflows: " << all.cpuOverflows << ".\n";
  return md.str();
}

std::string differentialSection(gpu::VulkanContext& context, uint64_t raysPerCase) {
  std::ostringstream md;
  std::string listing;
  md << "| case | holotrace | rays | hit/miss agreement | hit/miss disagreements | t disagreements | "
        "edge-or-vertex | silhouette-graze | interior |\n|---|---|---|---|---|---|---|---|---|\n";
  for (const TestMesh& local : closedMeshes()) {
    for (const Placement& p : {Placement{"origin", 1.0f, glm::vec3(0.0f)},
                               Placement{"embree-verify", 2.0f, glm::vec3(148376.0f, 1234.0f, -223423.0f)}}) {
      const TestMesh mesh = placed(local, p.scale, p.offset);
      const auto rays = interiorRays(mesh, RayKind::Random, static_cast<uint32_t>(raysPerCase), 77);
      md << agreementRows(mesh.name + " " + p.name + " random interior", mesh, rays, context, listing);
      std::fprintf(stderr, "differential %s %s done\n", mesh.name.c_str(), p.name.c_str());
    }
  }
  const TestMesh icosphere5 = icosphere(5);
  for (RayKind kind : {RayKind::Vertex, RayKind::Edge, RayKind::Axis, RayKind::ZeroComp}) {
    const auto rays = interiorRays(icosphere5, kind, static_cast<uint32_t>(raysPerCase / 4), 78);
    md << agreementRows("icosphere-s5 origin " + rayKindName(kind) + " interior", icosphere5, rays, context, listing);
  }
  const TestMesh bunnyMesh = bunny();
  if (!bunnyMesh.triangles.empty()) {
    const auto rays = exteriorRays(bunnyMesh, raysPerCase, 79);
    md << agreementRows("bunny exterior", bunnyMesh, rays, context, listing);
  } else {
    md << "| bunny | (glmark2-data not installed) | | | | | | | |\n";
  }
  md << "\nFirst disagreements of each case (at most 10 per case and side):\n\n"
     << (listing.empty() ? "- none\n" : listing);
  return md.str();
}

}  // namespace ht::accuracy::report
