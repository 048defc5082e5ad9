// builtin_scenes_test.cpp - procedural generators and the built-in scenes: features, framing, closed
// outward-facing meshes, and the mirror-test geometry checked by brute-force ray casting.
#include <gtest/gtest.h>

#include <cmath>
#include <map>
#include <optional>

#include "common/error.h"
#include "scene/builtin_scenes.h"
#include "scene/load_scene.h"
#include "scene/mesh_generators.h"
#include "scene_test_util.h"

namespace ht {
namespace {

// Every undirected edge used by exactly two triangles, in opposite directions (closed, consistently wound).
void expectClosedAndConsistent(const Scene& s, std::size_t first, std::size_t count) {
  std::map<std::pair<std::uint32_t, std::uint32_t>, int> directed;
  for (std::size_t i = first; i < first + count; ++i)
    for (int k = 0; k < 3; ++k) ++directed[{s.triangles[i][k], s.triangles[i][(k + 1) % 3]}];
  for (const auto& [edge, n] : directed) {
    EXPECT_EQ(n, 1) << "directed edge used twice";
    EXPECT_EQ(directed.count({edge.second, edge.first}), 1u) << "boundary edge";
  }
}

TEST(SceneGenerators, IcosphereIsClosedAndOutwardFacing) {
  Scene s;
  const glm::vec3 c(1, 2, 3);
  const TriangleRange r = makeIcosphere(s, c, 2.0f, 3, addMaterial(s, Material{}));
  EXPECT_EQ(r.count, 20u * 64u);                  // 20 * 4^3
  EXPECT_EQ(s.positions.size(), 10u * 64u + 2u);  // V = 10 * 4^n + 2 for a subdivided icosahedron
  expectClosedAndConsistent(s, r.first, r.count);
  for (const glm::vec3& p : s.positions) EXPECT_NEAR(glm::length(p - c), 2.0f, 1e-5f);
  for (const glm::uvec3& t : s.triangles) {
    const glm::vec3 centroid = (s.positions[t.x] + s.positions[t.y] + s.positions[t.z]) / 3.0f;
    EXPECT_GT(glm::dot(test::geometricNormal(s.positions, t), centroid - c), 0.0f);
  }
  ASSERT_EQ(s.normals.size(), s.positions.size());
  for (std::size_t i = 0; i < s.positions.size(); ++i)
    EXPECT_NEAR(glm::dot(s.normals[i], glm::normalize(s.positions[i] - c)), 1.0f, 1e-5f);
}

TEST(SceneGenerators, BoxIsClosedOutwardAndSized) {
  Scene s;
  const TriangleRange r = makeBox(s, {1, 0, 0}, {1, 2, 3}, addMaterial(s, Material{}));
  EXPECT_EQ(r.count, 12u);
  const Bounds3 b = s.bounds();
  EXPECT_EQ(b.lo, glm::vec3(0, -2, -3));
  EXPECT_EQ(b.hi, glm::vec3(2, 2, 3));
  for (const glm::uvec3& t : s.triangles) {
    const glm::vec3 centroid = (s.positions[t.x] + s.positions[t.y] + s.positions[t.z]) / 3.0f;
    const glm::vec3 n = test::geometricNormal(s.positions, t);
    EXPECT_GT(glm::dot(n, centroid - glm::vec3(1, 0, 0)), 0.0f);
    EXPECT_GT(glm::dot(n, s.normals[t.x]), 0.0f);  // shading normal agrees with the winding
  }
  // 24 vertices (4 per face, flat normals); welding them by position must give a closed surface.
  Scene welded;
  std::map<std::tuple<float, float, float>, std::uint32_t> ids;
  for (const glm::vec3& p : s.positions) ids.try_emplace({p.x, p.y, p.z}, static_cast<std::uint32_t>(ids.size()));
  for (const glm::uvec3& t : s.triangles) {
    glm::uvec3 w;
    for (int k = 0; k < 3; ++k) w[k] = ids[{s.positions[t[k]].x, s.positions[t[k]].y, s.positions[t[k]].z}];
    welded.triangles.push_back(w);
  }
  EXPECT_EQ(ids.size(), 8u);
  expectClosedAndConsistent(welded, 0, 12);
}

TEST(SceneGenerators, QuadFacesCrossOfItsHalfEdges) {
  Scene s;
  makeQuad(s, {0, 0, 0}, {0, 0, 1}, {1, 0, 0}, addMaterial(s, Material{}));  // z x x = +y
  for (const glm::uvec3& t : s.triangles) EXPECT_GT(test::geometricNormal(s.positions, t).y, 0.0f);
  EXPECT_EQ(s.normals[0], glm::vec3(0, 1, 0));
  EXPECT_EQ(s.texcoords[2], glm::vec2(1, 1));
}

TEST(SceneGenerators, CheckerTextureAlternates) {
  Scene s;
  const int t = addCheckerTexture(s, "c", 4, 2, glm::vec3(1), glm::vec3(0));
  const Texture& tex = s.textures[static_cast<std::size_t>(t)];
  EXPECT_EQ(tex.texels[0], glm::vec4(1, 1, 1, 1));   // cell (0,0)
  EXPECT_EQ(tex.texels[2], glm::vec4(0, 0, 0, 1));   // cell (1,0)
  EXPECT_EQ(tex.texels[10], glm::vec4(1, 1, 1, 1));  // cell (1,1)
}

void expectWellFormed(const Scene& s) {
  EXPECT_FALSE(s.materials.empty());
  EXPECT_EQ(s.triangleMaterial.size(), s.triangles.size());
  EXPECT_TRUE(s.normals.empty() || s.normals.size() == s.positions.size());
  EXPECT_TRUE(s.texcoords.empty() || s.texcoords.size() == s.positions.size());
  for (const glm::uvec3& t : s.triangles)
    for (int k = 0; k < 3; ++k) ASSERT_LT(t[k], s.positions.size());
  for (std::uint32_t m : s.triangleMaterial) ASSERT_LT(m, s.materials.size());
  for (const Material& m : s.materials)
    if (m.baseColorTexture >= 0) { EXPECT_LT(static_cast<std::size_t>(m.baseColorTexture), s.textures.size()); }
  for (const Light& l : s.lights) EXPECT_NEAR(glm::length(l.direction), 1.0f, 1e-5f);
}

TEST(SceneBuiltin, EveryNameLoadsWellFormedAndCentred) {
  const std::vector<std::string> names = builtinSceneNames();
  EXPECT_EQ(names.size(), 4u);
  for (const std::string& name : names) {
    SCOPED_TRACE(name);
    SceneLoadReport report;
    const Scene s = loadScene(name, report);
    EXPECT_EQ(s.name, name);
    expectWellFormed(s);
    EXPECT_EQ(report.triangles, s.triangles.size());
    const glm::vec3 c = s.bounds().center();
    EXPECT_LT(glm::length(c), 1e-4f);  // focal plane at the bounds centre = z = 0
  }
}

TEST(SceneBuiltin, ShowcaseHasEveryFeatureAndDepthOnBothSides) {
  const Scene s = loadScene("builtin:showcase");
  const SceneFeatures f = s.features();
  EXPECT_TRUE(f.lights);
  EXPECT_TRUE(f.mirrors);
  EXPECT_TRUE(f.glass);
  EXPECT_TRUE(f.textures);
  EXPECT_TRUE(f.emissive);
  bool point = false, directional = false, front = false, behind = false;
  for (const Light& l : s.lights) {
    point |= l.type == Light::Type::Point;
    directional |= l.type == Light::Type::Directional;
  }
  EXPECT_TRUE(point && directional);
  for (std::size_t i = 0; i < s.triangles.size(); ++i) {
    const Material& m = s.materials[s.triangleMaterial[i]];
    if (m.kind() == MaterialKind::Diffuse && m.baseColorTexture < 0 && m.name != "wall") {
      const float z = s.positions[s.triangles[i].x].z;
      front |= z > 0.1f;
      behind |= z < -0.1f;
    }
  }
  EXPECT_TRUE(front && behind);
  for (const Material& m : s.materials)
    if (m.kind() == MaterialKind::Glass) { EXPECT_FLOAT_EQ(m.ior, 1.5f); }
}

TEST(SceneBuiltin, PlainHasNoFeatures) {
  const SceneFeatures f = loadScene("builtin:plain").features();
  EXPECT_FALSE(f.lights || f.mirrors || f.glass || f.textures || f.emissive);
}

TEST(SceneBuiltin, SphereIsAFineUnitIcosphereAtTheOrigin) {
  const Scene s = loadScene("builtin:sphere");
  EXPECT_GE(s.triangles.size(), 20480u);
  ASSERT_EQ(s.materials.size(), 1u);
  EXPECT_EQ(s.materials[0].kind(), MaterialKind::Diffuse);
  for (const glm::vec3& p : s.positions) ASSERT_NEAR(glm::length(p), 1.0f, 1e-5f);
  EXPECT_TRUE(s.lights.empty());
}

TEST(SceneBuiltin, UnknownNameListsTheBuiltins) {
  try {
    loadScene("builtin:teapot");
    FAIL() << "expected SceneError";
  } catch (const SceneError& e) {
    EXPECT_EQ(e.file(), "builtin:teapot");
    EXPECT_NE(std::string(e.what()).find("builtin:showcase"), std::string::npos);
  }
}

TEST(SceneBuiltin, UnsupportedExtensionListsTheSupportedOnes) {
  try {
    loadScene("model.fbx");
    FAIL() << "expected SceneError";
  } catch (const SceneError& e) {
    EXPECT_EQ(e.file(), "model.fbx");
    EXPECT_NE(std::string(e.what()).find(".gltf"), std::string::npos);
    EXPECT_NE(std::string(e.what()).find("builtin:sphere"), std::string::npos);
  }
}

// ---- mirror-test: brute-force ray casting (Moller-Trumbore, "Fast, Minimum Storage Ray/Triangle
// Intersection", JGT 1997) over every triangle ----

struct Hit {
  float t;
  std::size_t triangle;
};

std::optional<Hit> closestHit(const Scene& s, glm::vec3 o, glm::vec3 d) {
  std::optional<Hit> best;
  for (std::size_t i = 0; i < s.triangles.size(); ++i) {
    const glm::vec3 a = s.positions[s.triangles[i].x], b = s.positions[s.triangles[i].y],
                    c = s.positions[s.triangles[i].z];
    const glm::vec3 e1 = b - a, e2 = c - a, p = glm::cross(d, e2);
    const float det = glm::dot(e1, p);
    if (std::fabs(det) < 1e-12f) continue;
    const glm::vec3 tv = o - a;
    const float u = glm::dot(tv, p) / det;
    const glm::vec3 q = glm::cross(tv, e1);
    const float v = glm::dot(d, q) / det;
    const float t = glm::dot(e2, q) / det;
    if (u < 0 || v < 0 || u + v > 1 || t <= 1e-4f) continue;
    if (!best || t < best->t) best = Hit{t, i};
  }
  return best;
}

const Material& materialOf(const Scene& s, const Hit& h) { return s.materials[s.triangleMaterial[h.triangle]]; }

// What a ray from `o` along `d` sees after at most one mirror bounce: the material of the last surface
// hit, or nullptr for the background.
const Material* traceOneBounce(const Scene& s, glm::vec3 o, glm::vec3 d) {
  const auto hit = closestHit(s, o, d);
  if (!hit) return nullptr;
  const Material& m = materialOf(s, *hit);
  if (m.kind() != MaterialKind::Mirror) return &m;
  const glm::vec3 n = glm::normalize(test::geometricNormal(s.positions, s.triangles[hit->triangle]));
  const glm::vec3 r = d - 2.0f * glm::dot(d, n) * n;  // mirror reflection
  const auto second = closestHit(s, o + hit->t * d, r);
  return second ? &materialOf(s, *second) : nullptr;
}

TEST(SceneBuiltin, MirrorTestEmitterIsVisibleOnlyThroughTheMirror) {
  const Scene s = loadScene("builtin:mirror-test");
  const SceneFeatures f = s.features();
  EXPECT_TRUE(f.mirrors && f.emissive);
  EXPECT_FALSE(f.glass || f.lights);

  // Looking Glass default framing: targetDiam 2, fovy 14 deg -> camera distance D = 1 / tan(7 deg).
  const float D = 1.0f / std::tan(glm::radians(7.0f));
  const glm::vec3 eye(0, 0, D);
  // The image centre (and points within the 0.75-radius disc) show the emitter via the mirror.
  for (const glm::vec2 p : {glm::vec2(0, 0), glm::vec2(0.3f, 0.2f), glm::vec2(-0.2f, -0.5f)}) {
    const glm::vec3 d = glm::normalize(glm::vec3(p, 0) - eye);
    ASSERT_EQ(materialOf(s, *closestHit(s, eye, d)).kind(), MaterialKind::Mirror);
    const Material* seen = traceOneBounce(s, eye, d);
    ASSERT_NE(seen, nullptr);
    EXPECT_GT(seen->emissive.x, 0.5f) << "point " << p.x << "," << p.y;
  }
  // Outside the disc the mirror shows the background.
  EXPECT_EQ(traceOneBounce(s, eye, glm::normalize(glm::vec3(0.0f, -0.95f, 0.0f) - eye)), nullptr);
  // No primary ray inside the frame (|x| <= 0.75, |y| <= 1 on the focal plane) hits the emitter directly.
  for (float y = -1.0f; y <= 1.0f; y += 0.1f)
    for (float x = -0.75f; x <= 0.75f; x += 0.25f) {
      const auto hit = closestHit(s, eye, glm::normalize(glm::vec3(x, y, 0) - eye));
      if (hit) { EXPECT_EQ(materialOf(s, *hit).kind(), MaterialKind::Mirror); }
    }
}

}  // namespace
}  // namespace ht
