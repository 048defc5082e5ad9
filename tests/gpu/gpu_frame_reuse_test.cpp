// Frame reuse after edits (RenderSettings::reuse, gpu/frame_reuse.h, docs/REUSE.md §3-4): a frame after a light edit
// re-shades the cached primary hits, a frame after a node move re-traces only the targets whose recorded segment
// cells meet the moved bounds; both equal a full render of the edited scene by a fresh Renderer, bit for bit, on
// builtin:showcase (mirror, glass, textures, a point light and a sun casting shadows) through several display models.
// Plus the C++ reference of the segment cells (conservative against an exact segment-box test) and of the marking
// pass (the GPU's dirty list == the CPU's from the same masks).
#include <gtest/gtest.h>

#include <algorithm>
#include <cstdio>
#include <cstring>
#include <random>

#include "bvh/offset_ray.h"
#include "camera_models/display_config.h"
#include "camera_models/lenticular_params.h"
#include "gpu/display_camera.h"
#include "gpu/frame_reuse.h"
#include "gpu/gpu_scene.h"
#include "gpu/segment_cells.h"
#include "gpu_test_util.h"
#include "scene/load_scene.h"
#include "scene/mesh_generators.h"
#include "scene/scene_edits.h"

namespace ht::test {
namespace {

using gpu::FrameReuse;

bool sameBits(const gpu::RenderResult& a, const gpu::RenderResult& b) {
  return a.rgba.size() == b.rgba.size() && std::memcmp(a.rgba.data(), b.rgba.data(), a.rgba.size() * 4) == 0;
}

double stageMs(const gpu::RenderResult& r, const std::string& name) {
  for (const gpu::StageTiming& s : r.stages) {
    if (s.name == name) return s.ms;
  }
  return 0.0;
}

gpu::RenderSettings reuseSettings() {
  gpu::RenderSettings s;
  s.spp = 2;
  s.maxDepth = 3;
  s.seed = 11;
  s.reuse = true;
  s.reuseMaxDirtyShare = 1.0;  // partial re-renders of any size (by default a move past 3/4 renders in full)
  return s;
}

// Small cameras of three display models around `scene`: a Portrait-calibrated lenticular panel (subpixel targets),
// a pinhole image and a 4-view projector array (pixel targets, several views).
std::vector<std::pair<std::string, gpu::FrameCamera>> cameras(const Scene& scene) {
  DisplayConfig portrait = builtinDisplay("portrait");
  portrait.calibration->screenW = 48;
  portrait.calibration->screenH = 36;
  const Bounds3 b = scene.bounds();
  const DisplayConfig wall = smallProjectorArray();
  return {{"lenticular", makeLenticularParams(portrait, b)},
          {"pinhole",
           lookAt(b.center() + glm::vec3(0.3f, 0.5f, 2.0f) * glm::length(b.extent()), b.center(), 35.0f, 40, 30)},
          {"projector-array", gpu::makeDisplayCamera(wall, b).camera}};
}

// A fresh Renderer's full frame of `scene`.
gpu::RenderResult fullRender(const Scene& scene, const gpu::FrameCamera& camera) {
  gpu::Renderer fresh(sharedContext(), scene);
  gpu::RenderSettings s = reuseSettings();
  s.reuse = false;
  return fresh.render(camera, s);
}

// How a test tells the renderer of a move: a rebuild (replaceSceneAfterMove) or the two-level BVH's refit and
// top-level update (moveNodes, holotraced's path).
enum class MoveThrough { Rebuild, TwoLevelUpdate };

// Moves `node` of `scene` by `by` and tells `renderer`, with the node's bounds before and after.
void moveNode(Scene& scene, const std::string& node, glm::dvec3 by, gpu::Renderer& renderer,
              MoveThrough through = MoveThrough::Rebuild) {
  const std::size_t index = *findNode(scene, node);
  const Bounds3 before = nodeWorldBounds(scene, index);
  const glm::vec4 beforeBall = nodeWorldBall(scene, index);
  glm::dmat4 world = scene.nodes[index].world;
  world[3] += glm::dvec4(by, 0.0);
  setNodeWorldMatrix(scene, node, world);
  if (through == MoveThrough::Rebuild) {
    renderer.replaceSceneAfterMove(scene, before, nodeWorldBounds(scene, index));
  } else {  // with the balls around the node (the marking pass's tighter test)
    const std::uint32_t nodes[] = {static_cast<std::uint32_t>(index)};
    renderer.moveNodes(
        scene, nodes, gpu::MovedBounds{before, nodeWorldBounds(scene, index), beforeBall, nodeWorldBall(scene, index)});
  }
}

// Edits light `light` of `edited`, tells `renderer` and renders the next frame, which re-shades the cached hits.
gpu::RenderResult relight(Scene& edited, std::size_t light, const LightEdit& edit, gpu::Renderer& renderer,
                          const gpu::FrameCamera& camera) {
  editLight(edited, light, edit);
  renderer.updateLights(edited);
  gpu::RenderResult r = renderer.render(camera, reuseSettings());
  EXPECT_EQ(r.reuse, FrameReuse::CachedPrimaryHits);
  return r;
}

// Colour and intensity edits leave every shadow ray where it was: its recorded occlusion holds, at every depth, and
// no ray is traced at all. A light switched off emits no shadow rays, so when it is switched on again its rays have
// no recorded occlusion and are traced; a light that moves has its rays traced too.
void expectLightEditsTraceOnlyTheRaysOfMovedOrRelitLights(const Scene& scene, Scene& edited, gpu::Renderer& renderer,
                                                          const gpu::FrameCamera& camera) {
  auto editAndRender = [&](std::size_t light, const LightEdit& edit) {
    gpu::RenderResult r = relight(edited, light, edit, renderer, camera);
    EXPECT_TRUE(sameBits(r, fullRender(edited, camera)));
    return r;
  };
  LightEdit tint;
  tint.color = glm::dvec3(0.6, 0.9, 1.0);
  tint.intensity = edited.lights[0].intensity * 0.7;
  EXPECT_EQ(editAndRender(0, tint).raysTraced, 0u);
  LightEdit off;
  off.intensity = 0.0;
  EXPECT_EQ(editAndRender(1, off).raysTraced, 0u);
  LightEdit on;
  on.intensity = scene.lights[1].intensity * 1.5;
  EXPECT_GT(editAndRender(1, on).raysTraced, 0u) << "the sun's rays were not emitted while it was off";
  EXPECT_EQ(editAndRender(1, on).raysTraced, 0u);
  LightEdit moved;
  moved.position = glm::dvec3(edited.lights[0].position) + glm::dvec3(-0.2, 0.1, 0.3);
  EXPECT_GT(editAndRender(0, moved).raysTraced, 0u);
  LightEdit turned;
  turned.direction = glm::normalize(glm::dvec3(0.3, -1.0, -0.2));
  EXPECT_GT(editAndRender(1, turned).raysTraced, 0u);
}

// Light values edited: no raygen and no closest-hit trace (primary and mirror/glass bounces come from the caches).
TEST(FrameReuse, LightEditsReshadeTheCachedPrimaryHitsBitForBit) {
  Scene scene = loadScene("builtin:showcase");
  ASSERT_GE(scene.lights.size(), 2u);
  for (const auto& [name, camera] : cameras(scene)) {
    SCOPED_TRACE(name);
    Scene edited = scene;
    gpu::Renderer renderer(sharedContext(), edited);
    const gpu::RenderResult first = renderer.render(camera, reuseSettings());
    EXPECT_EQ(first.reuse, FrameReuse::None);
    LightEdit moveAndTint;
    moveAndTint.position = glm::dvec3(edited.lights[0].position) + glm::dvec3(0.3, -0.1, 0.2);
    moveAndTint.color = glm::dvec3(1.0, 0.5, 0.25);
    moveAndTint.intensity = edited.lights[0].intensity * 1.7;
    editLight(edited, 0, moveAndTint);
    LightEdit dimSun;
    dimSun.intensity = edited.lights[1].intensity * 0.5;
    editLight(edited, 1, dimSun);
    renderer.updateLights(edited);
    const gpu::RenderResult reused = renderer.render(camera, reuseSettings());
    EXPECT_EQ(reused.reuse, FrameReuse::CachedPrimaryHits);
    EXPECT_EQ(stageMs(reused, "raygen"), 0.0);
    EXPECT_EQ(stageMs(reused, "trace"), 0.0) << "mirror and glass bounces come from the secondary cache too";
    EXPECT_GT(stageMs(first, "trace"), 0.0);
    const gpu::RenderResult reference = fullRender(edited, camera);
    EXPECT_TRUE(sameBits(reused, reference));
    EXPECT_FALSE(sameBits(reused, first)) << "the light edit changed nothing";
    // Unchanged since: the next frame also re-shades the cache, and is the same frame, tracing nothing.
    const gpu::RenderResult again = renderer.render(camera, reuseSettings());
    EXPECT_EQ(again.reuse, FrameReuse::CachedPrimaryHits);
    EXPECT_TRUE(sameBits(again, reference));
    EXPECT_EQ(again.raysTraced, 0u);
    expectLightEditsTraceOnlyTheRaysOfMovedOrRelitLights(scene, edited, renderer, camera);
  }
}

TEST(FrameReuse, OtherEditsAndOtherViewsRenderInFull) {
  Scene scene = loadScene("builtin:showcase");
  const auto cams = cameras(scene);
  const gpu::FrameCamera& camera = cams[1].second;
  gpu::Renderer renderer(sharedContext(), scene);
  renderer.render(camera, reuseSettings());
  glm::dmat4 lifted(1.0);
  lifted[3] = glm::dvec4(0.0, 0.3, 0.0, 1.0);
  setNodeWorldMatrix(scene, "green-sphere", lifted);
  renderer.replaceScene(scene);  // no bounds: nothing is kept
  gpu::RenderResult after = renderer.render(camera, reuseSettings());
  EXPECT_EQ(after.reuse, FrameReuse::None);
  EXPECT_TRUE(sameBits(after, fullRender(scene, camera)));
  gpu::RenderSettings otherSeed = reuseSettings();
  otherSeed.seed = 12;
  EXPECT_EQ(renderer.render(camera, otherSeed).reuse, FrameReuse::None);
  EXPECT_EQ(renderer.render(cams[0].second, otherSeed).reuse, FrameReuse::None);
  EXPECT_EQ(renderer.render(cams[0].second, otherSeed).reuse, FrameReuse::CachedPrimaryHits);
  gpu::RenderSettings off = otherSeed;
  off.reuse = false;
  EXPECT_EQ(renderer.render(cams[0].second, off).reuse, FrameReuse::None);
  EXPECT_EQ(renderer.render(cams[0].second, otherSeed).reuse, FrameReuse::None) << "a frame without reuse keeps none";
  // A light edit and a node move together: nothing is kept.
  LightEdit dim;
  dim.intensity = 1.0;
  editLight(scene, 0, dim);
  renderer.updateLights(scene);
  const Bounds3 old = nodeWorldBounds(scene, *findNode(scene, "green-sphere"));
  setNodeWorldMatrix(scene, "green-sphere", glm::dmat4(1.0));
  renderer.replaceSceneAfterMove(scene, old, nodeWorldBounds(scene, *findNode(scene, "green-sphere")));
  after = renderer.render(cams[0].second, otherSeed);
  EXPECT_EQ(after.reuse, FrameReuse::None);
}

// The property test of docs/REUSE.md §4: random moves of random nodes; each partial re-render equals a fresh full
// render of the edited scene bit for bit, and re-traces fewer targets than the frame has when the moved node is small;
// a light edit after the moves still re-shades the (updated) cached primary hits bit for bit.
// Random node moves, each followed by a partial re-render that must equal a fresh full render bit for bit, on the
// flattened BVH (rebuilt at each move, replaceSceneAfterMove) or on the two-level one (Renderer::moveNodes: refit and
// top level, the path holotraced takes; there some frames follow two moves, of one node or two).
void expectPartialRerendersEqualFullRenders(bool twoLevel) {
  Scene scene = loadScene("builtin:showcase");
  const auto cams = cameras(scene);
  std::mt19937 rng(twoLevel ? 4321 : 1234);
  std::uniform_real_distribution<double> offset(-0.25, 0.25);
  const std::vector<std::string> movable = {"mirror-sphere", "red-box", "green-sphere", "glass-sphere", "glow-sphere"};
  std::uint64_t traced = 0, total = 0;
  for (const auto& [name, camera] : cams) {
    SCOPED_TRACE(name);
    gpu::Renderer renderer(
        sharedContext(), scene,
        gpu::buildSceneBvh(scene, {}, twoLevel ? gpu::BvhLayoutPolicy::TwoLevel : gpu::BvhLayoutPolicy::Automatic));
    Scene edited = scene;
    const gpu::RenderResult first = renderer.render(camera, reuseSettings());
    ASSERT_EQ(first.reuse, FrameReuse::None);
    // A light moved first: its re-shaded frame adds the new shadow segments to the masks the moves are tested on.
    LightEdit shift;
    shift.position = glm::dvec3(edited.lights[0].position) + glm::dvec3(-0.4, 0.2, 0.1);
    editLight(edited, 0, shift);
    renderer.updateLights(edited);
    ASSERT_EQ(renderer.render(camera, reuseSettings()).reuse, FrameReuse::CachedPrimaryHits);
    for (int move = 0; move < 8; ++move) {
      const int moves = twoLevel && move % 3 == 2 ? 2 : 1;
      std::string nodes;
      for (int m = 0; m < moves; ++m) {
        const std::string node = movable[rng() % movable.size()];
        nodes += node + " ";
        const glm::dvec3 by(offset(rng), offset(rng), offset(rng));
        moveNode(edited, node, by, renderer, twoLevel ? MoveThrough::TwoLevelUpdate : MoveThrough::Rebuild);
      }
      SCOPED_TRACE(nodes + "move " + std::to_string(move));
      const gpu::RenderResult partial = renderer.render(camera, reuseSettings());
      EXPECT_EQ(partial.reuse, FrameReuse::PartialRetrace);
      EXPECT_TRUE(sameBits(partial, fullRender(edited, camera)));
      traced += partial.tracedTargets;
      total += frameShape(camera).targets();
    }
    // The partial re-renders kept the primary-hit cache up to date: a light edit now re-shades it.
    LightEdit warmer;
    warmer.color = glm::dvec3(1.0, 0.8, 0.6);
    const gpu::RenderResult lit = relight(edited, 0, warmer, renderer, camera);
    EXPECT_TRUE(sameBits(lit, fullRender(edited, camera)));
    // That frame traced the bounces again (the moves left their cache stale) and cached them and the occlusion of
    // their shadow rays: the next light edit traces nothing.
    warmer.intensity = 3.0;
    const gpu::RenderResult relit = relight(edited, 0, warmer, renderer, camera);
    EXPECT_EQ(stageMs(relit, "trace"), 0.0);
    EXPECT_EQ(relit.raysTraced, 0u);
    EXPECT_TRUE(sameBits(relit, fullRender(edited, camera)));
  }
  EXPECT_LT(traced, total) << "every target was re-traced: the masks select nothing";
}

TEST(FrameReuse, PartialRerenderAfterRandomNodeMovesEqualsAFullRender) {
  expectPartialRerendersEqualFullRenders(false);
}

TEST(FrameReuse, PartialRerenderAfterRandomNodeMovesOnTheTwoLevelBvhEqualsAFullRender) {
  expectPartialRerendersEqualFullRenders(true);
}

// A partial re-render's bounce rays that are their paths' cached rays, bit for bit, take the cached hits where their
// segments avoid the moved bounds, and walk only the moved instances from them where those hits are on none of them
// (docs/REUSE.md §4 "Bounce rays that take their cached hits"). The red box is seen in the mirror sphere and through
// the glass sphere, so the paths re-traced for it rebuild cached bounce rays. Moved back and forth, every frame
// equals a full render and the frame of a renderer that traces its bounce rays, bit for bit, and the cached hits
// spare rays.
TEST(FrameReuse, BounceRaysTakeTheirCachedHitsWhereTheMoveCannotHaveChangedThem) {
  Scene scene = loadScene("builtin:showcase");
  const std::size_t box = *findNode(scene, "red-box");
  for (const auto& [name, camera] : cameras(scene)) {
    SCOPED_TRACE(name);
    gpu::Renderer reusing(sharedContext(), scene, gpu::buildSceneBvh(scene, {}, gpu::BvhLayoutPolicy::TwoLevel));
    gpu::Renderer tracing(sharedContext(), scene, gpu::buildSceneBvh(scene, {}, gpu::BvhLayoutPolicy::TwoLevel));
    tracing.setBounceHitReuse(false);
    Scene edited = scene;
    ASSERT_EQ(reusing.render(camera, reuseSettings()).reuse, FrameReuse::None);
    ASSERT_EQ(tracing.render(camera, reuseSettings()).reuse, FrameReuse::None);
    std::uint64_t reusedRays = 0, tracedRays = 0;
    for (int move = 0; move < 4; ++move) {
      SCOPED_TRACE("move " + std::to_string(move));
      const Bounds3 before = nodeWorldBounds(edited, box);
      const glm::vec4 beforeBall = nodeWorldBall(edited, box);
      glm::dmat4 world = edited.nodes[box].world;
      world[3] += glm::dvec4(move % 2 ? -0.12 : 0.15, 0.0, move < 2 ? 0.04 : -0.03, 0.0);
      setNodeWorldMatrix(edited, "red-box", world);
      const std::uint32_t nodes[] = {static_cast<std::uint32_t>(box)};
      for (gpu::Renderer* r : {&reusing, &tracing}) {
        r->moveNodes(edited, nodes,
                     gpu::MovedBounds{before, nodeWorldBounds(edited, box), beforeBall, nodeWorldBall(edited, box)});
      }
      const gpu::RenderResult reused = reusing.render(camera, reuseSettings());
      const gpu::RenderResult traced = tracing.render(camera, reuseSettings());
      ASSERT_EQ(reused.reuse, FrameReuse::PartialRetrace);
      EXPECT_EQ(reused.tracedTargets, traced.tracedTargets);
      EXPECT_TRUE(sameBits(reused, traced));
      EXPECT_TRUE(sameBits(reused, fullRender(edited, camera)));
      reusedRays += reused.raysTraced;
      tracedRays += traced.raysTraced;
    }
    EXPECT_LT(reusedRays, tracedRays) << "no bounce ray took its cached hit";
  }
}

// RenderSettings::reuseMaxDirtyShare: a move whose marking pass lists more than that share of the targets renders
// the frame in full instead of re-rendering nearly all of it through the dirty list, which costs more. The room
// rises: the floor and walls, seen by almost every target, move. That frame records the state afresh, so the next,
// small move re-renders partially; with the share at 1 the same move re-renders partially too. Every frame equals a
// full render bit for bit.
TEST(FrameReuse, AMoveThatDirtiesMostTargetsRendersTheFrameInFull) {
  Scene scene = loadScene("builtin:showcase");
  for (const auto& [name, camera] : cameras(scene)) {
    if (name == "pinhole") continue;  // it sees the room from outside, with the background around it
    SCOPED_TRACE(name);
    for (const double share : {gpu::RenderSettings{}.reuseMaxDirtyShare, 1.0}) {
      SCOPED_TRACE("share " + std::to_string(share));
      gpu::RenderSettings settings = reuseSettings();
      settings.reuseMaxDirtyShare = share;
      Scene edited = scene;
      gpu::Renderer renderer(sharedContext(), edited, gpu::buildSceneBvh(edited, {}, gpu::BvhLayoutPolicy::TwoLevel));
      ASSERT_EQ(renderer.render(camera, settings).reuse, FrameReuse::None);
      const std::uint64_t targets = frameShape(camera).targets();
      moveNode(edited, "room", glm::dvec3(0.0, 0.05, 0.0), renderer, MoveThrough::TwoLevelUpdate);
      const gpu::RenderResult whole = renderer.render(camera, settings);
      EXPECT_EQ(whole.reuse, share < 1.0 ? FrameReuse::None : FrameReuse::PartialRetrace);
      EXPECT_GT(static_cast<double>(whole.tracedTargets), gpu::RenderSettings{}.reuseMaxDirtyShare * targets);
      EXPECT_TRUE(sameBits(whole, fullRender(edited, camera)));
      moveNode(edited, "glow-sphere", glm::dvec3(0.05, 0.02, 0.0), renderer, MoveThrough::TwoLevelUpdate);
      const gpu::RenderResult partial = renderer.render(camera, settings);
      EXPECT_EQ(partial.reuse, FrameReuse::PartialRetrace);
      EXPECT_LT(static_cast<double>(partial.tracedTargets), gpu::RenderSettings{}.reuseMaxDirtyShare * targets);
      EXPECT_TRUE(sameBits(partial, fullRender(edited, camera)));
    }
  }
}

// Through the staging path of a discrete GPU (VulkanContext::Options::mapDeviceMemory off: no buffer in device memory
// is mapped, so the scene's upload and each node move's upload go through staging buffers, the moves' through the
// one GpuScene keeps): the same frames, bit for bit, as the shared context's mapped memory gives, for full frames,
// partial re-renders after node moves on the two-level BVH and a light edit.
TEST(FrameReuse, TheStagingPathOfADiscreteGpuGivesTheSameFrames) {
  gpu::VulkanContext::Options options;
  options.mapDeviceMemory = false;
  gpu::VulkanContext unmapped(options);
  Scene scene = loadScene("builtin:showcase");
  const gpu::FrameCamera camera = cameras(scene)[2].second;  // the projector array: several views
  gpu::Renderer mapped(sharedContext(), scene, gpu::buildSceneBvh(scene, {}, gpu::BvhLayoutPolicy::TwoLevel));
  gpu::Renderer staged(unmapped, scene, gpu::buildSceneBvh(scene, {}, gpu::BvhLayoutPolicy::TwoLevel));
  auto expectSameFrames = [&](FrameReuse reuse) {
    const gpu::RenderResult a = staged.render(camera, reuseSettings()), b = mapped.render(camera, reuseSettings());
    EXPECT_EQ(a.reuse, reuse);
    EXPECT_EQ(b.reuse, reuse);
    EXPECT_TRUE(sameBits(a, b));
  };
  expectSameFrames(FrameReuse::None);
  std::mt19937 rng(77);
  std::uniform_real_distribution<double> offset(-0.2, 0.2);
  const char* movable[] = {"green-sphere", "glass-sphere", "glow-sphere"};
  for (int move = 0; move < 3; ++move) {
    SCOPED_TRACE("move " + std::to_string(move));
    const std::size_t index = *findNode(scene, movable[move]);
    const Bounds3 before = nodeWorldBounds(scene, index);
    glm::dmat4 world = scene.nodes[index].world;
    world[3] += glm::dvec4(offset(rng), offset(rng), offset(rng), 0.0);
    setNodeWorldMatrix(scene, movable[move], world);
    const std::uint32_t nodes[] = {static_cast<std::uint32_t>(index)};
    const gpu::MovedBounds bounds{before, nodeWorldBounds(scene, index)};
    staged.moveNodes(scene, nodes, bounds);
    mapped.moveNodes(scene, nodes, bounds);
    expectSameFrames(FrameReuse::PartialRetrace);
  }
  LightEdit dim;
  dim.intensity = scene.lights[1].intensity * 0.5;
  editLight(scene, 1, dim);
  staged.updateLights(scene);
  mapped.updateLights(scene);
  expectSameFrames(FrameReuse::CachedPrimaryHits);
  EXPECT_EQ(staged.bvhStats().fullBuilds, 1u);
}

// A light edit's frame records the cells of the shadow rays it traced, so a later move is tested against where the
// light is now. The lamp moves from the left to low on the right: the rays from the floor now run through the cells
// of a box on the right, whose shadow falls on floor that sees neither the box nor its cells. The box then rises,
// and that floor must be re-traced (with the old lamp's cells only, it was not).
TEST(FrameReuse, ALightEditRecordsItsShadowRaysForTheMovesAfter) {
  Scene scene;
  scene.name = "test:lamp-and-box";
  const std::uint32_t white = addDiffuseMirrorGlass(scene).diffuse;
  makeQuad(scene, glm::vec3(0.0f), glm::vec3(2.0f, 0.0f, 0.0f), glm::vec3(0.0f, 0.0f, -2.0f), white);
  SceneNode box;
  box.name = "box";
  box.firstVertex = static_cast<std::uint32_t>(scene.positions.size());
  const TriangleRange r = makeBox(scene, glm::vec3(0.0f), glm::vec3(0.15f), white);
  box.firstTriangle = static_cast<std::uint32_t>(r.first);
  box.triangleCount = static_cast<std::uint32_t>(r.count);
  box.vertexCount = static_cast<std::uint32_t>(scene.positions.size()) - box.firstVertex;
  scene.nodes.push_back(box);
  setNodeWorldMatrix(scene, "box", glm::translate(glm::dmat4(1.0), glm::dvec3(1.5, 0.2, 0.0)));
  Light lamp;
  lamp.position = glm::vec3(-1.5f, 1.0f, 0.0f);
  lamp.intensity = 2.0f;
  scene.lights.push_back(lamp);
  const gpu::FrameCamera camera = lookAt(glm::vec3(0.6f, 1.4f, 1.0f), glm::vec3(0.6f, 0.0f, 0.0f), 40.0f, 48, 36);

  gpu::Renderer renderer(sharedContext(), scene);
  Scene edited = scene;
  ASSERT_EQ(renderer.render(camera, reuseSettings()).reuse, FrameReuse::None);
  LightEdit lowRight;
  lowRight.position = glm::dvec3(1.95, 0.5, 0.0);
  const gpu::RenderResult lit = relight(edited, 0, lowRight, renderer, camera);
  moveNode(edited, "box", glm::dvec3(0.0, 0.12, 0.0), renderer);
  const gpu::RenderResult moved = renderer.render(camera, reuseSettings());
  EXPECT_EQ(moved.reuse, FrameReuse::PartialRetrace);
  EXPECT_FALSE(sameBits(moved, lit)) << "the box's shadow did not move in view";
  EXPECT_TRUE(sameBits(moved, fullRender(edited, camera)));
}

// The same over many batches: the secondary cache's queues are kept per batch, and the marking pass tests each
// batch's entries against its targets; partial re-renders and a light edit after them equal a full render.
TEST(FrameReuse, PartialRerenderOverManyBatchesEqualsAFullRender) {
  Scene scene = loadScene("builtin:showcase");
  const gpu::FrameCamera camera = cameras(scene)[0].second;
  gpu::RenderSettings batched = reuseSettings();
  batched.maxPathsPerBatch = 1024;
  ASSERT_GT(frameShape(camera).targets() * batched.spp, 8u * batched.maxPathsPerBatch);
  gpu::Renderer renderer(sharedContext(), scene);
  Scene edited = scene;
  ASSERT_EQ(renderer.render(camera, batched).reuse, FrameReuse::None);
  std::mt19937 rng(77);
  std::uniform_real_distribution<double> offset(-0.25, 0.25);
  for (const char* node : {"glass-sphere", "mirror-sphere", "green-sphere"}) {
    SCOPED_TRACE(node);
    moveNode(edited, node, glm::dvec3(offset(rng), offset(rng), offset(rng)), renderer);
    const gpu::RenderResult partial = renderer.render(camera, batched);
    EXPECT_EQ(partial.reuse, FrameReuse::PartialRetrace);
    EXPECT_LT(partial.tracedTargets, frameShape(camera).targets());
    EXPECT_TRUE(sameBits(partial, fullRender(edited, camera)));
  }
  LightEdit dim;
  dim.intensity = edited.lights[0].intensity * 0.5;
  editLight(edited, 0, dim);
  renderer.updateLights(edited);
  const gpu::RenderResult lit = renderer.render(camera, batched);
  EXPECT_EQ(lit.reuse, FrameReuse::CachedPrimaryHits);
  EXPECT_TRUE(sameBits(lit, fullRender(edited, camera)));
}

// The bounce cache packs the queues of every batch and depth one after the other (gpu/frame_reuse.h): a budget of
// exactly the entries a frame traces holds them all (a batch's worth per depth would need several times more), and
// the edits after it reuse them. One entry less overflows: that frame keeps no state, the next one of the view
// records without the cache (bounces by their cells), and every frame still equals a full render.
TEST(FrameReuse, TheBounceCacheHoldsTheQueuesPackedAndAnOverflowKeepsNoState) {
  const Scene scene = loadScene("builtin:showcase");
  const gpu::FrameCamera camera = cameras(scene)[0].second;
  gpu::RenderSettings batched = reuseSettings();
  batched.maxPathsPerBatch = 1024;  // queues of many batches
  std::uint64_t entries = 0;
  {
    gpu::Renderer probe(sharedContext(), scene);
    probe.render(camera, batched);
    entries = probe.reuseSnapshot().secondarySegments.size();
  }
  const std::uint64_t paths = frameShape(camera).targets() * batched.spp;
  ASSERT_GT(entries, 0u);
  ASSERT_LT(entries * 2, paths * batched.maxDepth) << "the bounce queues should be a fraction of a batch's worth";
  EXPECT_GT(entries, paths / 4) << "the cache should grow while the frame fills it (it starts at paths / 4)";
  constexpr std::uint64_t kEntryBytes = gpu::kSecondaryBytesPerPath;
  for (const std::uint64_t budget : {entries * kEntryBytes, (entries - 1) * kEntryBytes}) {
    const bool fits = budget == entries * kEntryBytes;
    SCOPED_TRACE(fits ? "a budget of exactly the frame's entries" : "one entry less");
    gpu::Renderer renderer(sharedContext(), scene);
    renderer.setBounceCacheBudget(budget);
    Scene edited = scene;
    ASSERT_EQ(renderer.render(camera, batched).reuse, FrameReuse::None);
    EXPECT_EQ(renderer.reuseSnapshot().secondarySegments.size(), fits ? entries : 0u);
    moveNode(edited, "glow-sphere", glm::dvec3(-0.15, 0.05, 0.1), renderer);
    const gpu::RenderResult first = renderer.render(camera, batched);
    EXPECT_EQ(first.reuse, fits ? FrameReuse::PartialRetrace : FrameReuse::None);
    EXPECT_EQ(renderer.reuseSnapshot().secondaryExact, fits);
    EXPECT_TRUE(sameBits(first, fullRender(edited, camera)));
    moveNode(edited, "mirror-sphere", glm::dvec3(0.1, 0.0, -0.1), renderer);
    const gpu::RenderResult second = renderer.render(camera, batched);
    EXPECT_EQ(second.reuse, FrameReuse::PartialRetrace);
    EXPECT_EQ(renderer.reuseSnapshot().secondaryExact, fits) << "after an overflow, bounces go by their cells";
    EXPECT_TRUE(sameBits(second, fullRender(edited, camera)));
  }
}

// The GPU marking pass lists exactly the targets the C++ reference picks from the masks the previous frame recorded.
// Once in one batch and once in many (the secondary cache's queues are kept per batch), and with the balls around
// the moved node (Renderer::moveNodes), which pass over fewer targets than the bounds alone.
void checkMarkingPassAgainstItsCpuReference(std::uint32_t maxPathsPerBatch, bool withBalls = false) {
  gpu::RenderSettings settings = reuseSettings();
  settings.maxPathsPerBatch = maxPathsPerBatch;
  Scene scene = loadScene("builtin:showcase");
  const gpu::FrameCamera camera = cameras(scene)[0].second;
  gpu::Renderer renderer(sharedContext(), scene);
  renderer.render(camera, settings);
  const gpu::Renderer::ReuseSnapshot before = renderer.reuseSnapshot();
  ASSERT_EQ(before.segmentMasks.size(), frameShape(camera).targets() * gpu::kMaskWords);
  const std::size_t index = *findNode(scene, "glow-sphere");
  const Bounds3 old = nodeWorldBounds(scene, index);
  const glm::vec4 oldBall = nodeWorldBall(scene, index);
  glm::dmat4 world(1.0);
  world[3] = glm::dvec4(-0.2, 0.1, 0.0, 1.0);
  setNodeWorldMatrix(scene, "glow-sphere", world);
  const Bounds3 moved = nodeWorldBounds(scene, index);
  if (withBalls) {
    const std::uint32_t nodes[] = {static_cast<std::uint32_t>(index)};
    renderer.moveNodes(scene, nodes, gpu::MovedBounds{old, moved, oldBall, nodeWorldBall(scene, index)});
  } else {
    renderer.replaceSceneAfterMove(scene, old, moved);
  }
  const gpu::RenderResult partial = renderer.render(camera, settings);
  ASSERT_EQ(partial.reuse, FrameReuse::PartialRetrace);
  const gpu::Renderer::ReuseSnapshot after = renderer.reuseSnapshot();
  ASSERT_FALSE(before.primaryHits.empty()) << "a small frame caches its primary hits";
  gpu::ReusePlan plan;
  plan.gridCells[0] = after.movedCells[0];
  plan.gridCells[1] = after.movedCells[1];
  plan.movedLo = after.movedLo;
  plan.movedHi = after.movedHi;
  plan.movedBalls = {after.movedBalls[0], after.movedBalls[1]};
  EXPECT_EQ(plan.movedBalls[0].w >= 0.0f, withBalls);
  plan.secondaryExact = after.secondaryExact;
  EXPECT_TRUE(after.secondaryExact) << "the mirror's and the glass's queues are cached: tested entry by entry";
  EXPECT_FALSE(before.secondarySegments.empty());
  Bounds3 both = old;
  both.extend(moved.lo);
  both.extend(moved.hi);
  const gpu_shared::uvec2 cells = gpu_shared::ht_grid_bounds_mask(both.lo, both.hi, before.grid);
  EXPECT_EQ(plan.gridCells[0], cells.x);
  EXPECT_EQ(plan.gridCells[1], cells.y);
  EXPECT_TRUE(glm::all(glm::lessThan(plan.movedLo, glm::min(old.lo, moved.lo))));
  EXPECT_TRUE(glm::all(glm::greaterThan(plan.movedHi, glm::max(old.hi, moved.hi))));
  const std::vector<std::uint32_t> expected =
      gpu::markDirtyTargets(before.segmentMasks, plan, before.primaryRays, before.primaryHits, settings.spp,
                            gpu::packLights(scene), before.secondarySegments);
  std::vector<std::uint32_t> listed = after.dirtyTargets;
  std::sort(listed.begin(), listed.end());
  EXPECT_EQ(listed, expected);
  EXPECT_EQ(partial.tracedTargets, expected.size());
  EXPECT_GT(expected.size(), 0u);
  if (withBalls) {
    plan.movedBalls = gpu::kNoBalls;
    const std::size_t boundsAlone =
        gpu::markDirtyTargets(before.segmentMasks, plan, before.primaryRays, before.primaryHits, settings.spp,
                              gpu::packLights(scene), before.secondarySegments)
            .size();
    EXPECT_LT(expected.size(), boundsAlone) << "a sphere fills half of its box";
  }
}

TEST(FrameReuse, MarkingPassMatchesItsCpuReference) { checkMarkingPassAgainstItsCpuReference(0); }
TEST(FrameReuse, MarkingPassMatchesItsCpuReferenceOverManyBatches) { checkMarkingPassAgainstItsCpuReference(1024); }
TEST(FrameReuse, MarkingPassWithTheMovedNodesBallsMatchesItsCpuReference) {
  checkMarkingPassAgainstItsCpuReference(0, true);
}

// Does the segment o + t d, t in [t0, t1], meet the box [lo, hi]? (Slab test in double precision.)
bool segmentMeetsBox(glm::dvec3 o, glm::dvec3 d, double t0, double t1, glm::dvec3 lo, glm::dvec3 hi) {
  for (int a = 0; a < 3; ++a) {
    if (d[a] == 0.0) {
      if (o[a] < lo[a] || o[a] > hi[a]) return false;
      continue;
    }
    double ta = (lo[a] - o[a]) / d[a], tb = (hi[a] - o[a]) / d[a];
    t0 = std::max(t0, std::min(ta, tb));
    t1 = std::min(t1, std::max(ta, tb));
  }
  return t0 <= t1;
}

// The box mask holds exactly the cells of the box, for every pair of corners (an empty range on any axis: none).
TEST(SegmentCells, BoxMaskIsExactlyTheCellsOfTheBox) {
  for (std::uint32_t from = 0; from < 64; ++from) {
    for (std::uint32_t to = 0; to < 64; ++to) {
      const gpu_shared::uvec3 a(from % 4, from / 4 % 4, from / 16), b(to % 4, to / 4 % 4, to / 16);
      std::uint64_t expected = 0;
      for (std::uint32_t cell = 0; cell < 64; ++cell) {
        const std::uint32_t x = cell % 4, y = cell / 4 % 4, z = cell / 16;
        if (x >= a.x && x <= b.x && y >= a.y && y <= b.y && z >= a.z && z <= b.z) expected |= 1ull << cell;
      }
      const gpu_shared::uvec2 mask = gpu_shared::ht_grid_box_mask(a, b);
      ASSERT_EQ((std::uint64_t{mask.y} << 32) | mask.x, expected) << "cells " << from << " to " << to;
    }
  }
}

// Conservative: whenever a segment meets a box (inside or outside the grid's bounds, misses to infinity included),
// its cells and the box's cells share a bit, and the float slab test meets the padded box; and the cells are not
// simply all of them.
TEST(SegmentCells, EverySegmentThatMeetsABoxSharesOneOfItsCells) {
  gpu_shared::SegmentGrid grid{glm::vec4(-1.0f, -0.5f, -2.0f, 0.0f), glm::vec4(2.0f, 4.0f, 1.0f, 0.0f)};
  std::mt19937 rng(99);
  std::uniform_real_distribution<float> coord(-4.0f, 4.0f), size(0.0f, 2.0f), unit(-1.0f, 1.0f);
  int meeting = 0, cellsMarked = 0, segments = 0;
  for (int i = 0; i < 200000; ++i) {
    const glm::vec3 o(coord(rng), coord(rng), coord(rng));
    glm::vec3 d(unit(rng), unit(rng), unit(rng));
    if (i % 7 == 0) d.y = 0.0f;  // axis-parallel directions
    const float t1 = i % 3 == 0 ? 3.0e38f : std::abs(coord(rng)) * 3.0f;
    const glm::vec3 lo(coord(rng), coord(rng), coord(rng));
    const glm::vec3 hi = lo + glm::vec3(size(rng), size(rng), size(rng));
    const gpu_shared::uvec2 seg = gpu_shared::ht_segment_cells(o, d, 0.0f, t1, grid);
    const gpu_shared::uvec2 box = gpu_shared::ht_grid_bounds_mask(lo, hi, grid);
    ++segments;
    cellsMarked += __builtin_popcount(seg.x) + __builtin_popcount(seg.y);
    if (segmentMeetsBox(o, d, 0.0, t1, lo, hi)) {
      ++meeting;
      ASSERT_NE((seg.x & box.x) | (seg.y & box.y), 0u) << "segment " << i << " meets its box in no shared cell";
      const glm::vec3 pad = gpu_shared::HT_GRID_PAD / glm::vec3(grid.scale);
      ASSERT_TRUE(gpu_shared::ht_segment_meets_box(o, d, 0.0f, t1, lo - pad, hi + pad)) << "segment " << i;
    }
  }
  EXPECT_GT(meeting, 1000);
  EXPECT_LT(cellsMarked, segments * 40) << "segments mark most of the 64 cells";
  const gpu_shared::uvec2 nan =
      gpu_shared::ht_segment_cells(glm::vec3(std::nanf("")), glm::vec3(1.0f), 0.0f, 1.0f, grid);
  EXPECT_EQ(nan.x & nan.y, 0xffffffffu);
}

// The balls' test is conservative: a segment (misses to infinity included) whose points come within the radius of the
// centre, in double precision, meets the ball; segments that pass more than 1 % of the radius and 1e-3 outside it do
// not.
// The shadow form meets the ball wherever a shadow ray from the point does.
TEST(SegmentCells, EverySegmentThatMeetsABallIsFoundAndOnlyThoseNearIt) {
  std::mt19937 rng(7);
  std::uniform_real_distribution<float> coord(-4.0f, 4.0f), radius(1e-3f, 2.0f), unit(-1.0f, 1.0f);
  int meeting = 0, far = 0;
  for (int i = 0; i < 200000; ++i) {
    const glm::vec4 ball(coord(rng), coord(rng), coord(rng), radius(rng));
    const glm::vec3 c(ball);
    // segments aimed near the ball, so that about half of them meet it
    glm::vec3 o(coord(rng), coord(rng), coord(rng));
    const glm::vec3 aim = c + glm::vec3(unit(rng), unit(rng), unit(rng)) * (2.0f * ball.w);
    glm::vec3 d = aim - o;
    if (i % 5 == 0) d = glm::normalize(d);
    const float t0 = i % 4 == 0 ? 0.0f : 0.25f * std::abs(unit(rng));
    const float t1 = i % 3 == 0 ? 3.0e38f : t0 + 2.0f * std::abs(unit(rng));
    // the distance in double from the centre to the points o + t d, t in [t0, min(t1, 1e30)]
    const glm::dvec3 od(o), dd(d), cd(c);
    const double tEnd = std::min<double>(t1, 1e30);
    const double tNear = std::clamp(glm::dot(cd - od, dd) / glm::dot(dd, dd), double(t0), tEnd);
    const double dist = glm::length(od + tNear * dd - cd);
    const bool found = gpu_shared::ht_segment_meets_balls(o, d, t0, t1, ball, ball);
    if (dist <= ball.w) {
      ++meeting;
      ASSERT_TRUE(found) << "segment " << i << " passes " << dist << " from the centre of a ball of " << ball.w;
    } else if (dist > 1.01 * ball.w + 1e-3) {
      ++far;
      ASSERT_FALSE(found) << "segment " << i << " passes " << dist << " from the centre of a ball of " << ball.w;
    }
    const glm::vec4 point(aim, 1.0f), sun(0.0f, 0.0f, 0.0f, 2.0f);  // HT_LIGHT_POINT, HT_LIGHT_DIRECTIONAL
    if (dist <= ball.w && t0 == 0.0f) {  // the shadow ray from o towards a light at `aim`, or along d to infinity
      if (i % 5 != 0 && tNear <= 1.0) {  // (d = aim - o: the shadow ray holds the segment's nearest point)
        ASSERT_TRUE(gpu_shared::ht_shadow_meets_balls(o, 0.0f, point, glm::vec3(0.0f), ball, ball)) << "segment " << i;
      }
      if (t1 >= 3.0e38f) {
        ASSERT_TRUE(gpu_shared::ht_shadow_meets_balls(o, 0.0f, sun, -d, ball, ball)) << "segment " << i;
      }
    }
  }
  EXPECT_GT(meeting, 20000);
  EXPECT_GT(far, 20000);
  const glm::vec4 none(0.0f, 0.0f, 0.0f, -1.0f);
  EXPECT_TRUE(gpu_shared::ht_segment_meets_balls(glm::vec3(100.0f), glm::vec3(1.0f), 0.0f, 1.0f, none, none))
      << "without balls, the bounds decide alone";
}

// The shadow test of the marking pass is conservative for the rays shade.comp traces: a shadow ray from the offset
// origin ht_offset_ray(s.p, n) of a surface point s.p that rounds differently from the marking pass's o + t d, with
// the direction and distance computed as emit_shadow_rays does, meets a box only where ht_shadow_meets_box says so
// (point and directional lights, boxes far and boxes of 1e-4 placed at the ray); and the test is not simply "yes".
TEST(SegmentCells, ShadowTestMeetsEveryBoxTheTracedShadowRayMeets) {
  std::mt19937 rng(7);
  std::uniform_real_distribution<float> coord(-4.0f, 4.0f), size(0.0f, 1.0f), unit(-1.0f, 1.0f), dist(0.05f, 6.0f);
  std::uniform_int_distribution<int> ulps(-4, 4);
  int tinyMeeting = 0, largeMeeting = 0, largeSaid = 0;
  for (int i = 0; i < 200000; ++i) {
    const glm::vec3 o(coord(rng), coord(rng), coord(rng));
    const glm::vec3 d = glm::normalize(glm::vec3(unit(rng), unit(rng), unit(rng))) * (i % 4 == 0 ? 3.0f : 1.0f);
    const float t = dist(rng);
    // shade.comp's surface point: the exact hit rounded, a few ULPs off per axis.
    const glm::dvec3 exact = glm::dvec3(o) + double(t) * glm::dvec3(d);
    glm::vec3 sp(exact);
    for (int k = 0; k < 3; ++k) {
      for (int n = ulps(rng); n != 0; n += n > 0 ? -1 : 1) sp[k] = std::nextafter(sp[k], n > 0 ? 1e30f : -1e30f);
    }
    const glm::vec3 normal = glm::normalize(glm::vec3(unit(rng), unit(rng), unit(rng)));
    const bool directional = i % 3 == 0;
    const glm::vec3 lightPos(coord(rng), coord(rng), coord(rng));
    const glm::vec3 travel = glm::normalize(glm::vec3(unit(rng), unit(rng), unit(rng)));
    // emit_shadow_rays / light_incidence
    const glm::vec3 origin = gpu_shared::ht_offset_ray(sp, normal);
    glm::vec3 wi = -travel;
    float reach = 3.0e38f;
    if (!directional) {
      const glm::vec3 toLight = lightPos - sp;
      reach = std::sqrt(glm::dot(toLight, toLight));
      wi = toLight / reach;
    }
    glm::vec3 lo = 0.5f * glm::vec3(coord(rng), coord(rng), coord(rng));
    glm::vec3 hi = lo + 2.0f * glm::vec3(size(rng), size(rng), size(rng));
    if (i % 2 == 0) {  // a tiny box at a random point of the traced ray, nudged by up to 2e-4
      const float s = directional ? dist(rng) : reach * (0.5f + 0.5f * unit(rng));
      const glm::vec3 at = origin + s * wi + 2e-4f * glm::vec3(unit(rng), unit(rng), unit(rng));
      lo = at - glm::vec3(5e-5f);
      hi = at + glm::vec3(5e-5f);
    }
    const glm::vec3 p = gpu_shared::ht_cached_hit_point(o, d, t);
    const float pErr = gpu_shared::ht_cached_hit_error(o, d, t);
    const bool says = gpu_shared::ht_shadow_meets_box(
        p, pErr, glm::vec4(lightPos, directional ? float(gpu_shared::HT_LIGHT_DIRECTIONAL) : 0.0f), travel, lo, hi);
    const bool large = i % 2 != 0;
    largeSaid += large && says;
    if (segmentMeetsBox(origin, wi, 0.0, reach, lo, hi)) {
      (large ? largeMeeting : tinyMeeting) += 1;
      ASSERT_TRUE(says) << "shadow ray " << i << (directional ? " (directional)" : " (point)") << " meets its box";
    }
  }
  EXPECT_GT(tinyMeeting, 5000) << "few tiny boxes on the ray: the padding is not exercised";
  EXPECT_GT(largeMeeting, 1000);
  EXPECT_LT(largeSaid, largeMeeting + largeMeeting / 20) << "the padded test says yes for boxes the ray does not meet";
}

// The box version an accumulation's marking pass uses (ht_box_shadow_meets_box: shadow rays from any point of a box
// of hit points): whenever the tested point version (above) says a ray from a point of the box meets a box, so does
// the box version (corners and random points inside, point and directional lights); for a box of one point both
// agree; and it is not simply "yes".
TEST(SegmentCells, BoxShadowTestMeetsWhereTheShadowRayOfAnyPointInTheBoxDoes) {
  std::mt19937 rng(11);
  std::uniform_real_distribution<float> coord(-4.0f, 4.0f), size(0.0f, 1.0f), unit(0.0f, 1.0f);
  int pointSaid = 0, boxSaid = 0, singleDiffer = 0, singles = 0;
  for (int i = 0; i < 100000; ++i) {
    const bool directional = i % 3 == 0, single = i % 5 == 0;
    const glm::vec4 light(coord(rng), coord(rng), coord(rng),
                          directional ? float(gpu_shared::HT_LIGHT_DIRECTIONAL) : 0.0f);
    const glm::vec3 travel = glm::normalize(glm::vec3(coord(rng), coord(rng), coord(rng)));
    const glm::vec3 pLo(coord(rng), coord(rng), coord(rng));
    const glm::vec3 pHi = single ? pLo : pLo + 0.3f * glm::vec3(size(rng), size(rng), size(rng));
    const float pErr = 1e-4f * size(rng);
    const glm::vec3 lo = 0.5f * glm::vec3(coord(rng), coord(rng), coord(rng));
    const glm::vec3 hi = lo + 2.0f * glm::vec3(size(rng), size(rng), size(rng));
    const bool box = gpu_shared::ht_box_shadow_meets_box(pLo, pHi, pErr, light, travel, lo, hi);
    boxSaid += box;
    bool anyPoint = false;
    for (int k = 0; k < 12; ++k) {  // the 8 corners, then random points
      const glm::vec3 f =
          k < 8 ? glm::vec3(k & 1, (k >> 1) & 1, (k >> 2) & 1) : glm::vec3(unit(rng), unit(rng), unit(rng));
      const glm::vec3 p = pLo + f * (pHi - pLo);
      if (gpu_shared::ht_shadow_meets_box(p, pErr, light, travel, lo, hi)) {
        anyPoint = true;
        ASSERT_TRUE(box) << "case " << i << (directional ? " (directional)" : " (point)") << ", point " << k;
      }
    }
    pointSaid += anyPoint;
    if (single) {
      singles += 1;
      singleDiffer += box != anyPoint;
    }
  }
  std::printf("[ box shadow test ] %d of 100000 said yes, %d with a point of the box saying yes\n", boxSaid, pointSaid);
  EXPECT_GT(pointSaid, 2000);
  EXPECT_LT(boxSaid, pointSaid + pointSaid / 2) << "the box test says yes far beyond its points";
  EXPECT_LT(singleDiffer, singles / 1000 + 1) << "for one point the box test is not the point test";
}

}  // namespace
}  // namespace ht::test
