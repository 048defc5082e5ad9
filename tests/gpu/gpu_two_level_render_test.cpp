// gpu_two_level_render_test.cpp - the renderer on the two-level BVH (docs/BVH.md §9, docs/REUSE.md §3): frames equal
// the flattened BVH's frames bit for bit (mirrors, glass, shadows, several instances of one mesh, shadow rays that
// skip the convex node they leave), before and after random node moves served by Renderer::moveNodes without a
// rebuild; its closest hits equal the CPU reference's.
#include <gtest/gtest.h>

#include <cstring>
#include <random>
#include <string>
#include <vector>

#include <glm/gtc/matrix_transform.hpp>

#include "bvh/cpu_traversal.h"
#include "gpu/scene_bvh.h"
#include "gpu_test_util.h"
#include "scene/convex_sides.h"
#include "scene/mesh_generators.h"
#include "scene/scene_edits.h"

namespace ht::test {
namespace {

// Appends an icosphere as node `name` instancing glTF-style mesh `mesh` (same subdivisions = same triangles).
void addSphereNode(Scene& s, const std::string& name, std::int32_t mesh, glm::vec3 centre, float radius,
                   std::uint32_t material) {
  SceneNode node;
  node.name = name;
  node.mesh = mesh;
  node.firstVertex = static_cast<std::uint32_t>(s.positions.size());
  const TriangleRange r = makeIcosphere(s, glm::vec3(0.0f), radius, 2, material);
  node.firstTriangle = static_cast<std::uint32_t>(r.first);
  node.triangleCount = static_cast<std::uint32_t>(r.count);
  node.vertexCount = static_cast<std::uint32_t>(s.positions.size()) - node.firstVertex;
  s.nodes.push_back(node);
  setNodeWorldMatrix(s, name, glm::translate(glm::dmat4(1.0), glm::dvec3(centre)));
}

// Three diffuse instances of one mesh, a mirror, a glass ball, a floor, a sun and a point light.
Scene instancedScene() {
  Scene s;
  s.name = "test:two-level";
  const DiffuseMirrorGlass materials = addDiffuseMirrorGlass(s);
  const std::uint32_t d = materials.diffuse, m = materials.mirror, g = materials.glass;
  addSphereNode(s, "ball0", 0, glm::vec3(-0.4f, -0.1f, 0.0f), 0.2f, d);
  addSphereNode(s, "ball1", 0, glm::vec3(0.0f, -0.1f, -0.3f), 0.2f, d);
  addSphereNode(s, "ball2", 0, glm::vec3(0.4f, -0.1f, 0.1f), 0.2f, d);
  addSphereNode(s, "mirror", 1, glm::vec3(0.1f, 0.25f, -0.2f), 0.25f, m);
  addSphereNode(s, "glass", 2, glm::vec3(-0.05f, -0.15f, 0.35f), 0.15f, g);
  makeQuad(s, glm::vec3(0.0f, -0.3f, 0.0f), glm::vec3(1.0f, 0.0f, 0.0f), glm::vec3(0.0f, 0.0f, -1.0f), d);
  Light sun;
  sun.type = Light::Type::Directional;
  sun.direction = glm::normalize(glm::vec3(0.3f, -1.0f, -0.4f));
  sun.intensity = 2.0f;
  s.lights.push_back(sun);
  Light lamp;
  lamp.position = glm::vec3(0.3f, 0.8f, 0.6f);
  lamp.intensity = 1.5f;
  s.lights.push_back(lamp);
  markConvexNodes(s);  // the balls: their shadow rays skip them (docs/BVH.md §9.6)
  return s;
}

gpu::RenderSettings settings() {
  gpu::RenderSettings s;
  s.spp = 2;
  s.maxDepth = 4;
  return s;
}

const gpu_shared::PinholeParams kCamera =
    lookAt(glm::vec3(0.2f, 0.5f, 1.6f), glm::vec3(0.0f, -0.1f, 0.0f), 45.0f, 64, 48);

gpu::RenderResult renderFlattened(const Scene& s) {
  gpu::Renderer renderer(sharedContext(), s, gpu::buildSceneBvh(s, {}, gpu::BvhLayoutPolicy::Flattened));
  EXPECT_EQ(renderer.bvhStats().layout, bvh::BvhLayout::Flattened);
  return renderer.render(kCamera, settings());
}

void expectSameBits(const gpu::RenderResult& a, const gpu::RenderResult& b, const std::string& what) {
  ASSERT_EQ(a.rgba.size(), b.rgba.size()) << what;
  size_t differing = 0;
  for (size_t i = 0; i < a.rgba.size(); ++i) differing += std::memcmp(&a.rgba[i], &b.rgba[i], sizeof(float)) != 0;
  EXPECT_EQ(differing, 0u) << what << ": floats differing of " << a.rgba.size();
}

// The two-level renderer's closest hits == the CPU two-level reference == the CPU flattened reference, bit for bit.
void expectHitParity(gpu::Renderer& renderer, const Scene& s) {
  const std::vector<gpu_shared::HtRay> rays = pinholeRays(kCamera);
  const std::vector<gpu_shared::HtHit> gpu = renderer.traceClosest(rays);
  const bvh::TwoLevelBvh cpu(s.positions, s.triangles, gpu::instanceRanges(s));
  const bvh::GpuBvh flat = bvh::buildGpuBvh(s.positions, s.triangles, {});
  size_t hits = 0;
  for (size_t i = 0; i < rays.size(); ++i) {
    const gpu_shared::HtHit twoLevel = bvh::traceClosestTwoLevel(cpu, rays[i]).hit;
    const gpu_shared::HtHit flattened = bvh::traceClosest(flat, rays[i]).hit;
    ASSERT_EQ(std::memcmp(&gpu[i], &twoLevel, sizeof twoLevel), 0) << "ray " << i;
    ASSERT_EQ(std::memcmp(&gpu[i], &flattened, sizeof flattened), 0) << "ray " << i;
    hits += flattened.triId != gpu_shared::HT_MISS;
  }
  EXPECT_GT(hits, rays.size() / 4);
}

TEST(GpuTwoLevelRender, FramesEqualTheFlattenedBvhBeforeAndAfterRandomMovesWithoutRebuilds) {
  Scene scene = instancedScene();
  gpu::Renderer twoLevel(sharedContext(), scene, gpu::buildSceneBvh(scene, {}, gpu::BvhLayoutPolicy::TwoLevel));
  ASSERT_EQ(twoLevel.bvhStats().layout, bvh::BvhLayout::TwoLevel);
  expectSameBits(twoLevel.render(kCamera, settings()), renderFlattened(scene), "static scene");
  expectHitParity(twoLevel, scene);

  std::mt19937 rng(16);
  std::uniform_real_distribution<double> offset(-0.15, 0.15), angle(-3.1, 3.1);
  const char* names[] = {"ball0", "ball1", "ball2", "mirror", "glass"};
  for (int edit = 0; edit < 3; ++edit) {
    const std::uint32_t node = static_cast<std::uint32_t>(rng() % 5);
    const glm::dmat4 world =
        glm::rotate(glm::translate(scene.nodes[node].world, glm::dvec3(offset(rng), offset(rng) * 0.3, offset(rng))),
                    angle(rng), glm::normalize(glm::dvec3(0.3, 1.0, 0.2)));
    setNodeWorldMatrix(scene, names[node], world);
    const std::uint32_t moved[] = {node};
    twoLevel.moveNodes(scene, moved);
    const std::string what = "after move " + std::to_string(edit) + " of " + names[node];
    expectSameBits(twoLevel.render(kCamera, settings()), renderFlattened(scene), what);
  }
  expectHitParity(twoLevel, scene);
  const gpu::BvhStats stats = twoLevel.bvhStats();
  EXPECT_EQ(stats.fullBuilds, 1u) << "a node move on the two-level BVH must not rebuild";
  EXPECT_EQ(stats.instanceUpdates, 3u);
}

// A node marked convex lets the rays that leave it on its outside skip it, on both layouts (the bottom level, the
// tagged triangles): shadow rays, reflections, refractions out of the glass ball. On the instanced scene the marks
// change no bit: no ball can shadow or reflect itself. A false mark shows that the skip is real: a floor and a roof
// over it in one node, marked convex, lose the roof's shadow.
TEST(GpuTwoLevelRender, RaysSkipTheConvexNodeTheyLeaveOnBothLayouts) {
  const Scene marked = instancedScene();
  ASSERT_EQ(marked.nodes[0].convexSides, kConvexFront);
  Scene unmarked = marked;
  for (SceneNode& node : unmarked.nodes) node.convexSides = 0;
  expectSameBits(renderFlattened(marked), renderFlattened(unmarked), "the marks, flattened");

  Scene shelter;
  shelter.name = "test:shelter";
  const std::uint32_t d = addDiffuseMirrorGlass(shelter).diffuse;
  SceneNode node;
  node.name = "shelter";
  makeQuad(shelter, glm::vec3(0.0f, -0.3f, 0.0f), glm::vec3(1.0f, 0.0f, 0.0f), glm::vec3(0.0f, 0.0f, -1.0f), d);
  makeQuad(shelter, glm::vec3(0.0f, 0.1f, 0.0f), glm::vec3(0.25f, 0.0f, 0.0f), glm::vec3(0.0f, 0.0f, -0.25f), d);
  node.vertexCount = static_cast<std::uint32_t>(shelter.positions.size());
  node.triangleCount = static_cast<std::uint32_t>(shelter.triangles.size());
  shelter.nodes.push_back(node);
  Light sun;
  sun.type = Light::Type::Directional;
  sun.direction = glm::normalize(glm::vec3(0.6f, -1.0f, 0.2f));  // the roof's shadow falls beside it
  sun.intensity = 2.0f;
  shelter.lights.push_back(sun);
  markConvexNodes(shelter);
  ASSERT_EQ(shelter.nodes[0].convexSides, 0);
  const gpu::RenderResult truthful = renderFlattened(shelter);
  shelter.nodes[0].convexSides = kConvexFront;  // false: the floor's shadow rays now skip the roof
  const gpu::RenderResult flattened = renderFlattened(shelter);
  gpu::Renderer twoLevel(sharedContext(), shelter, gpu::buildSceneBvh(shelter, {}, gpu::BvhLayoutPolicy::TwoLevel));
  expectSameBits(twoLevel.render(kCamera, settings()), flattened, "the false mark, two-level");
  ASSERT_EQ(truthful.rgba.size(), flattened.rgba.size());
  size_t lit = 0, darker = 0;
  for (size_t i = 0; i < truthful.rgba.size(); ++i) {
    lit += flattened.rgba[i] > truthful.rgba[i];
    darker += flattened.rgba[i] < truthful.rgba[i];
  }
  EXPECT_GT(lit, truthful.rgba.size() / 50) << "the roof's shadow should be gone";
  EXPECT_EQ(darker, 0u);
}

TEST(GpuTwoLevelRender, AMoveOnTheFlattenedBvhSwitchesToTwoLevelOnceThenUpdates) {
  Scene scene = instancedScene();
  gpu::Renderer renderer(sharedContext(), scene, gpu::buildSceneBvh(scene, {}, gpu::BvhLayoutPolicy::Flattened));
  const std::uint32_t moved[] = {1};
  for (int k = 1; k <= 2; ++k) {
    setNodeWorldMatrix(scene, "ball1", glm::translate(glm::dmat4(1.0), glm::dvec3(0.05 * k, -0.1, -0.3)));
    renderer.moveNodes(scene, moved);
  }
  const gpu::BvhStats stats = renderer.bvhStats();
  EXPECT_EQ(stats.layout, bvh::BvhLayout::TwoLevel);
  EXPECT_EQ(stats.fullBuilds, 2u);  // construction + the switch
  EXPECT_EQ(stats.instanceUpdates, 1u);
  expectSameBits(renderer.render(kCamera, settings()), renderFlattened(scene), "after the switch and a move");
}

}  // namespace
}  // namespace ht::test
