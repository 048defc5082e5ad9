// Self-intersection (issue 4, docs/ACCURACY.md): secondary rays spawned with ht_offset_ray (bvh/offset_ray.h, Ray
// Tracing Gems ch. 6) never re-hit the surface they leave.
//   Shadow acne: lit surfaces - a tilted plane (16x16 quads) and a convex icosphere (5120 triangles) - at scales
//   1e-3 ... 1e6, at the origin and translated 1000 sizes away. Points come from primary hits (barycentric
//   interpolation, as RTG ch. 6 recommends), shadow rays go from the offset origin to a point light. On the plane
//   every light is on the viewer's side, so every sample must be lit; on the convex polyhedron a point of face f is
//   lit exactly when the light lies in front of f's plane (the polyhedron is the intersection of its faces' back
//   half-spaces), so samples with cos(n, L - p) > kGrazing must be lit. Samples with the light behind the face are
//   reported ("leaks" = not shadowed) but not asserted: near the origin ht_offset_ray moves a point by n/65536 in
//   absolute units (RTG ch. 6 float_scale), a quarter of a triangle edge at scale 1e-3, so a shadow ray from a point
//   near the silhouette can legitimately pass beside the polyhedron.
//   Mirror rays: the reflection of the primary ray about the face normal, spawned with ht_offset_ray, must escape
//   both surfaces (plane and convex polyhedron), in particular never re-hit the triangle it starts on.
// Both the CPU reference (bvh/cpu_traversal.h) and the GPU kernel (gpu::Renderer::traceClosest / traceOccluded)
// trace their own primaries, shadow and mirror rays. A control spawns the same rays from the hit point itself: it
// must show acne somewhere, or this test could not detect a broken offset.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <cstdio>
#include <functional>
#include <random>
#include <span>
#include <string>
#include <vector>

#include <glm/gtc/matrix_transform.hpp>

#include "accuracy_test_util.h"
#include "bvh/cpu_traversal.h"
#include "bvh/offset_ray.h"
#include "gpu/renderer.h"
#include "test_meshes.h"

namespace ht::accuracy {
namespace {

using gpu_shared::HT_MISS;
using gpu_shared::HtHit;
using gpu_shared::HtRay;

constexpr double kGrazing = 1e-3;  // |cos| below this: the light grazes the face plane, no expectation
constexpr float kFar = 1e30f;

// Placement of a local shape: world = local * scale + offset (double, rounded once, like test_meshes placed()).
struct Frame {
  double scale = 1.0;
  glm::dvec3 offset{0.0};
  glm::vec3 toWorld(glm::dvec3 local) const { return glm::vec3(local * scale + offset); }
};

// Tilted square plane through the local origin: (x, 0, z), |x|, |z| <= 1, rotated about a generic axis.
glm::dmat3 planeRotation() {
  return glm::dmat3(glm::rotate(glm::dmat4(1.0), 0.6, glm::normalize(glm::dvec3(1, 2, 3))));
}

TestMesh tiltedPlane(int quads) {
  TestMesh mesh;
  mesh.name = "plane-" + std::to_string(quads) + "x" + std::to_string(quads);
  mesh.closed = false;
  const glm::dmat3 r = planeRotation();
  for (int i = 0; i <= quads; ++i)
    for (int j = 0; j <= quads; ++j)
      mesh.positions.emplace_back(r * glm::dvec3(-1.0 + 2.0 * i / quads, 0.0, -1.0 + 2.0 * j / quads));
  auto at = [&](int i, int j) { return static_cast<uint32_t>(i * (quads + 1) + j); };
  for (int i = 0; i < quads; ++i)
    for (int j = 0; j < quads; ++j) {
      mesh.triangles.emplace_back(at(i, j), at(i, j + 1), at(i + 1, j + 1));
      mesh.triangles.emplace_back(at(i, j), at(i + 1, j + 1), at(i + 1, j));
    }
  return mesh;
}

// Local-space primary rays and lights for one shape; mapped to world by the Frame.
struct LocalSample {
  glm::dvec3 eye, target, light;
};

std::vector<LocalSample> planeSamples(uint32_t count, std::mt19937& rng) {
  std::uniform_real_distribution<double> u(-1.0, 1.0), height(0.02, 3.0);
  const glm::dmat3 r = planeRotation();
  std::vector<LocalSample> s(count);
  for (auto& x : s)  // viewer and light above the plane (local +y), targets inside its border
    x = {r * glm::dvec3(0.7 * u(rng), 2.0, 0.7 * u(rng)), r * glm::dvec3(0.8 * u(rng), 0.0, 0.8 * u(rng)),
         r * glm::dvec3(3.0 * u(rng), height(rng), 3.0 * u(rng))};
  return s;
}

glm::dvec3 randomUnit(std::mt19937& rng) {
  std::normal_distribution<double> g;
  for (;;) {
    const glm::dvec3 v(g(rng), g(rng), g(rng));
    if (glm::length(v) > 1e-6) return glm::normalize(v);
  }
}

std::vector<LocalSample> sphereSamples(uint32_t count, std::mt19937& rng) {
  std::uniform_real_distribution<double> u(0.0, 1.0);
  std::vector<LocalSample> s(count);
  for (auto& x : s)  // viewer on radius 3, target inside radius 0.9 (always hits), light on radius 1.5 ... 4
    x = {3.0 * randomUnit(rng), 0.9 * std::cbrt(u(rng)) * randomUnit(rng), (1.5 + 2.5 * u(rng)) * randomUnit(rng)};
  return s;
}

struct Counts {
  uint64_t samples = 0, primaryMisses = 0;
  uint64_t shouldBeLit = 0, acne = 0, shouldBeShadowed = 0, leaks = 0, grazing = 0;
  uint64_t mirrorRays = 0, mirrorHits = 0, mirrorSelfHits = 0;
  uint64_t controlAcne = 0, controlMirrorSelfHits = 0;  // same rays spawned from the hit point, no offset
};

// What the tracer under test provides: closest hits and occlusion flags for a batch.
struct Tracer {
  std::function<std::vector<HtHit>(std::span<const HtRay>)> closest;
  std::function<std::vector<uint32_t>(std::span<const HtRay>)> occluded;
};

struct Surface {
  glm::vec3 point, normal;  // hit point (barycentric) and unit face normal facing the incoming ray
};

Surface surfaceAt(const TestMesh& mesh, const HtHit& hit, glm::vec3 incoming) {
  const glm::uvec3 t = mesh.triangles[hit.triId];
  const glm::vec3 a = mesh.positions[t.x], b = mesh.positions[t.y], c = mesh.positions[t.z];
  const glm::vec3 p = (1.0f - hit.u - hit.v) * a + hit.u * b + hit.v * c;
  glm::vec3 n = glm::normalize(glm::vec3(glm::cross(glm::dvec3(b) - glm::dvec3(a), glm::dvec3(c) - glm::dvec3(a))));
  if (glm::dot(n, incoming) > 0.0f) n = -n;
  return {p, n};
}

// cos(angle between the face normal and the direction to the light), in double from the float positions.
double lightCosine(const Surface& s, glm::vec3 light) {
  const glm::dvec3 toLight = glm::dvec3(light) - glm::dvec3(s.point);
  return glm::dot(glm::dvec3(s.normal), toLight) / glm::length(toLight);
}

// The secondary rays of every primary hit: offset (under test) and spawned at the hit point (control).
struct SecondaryRays {
  std::vector<HtRay> shadow, controlShadow, mirror, controlMirror;
  std::vector<double> lightCosines;  // per shadow ray; 1 on the plane (the light is always on the lit side)
  std::vector<uint32_t> sourceTriangle;
};

SecondaryRays spawnSecondaryRays(const TestMesh& mesh, bool convex, std::span<const HtRay> primaries,
                                 std::span<const HtHit> hits, std::span<const glm::vec3> lights, Counts& c) {
  SecondaryRays out;
  for (std::size_t i = 0; i < hits.size(); ++i) {
    if (hits[i].triId == HT_MISS) {
      ++c.primaryMisses;
      continue;
    }
    const Surface s = surfaceAt(mesh, hits[i], primaries[i].dir);
    const glm::vec3 origin = gpu_shared::ht_offset_ray(s.point, s.normal);
    out.shadow.push_back({origin, 0.0f, lights[i] - origin, 1.0f});
    out.controlShadow.push_back({s.point, 0.0f, lights[i] - s.point, 1.0f});
    out.lightCosines.push_back(convex ? lightCosine(s, lights[i]) : 1.0);
    const glm::vec3 d = glm::normalize(primaries[i].dir);
    const glm::vec3 r = d - 2.0f * glm::dot(d, s.normal) * s.normal;  // mirror direction
    out.mirror.push_back({origin, 0.0f, r, kFar});
    out.controlMirror.push_back({s.point, 0.0f, r, kFar});
    out.sourceTriangle.push_back(hits[i].triId);
  }
  return out;
}

void countShadows(const SecondaryRays& rays, const Tracer& tracer, Counts& c) {
  const auto occluded = tracer.occluded(rays.shadow), controlOccluded = tracer.occluded(rays.controlShadow);
  for (std::size_t i = 0; i < rays.shadow.size(); ++i) {
    if (rays.lightCosines[i] > kGrazing) {
      ++c.shouldBeLit;
      c.acne += occluded[i];
      c.controlAcne += controlOccluded[i];
    } else if (rays.lightCosines[i] < -kGrazing) {
      ++c.shouldBeShadowed;
      c.leaks += occluded[i] ? 0 : 1;
    } else {
      ++c.grazing;
    }
  }
}

void countMirrors(const SecondaryRays& rays, const Tracer& tracer, Counts& c) {
  const auto hits = tracer.closest(rays.mirror), controlHits = tracer.closest(rays.controlMirror);
  c.mirrorRays = rays.mirror.size();
  for (std::size_t i = 0; i < rays.mirror.size(); ++i) {
    c.mirrorHits += hits[i].triId != HT_MISS ? 1 : 0;
    c.mirrorSelfHits += hits[i].triId == rays.sourceTriangle[i] ? 1 : 0;
    c.controlMirrorSelfHits += controlHits[i].triId == rays.sourceTriangle[i] ? 1 : 0;
  }
}

// Primary rays from the local samples, then shadow and mirror rays from their hits.
Counts runSamples(const TestMesh& mesh, bool convex, const Frame& frame, std::span<const LocalSample> local,
                  const Tracer& tracer) {
  Counts c;
  c.samples = local.size();
  std::vector<HtRay> primaries;
  std::vector<glm::vec3> lights;
  for (const LocalSample& s : local) {
    const glm::vec3 eye = frame.toWorld(s.eye);
    primaries.push_back({eye, 0.0f, frame.toWorld(s.target) - eye, 2.0f});
    lights.push_back(frame.toWorld(s.light));
  }
  const std::vector<HtHit> hits = tracer.closest(primaries);
  const SecondaryRays rays = spawnSecondaryRays(mesh, convex, primaries, hits, lights, c);
  countShadows(rays, tracer, c);
  countMirrors(rays, tracer, c);
  return c;
}

Tracer cpuTracer(const bvh::GpuBvh& bvh) {
  return {[&bvh](std::span<const HtRay> rays) {
            std::vector<HtHit> out;
            for (const auto& r : bvh::traceClosestBatch(bvh, rays)) {
              EXPECT_FALSE(r.overflow);
              out.push_back(r.hit);
            }
            return out;
          },
          [&bvh](std::span<const HtRay> rays) {
            std::vector<uint32_t> out;
            for (const auto& r : bvh::traceAnyBatch(bvh, rays)) {
              EXPECT_FALSE(r.overflow);
              out.push_back(r.hit.triId != HT_MISS ? 1u : 0u);
            }
            return out;
          }};
}

Tracer gpuTracer(gpu::Renderer& renderer) {
  return {[&renderer](std::span<const HtRay> rays) { return renderer.traceClosest(rays); },
          [&renderer](std::span<const HtRay> rays) { return renderer.traceOccluded(rays); }};
}

struct ScalePlacement {
  std::string name;
  Frame frame;
};

std::vector<ScalePlacement> scalePlacements() {
  std::vector<ScalePlacement> out;
  for (double scale : {1e-3, 1e-1, 1.0, 1e2, 1e4, 1e6}) {
    char name[64];
    std::snprintf(name, sizeof name, "s=%g", scale);
    out.push_back({name, {scale, glm::dvec3(0.0)}});
    // 1000 sizes away along a generic direction (at s=1e6 the surface sits near 1e9).
    std::snprintf(name, sizeof name, "s=%g t=1e3*s", scale);
    out.push_back({name, {scale, 1e3 * scale * glm::dvec3(0.8, -0.5, 0.33)}});
  }
  return out;
}

void report(const char* side, const std::string& mesh, const std::string& place, const Counts& c) {
  std::printf(
      "%-3s %-11s %-16s samples %llu lit %llu acne %llu | shadowed %llu leaks %llu | grazing %llu | "
      "mirror %llu hits %llu self %llu | control (no offset): acne %llu mirror self %llu\n",
      side, mesh.c_str(), place.c_str(), (unsigned long long)c.samples, (unsigned long long)c.shouldBeLit,
      (unsigned long long)c.acne, (unsigned long long)c.shouldBeShadowed, (unsigned long long)c.leaks,
      (unsigned long long)c.grazing, (unsigned long long)c.mirrorRays, (unsigned long long)c.mirrorHits,
      (unsigned long long)c.mirrorSelfHits, (unsigned long long)c.controlAcne,
      (unsigned long long)c.controlMirrorSelfHits);
}

void expectClean(const Counts& c, const std::string& where) {
  EXPECT_EQ(c.primaryMisses, 0u) << where;
  EXPECT_EQ(c.acne, 0u) << where;
  EXPECT_EQ(c.mirrorHits, 0u) << where;
  EXPECT_EQ(c.mirrorSelfHits, 0u) << where;
}

TEST(SelfIntersection, OffsetRaysNeitherShowAcneNorReHitTheirSurface) {
  const uint32_t count = test::scaledCount(20000);
  const TestMesh plane = tiltedPlane(16), sphere = icosphere(4);
  uint64_t controlAcne = 0, controlSelfHits = 0, lit = 0, shadowed = 0;
  for (const ScalePlacement& place : scalePlacements()) {
    for (const bool convex : {false, true}) {
      const TestMesh& local = convex ? sphere : plane;
      const TestMesh mesh = placed(local, static_cast<float>(place.frame.scale), glm::vec3(place.frame.offset));
      std::mt19937 rng(convex ? 41 : 17);
      const auto samples = convex ? sphereSamples(count, rng) : planeSamples(count, rng);
      const bvh::GpuBvh bvh = bvh::buildGpuBvh(mesh.positions, mesh.triangles, bvh::BuildOptions{});
      ASSERT_EQ(bvh.report.trianglesDropped, 0u) << mesh.name << " " << place.name;
      gpu::Renderer renderer(test::sharedContext(), toScene(mesh));
      for (const bool onGpu : {false, true}) {
        const Counts c = runSamples(mesh, convex, place.frame, samples, onGpu ? gpuTracer(renderer) : cpuTracer(bvh));
        report(onGpu ? "gpu" : "cpu", local.name, place.name, c);
        expectClean(c, std::string(onGpu ? "gpu " : "cpu ") + local.name + " " + place.name);
        controlAcne += c.controlAcne;
        controlSelfHits += c.controlMirrorSelfHits;
        lit += c.shouldBeLit;
        shadowed += c.shouldBeShadowed;
      }
    }
  }
  std::printf(
      "total: %llu lit and %llu shadowed samples checked; control without offset: %llu acne, %llu mirror "
      "self-hits\n",
      (unsigned long long)lit, (unsigned long long)shadowed, (unsigned long long)controlAcne,
      (unsigned long long)controlSelfHits);
  EXPECT_GT(controlAcne + controlSelfHits, 0u) << "spawning at the hit point itself should self-intersect somewhere";
}

}  // namespace
}  // namespace ht::accuracy
