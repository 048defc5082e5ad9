#include "interior_rays.h"

#include <cmath>
#include <numbers>
#include <random>

namespace ht::accuracy {
namespace {

using gpu_shared::HtRay;

// Uniform direction on the unit sphere (z = cos theta uniform, Archimedes' hat-box theorem).
glm::dvec3 uniformDirection(std::mt19937_64& rng) {
  std::uniform_real_distribution<double> unit(-1.0, 1.0), angle(0.0, 2.0 * std::numbers::pi);
  const double z = unit(rng), phi = angle(rng), r = std::sqrt(std::max(0.0, 1.0 - z * z));
  return {r * std::cos(phi), r * std::sin(phi), z};
}

// A point inside the mesh's interior region, in local units (before placement).
glm::dvec3 localInteriorPoint(const Interior& interior, std::mt19937_64& rng) {
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  const double radius = interior.radius * std::cbrt(unit(rng));  // uniform in the ball
  const glm::dvec3 inBall = uniformDirection(rng) * radius;
  if (interior.kind == Interior::Kind::Ball) return inBall;
  const double a = 2.0 * std::numbers::pi * unit(rng);
  return glm::dvec3(interior.circleRadius * std::cos(a), 0.0, interior.circleRadius * std::sin(a)) + inBall;
}

glm::vec3 interiorOrigin(const TestMesh& mesh, std::mt19937_64& rng) {
  const glm::dvec3 local = localInteriorPoint(mesh.interior, rng);
  return glm::vec3(local * double(mesh.scale) + glm::dvec3(mesh.offset));
}

glm::vec3 direction(const TestMesh& mesh, RayKind kind, glm::vec3 origin, std::mt19937_64& rng) {
  std::uniform_int_distribution<size_t> pickTri(0, mesh.triangles.size() - 1);
  std::uniform_int_distribution<int> pickCorner(0, 2), pickAxis(0, 5);
  switch (kind) {
    case RayKind::Vertex: {
      const glm::uvec3 tri = mesh.triangles[pickTri(rng)];
      return mesh.positions[tri[pickCorner(rng)]] - origin;
    }
    case RayKind::Edge: {
      const glm::uvec3 tri = mesh.triangles[pickTri(rng)];
      const int k = pickCorner(rng);
      const glm::vec3 mid = 0.5f * (mesh.positions[tri[k]] + mesh.positions[tri[(k + 1) % 3]]);
      return mid - origin;
    }
    case RayKind::Axis: {
      const int a = pickAxis(rng);
      glm::vec3 d(0.0f);
      d[a % 3] = a < 3 ? 1.0f : -1.0f;
      return d;
    }
    case RayKind::ZeroComp: {
      glm::vec3 d = glm::vec3(uniformDirection(rng));
      d[pickCorner(rng)] = 0.0f;
      return d;
    }
    default: return glm::vec3(uniformDirection(rng));
  }
}

}  // namespace

std::string rayKindName(RayKind kind) {
  static const char* const kNames[] = {"random", "vertex", "edge", "axis", "zero-component"};
  return kNames[static_cast<uint32_t>(kind)];
}

std::vector<HtRay> interiorRays(const TestMesh& mesh, RayKind kind, uint32_t count, uint32_t seed) {
  std::mt19937_64 rng(seed * 0x9E3779B97F4A7C15ull + static_cast<uint64_t>(kind));
  std::vector<HtRay> rays;
  rays.reserve(count);
  while (rays.size() < count) {
    const glm::vec3 o = interiorOrigin(mesh, rng);
    const glm::vec3 d = direction(mesh, kind, o, rng);
    if (d == glm::vec3(0.0f)) continue;  // the origin rounded onto the aimed-at point: not a ray
    rays.push_back(HtRay{o, 0.0f, d, 3.0e38f});
  }
  return rays;
}

std::vector<HtRay> mixedInteriorRays(const TestMesh& mesh, uint32_t count, uint32_t seed) {
  const auto kinds = static_cast<uint32_t>(RayKind::Count);
  std::vector<HtRay> rays;
  rays.reserve(count);
  for (uint32_t k = kinds; k-- > 0;) {
    const uint32_t n = k == 0 ? count - static_cast<uint32_t>(rays.size()) : count / kinds;
    auto part = interiorRays(mesh, static_cast<RayKind>(k), n, seed);
    rays.insert(rays.end(), part.begin(), part.end());
  }
  return rays;
}

}  // namespace ht::accuracy
