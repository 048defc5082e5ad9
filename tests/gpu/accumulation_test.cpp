// accumulation_test.cpp - progressive accumulation (gpu/accumulator.h, docs/REUSE.md §1-§2) on every row of the
// display-model registry: k frames of N samples equal one frame of k*N samples bit for bit (4 x 1, 2 x 2 and 1 x 4),
// on a scene with a diffuse sphere, a glass sphere (the Fresnel choice's random number), a mirror and a light
// (shadow rays); a scene edit or a camera change restarts the sums; the adaptive policy converges and then traces
// nothing more.
#include <gtest/gtest.h>

#include <algorithm>
#include <cstdio>
#include <cstring>
#include <memory>
#include <optional>
#include <random>
#include <span>
#include <string>
#include <utility>
#include <vector>

#include "camera_models/display_config.h"
#include "camera_models/display_model_registry.h"
#include "gpu/accumulation_error.h"
#include "gpu/display_camera.h"
#include "gpu/frame_reuse.h"
#include "gpu/gpu_scene.h"
#include "gpu_test_util.h"
#include "scene/scene.h"
#include "scene/scene_edits.h"

namespace ht::test {
namespace {

constexpr std::uint64_t kMaxTargets = 1u << 14;  // tiny frames: the test is about bits, not images

Scene accumulationScene() {
  Scene s;
  Material white;
  white.baseColor = glm::vec3(0.9f);
  Material glass;
  glass.transmission = 1.0f;
  Material mirror;
  mirror.metallic = 1.0f;
  mirror.roughness = 0.0f;
  addIcosphere(s, glm::vec3(-0.25f, 0.0f, 0.0f), 0.3f, 1, addMaterial(s, white));
  addIcosphere(s, glm::vec3(0.25f, 0.05f, 0.15f), 0.22f, 1, addMaterial(s, glass));
  addQuad(s, glm::vec3(-1.0f, -0.4f, -0.6f), glm::vec3(2.0f, 0.0f, 0.0f), glm::vec3(0.0f, 0.0f, 1.2f),
          addMaterial(s, mirror));
  Light light;
  light.position = glm::vec3(0.5f, 1.0f, 1.0f);
  light.intensity = 2.0f;
  s.lights.push_back(light);
  s.ambient = glm::vec3(0.3f);
  return s;
}

// `frames` progressive frames of `spp` samples into a fresh accumulation (uniform policy); the last frame.
gpu::RenderResult accumulateFrames(gpu::Renderer& renderer, const FrameCamera& camera, std::uint32_t frames,
                                   std::uint32_t spp) {
  gpu::AccumulationPolicy uniform;
  uniform.adaptive = false;
  uniform.maxSpp = 1u << 20;
  gpu::Accumulator accumulator(uniform);
  gpu::RenderSettings settings;
  settings.spp = spp;
  settings.seed = 7;
  gpu::RenderResult frame;
  for (std::uint32_t k = 0; k < frames; ++k) frame = renderer.accumulate(camera, settings, accumulator);
  EXPECT_EQ(frame.accumulation.minSamples, frames * spp);
  EXPECT_EQ(frame.accumulation.maxSamples, frames * spp);
  EXPECT_EQ(frame.accumulation.frames, frames);
  return frame;
}

bool sameBits(const gpu::RenderResult& a, const gpu::RenderResult& b) {
  return a.rgba.size() == b.rgba.size() && std::memcmp(a.rgba.data(), b.rgba.data(), a.rgba.size() * 4) == 0;
}

// The shown frames of k x N and 1 x kN are the same floats, for every camera model.
TEST(Accumulation, KFramesOfNSamplesEqualOneFrameOfKNSamplesOnEveryModel) {
  const Scene scene = accumulationScene();
  gpu::Renderer renderer(sharedContext(), scene);
  int modelsChecked = 0;
  for (const DisplayModelRow& row : displayModels()) {
    SCOPED_TRACE(std::string(row.name));
    DisplayConfig config = parseDisplayConfig(row.example, "example", HT_TEST_DATA_DIR);
    const FrameCamera camera = row.makeCamera(config, scene.bounds(), testRayTable());
    if (frameShape(camera).targets() > kMaxTargets) continue;
    const gpu::RenderResult one = accumulateFrames(renderer, camera, 1, 4);
    const gpu::RenderResult four = accumulateFrames(renderer, camera, 4, 1);
    const gpu::RenderResult two = accumulateFrames(renderer, camera, 2, 2);
    EXPECT_TRUE(sameBits(one, four)) << "4 frames of spp 1 differ from 1 frame of spp 4";
    EXPECT_TRUE(sameBits(one, two)) << "2 frames of spp 2 differ from 1 frame of spp 4";
    EXPECT_EQ(one.nonFiniteSamples, 0u);
    float brightest = 0.0f;
    for (float v : one.rgba) brightest = std::max(brightest, v);
    EXPECT_GT(brightest, 0.05f) << "the frame sees nothing: the equality would be vacuous";
    ++modelsChecked;
  }
  EXPECT_GE(modelsChecked, 5);
}

// A progressive accumulation that reaches N >= 3 samples per target shows what a single frame of N samples shows,
// bit for bit, on every model and with glass: the same lattice points, the same sum order and the same Fresnel
// choices (keyed by the absolute sample index in both, docs/REUSE.md §6 item 3). So a progressive stream reaches the
// single frame's image, and its error, exactly when it reaches the single frame's sample count.
TEST(Accumulation, EightProgressiveSamplesEqualASingleFrameOfEightOnEveryModelWithGlass) {
  const Scene scene = accumulationScene();
  gpu::Renderer renderer(sharedContext(), scene);
  int modelsChecked = 0;
  for (const DisplayModelRow& row : displayModels()) {
    SCOPED_TRACE(std::string(row.name));
    DisplayConfig config = parseDisplayConfig(row.example, "example", HT_TEST_DATA_DIR);
    const FrameCamera camera = row.makeCamera(config, scene.bounds(), testRayTable());
    if (frameShape(camera).targets() > kMaxTargets / 4) continue;
    gpu::RenderSettings single;
    single.spp = 8;
    single.seed = 7;
    EXPECT_TRUE(sameBits(accumulateFrames(renderer, camera, 4, 2), renderer.render(camera, single)))
        << "4 progressive frames of spp 2 differ from a single frame of spp 8";
    ++modelsChecked;
  }
  EXPECT_GE(modelsChecked, 5);
}

// An edit of the renderer's scene (lights here) or a camera change starts a new accumulation: no frame sums
// samples of two scene versions (docs/REUSE.md §5).
TEST(Accumulation, SceneEditOrCameraChangeRestartsTheSums) {
  Scene scene = accumulationScene();
  gpu::Renderer renderer(sharedContext(), scene);
  const FrameCamera camera = lookAt(glm::vec3(0.0f, 0.2f, 2.0f), glm::vec3(0.0f), 40.0f, 16, 12);
  gpu::AccumulationPolicy uniform;
  uniform.adaptive = false;
  gpu::Accumulator accumulator(uniform);
  gpu::RenderSettings settings;
  settings.spp = 2;
  settings.seed = 7;
  EXPECT_TRUE(renderer.accumulate(camera, settings, accumulator).accumulation.restarted);
  EXPECT_EQ(renderer.accumulate(camera, settings, accumulator).accumulation.minSamples, 4u);
  LightEdit dim;
  dim.intensity = 0.5;
  editLight(scene, 0, dim);
  renderer.updateLights(scene);
  const gpu::RenderResult afterEdit = renderer.accumulate(camera, settings, accumulator);
  EXPECT_TRUE(afterEdit.accumulation.restarted);
  EXPECT_EQ(afterEdit.accumulation.maxSamples, 2u);
  // The frame after the edit is the first frame of a fresh accumulation of the edited scene, bit for bit.
  gpu::Renderer fresh(sharedContext(), scene);
  gpu::Accumulator clean(uniform);
  EXPECT_TRUE(sameBits(afterEdit, fresh.accumulate(camera, settings, clean)));
  const FrameCamera moved = lookAt(glm::vec3(0.1f, 0.2f, 2.0f), glm::vec3(0.0f), 40.0f, 16, 12);
  EXPECT_TRUE(renderer.accumulate(moved, settings, accumulator).accumulation.restarted);
  settings.spp = 3;  // another per-frame count continues the same accumulation
  EXPECT_FALSE(renderer.accumulate(moved, settings, accumulator).accumulation.restarted);
}

// Node moves restart the sums too: the first move of a flattened scene switches it to the two-level BVH (a full
// build), the second takes the fast path (refit + top level) and must bump the scene version all the same (it did
// not when both landed: a stream after a session's second move summed samples of two scenes).
TEST(Accumulation, NodeMovesOnBothBvhPathsRestartTheSums) {
  Scene scene = loadScene("builtin:showcase");
  const std::optional<std::size_t> node = findNode(scene, "glow-sphere");
  ASSERT_TRUE(node);
  gpu::Renderer renderer(sharedContext(), scene);
  const FrameCamera camera = lookAt(glm::vec3(0.0f, 0.3f, 2.5f), glm::vec3(0.0f), 40.0f, 16, 12);
  gpu::AccumulationPolicy uniform;
  uniform.adaptive = false;
  gpu::Accumulator accumulator(uniform);
  gpu::RenderSettings settings;
  settings.spp = 2;
  settings.seed = 7;
  renderer.accumulate(camera, settings, accumulator);
  EXPECT_EQ(renderer.accumulate(camera, settings, accumulator).accumulation.minSamples, 4u);
  const std::uint32_t moved[] = {static_cast<std::uint32_t>(*node)};
  for (int move = 1; move <= 2; ++move) {
    SCOPED_TRACE("move " + std::to_string(move));
    setNodeWorldMatrix(scene, "glow-sphere",
                       glm::translate(scene.nodes[*node].world, glm::dvec3(0.1 * move, 0.05, 0.0)));
    renderer.moveNodes(scene, moved);
    const gpu::RenderResult frame = renderer.accumulate(camera, settings, accumulator);
    EXPECT_TRUE(frame.accumulation.restarted);
    EXPECT_EQ(frame.accumulation.maxSamples, 2u);
    gpu::Renderer fresh(sharedContext(), scene);
    gpu::Accumulator clean(uniform);
    EXPECT_TRUE(sameBits(frame, fresh.accumulate(camera, settings, clean)));
  }
  EXPECT_EQ(renderer.bvhStats().instanceUpdates, 1u) << "the second move did not take the two-level fast path";
}

// Accumulates until the stop rule holds for every target (at most 60 frames); the last frame.
gpu::RenderResult accumulateToConvergence(gpu::Renderer& renderer, const FrameCamera& camera,
                                          gpu::Accumulator& accumulator, const gpu::RenderSettings& settings) {
  gpu::RenderResult frame;
  for (int k = 0; k < 60 && !(k > 0 && frame.accumulation.converged); ++k) {
    frame = renderer.accumulate(camera, settings, accumulator);
  }
  EXPECT_TRUE(frame.accumulation.converged);
  return frame;
}

// The node-move tests' accumulations: converged after 4-12 samples, `spp` per frame.
gpu::AccumulationPolicy movePolicy() {
  gpu::AccumulationPolicy policy;
  policy.targetError = 0.05f;
  policy.minSpp = 4;
  policy.maxSpp = 12;
  return policy;
}
gpu::RenderSettings moveSettings(std::uint32_t spp) {
  gpu::RenderSettings settings;
  settings.spp = spp;
  settings.seed = 7;
  return settings;
}

// Property test of the partial restart (docs/REUSE.md §4 in streams): random node moves (the mirror, glass and
// glowing spheres and a box of the showcase, which has a shadowing light) during a converged accumulation restart
// only the targets whose recorded segment cells meet the moved bounds; the others keep their sums, and the
// accumulation converges to the very frame a fresh accumulation of the edited scene converges to, bit for bit.
TEST(Accumulation, NodeMovesRestartOnlyNearbyTargetsAndConvergeToTheFreshAccumulation) {
  Scene scene = loadScene("builtin:showcase");
  // On the two-level BVH, as holotraced traces a scene whose nodes move: only such scenes record segment cells.
  gpu::Renderer renderer(sharedContext(), scene, gpu::buildSceneBvh(scene, {}, gpu::BvhLayoutPolicy::TwoLevel));
  const gpu::AccumulationPolicy policy = movePolicy();
  const gpu::RenderSettings settings = moveSettings(2);
  const DisplayConfig projectors = smallProjectorArray();
  const std::vector<std::pair<std::string, FrameCamera>> cameras = {
      {"pinhole", lookAt(glm::vec3(0.0f, 0.4f, 2.6f), glm::vec3(0.0f, 0.1f, 0.0f), 45.0f, 32, 24)},
      {"projector array", gpu::makeDisplayCamera(projectors, scene.bounds()).camera}};
  std::vector<std::unique_ptr<gpu::Accumulator>> accumulators;
  for (const auto& entry : cameras) {
    accumulators.push_back(std::make_unique<gpu::Accumulator>(policy));
    accumulateToConvergence(renderer, entry.second, *accumulators.back(), settings);
  }
  std::mt19937 rng(16);
  std::uniform_real_distribution<double> offset(-0.12, 0.12);
  const char* names[] = {"mirror-sphere", "glass-sphere", "glow-sphere", "red-box"};
  std::uint64_t resetSum = 0, targetSum = 0;
  for (int edit = 0; edit < 3; ++edit) {
    const char* name = names[rng() % 4];
    const std::size_t node = *findNode(scene, name);
    const Bounds3 before = nodeWorldBounds(scene, node);
    setNodeWorldMatrix(
        scene, name, glm::translate(scene.nodes[node].world, glm::dvec3(offset(rng), 0.3 * offset(rng), offset(rng))));
    const std::uint32_t moved[] = {static_cast<std::uint32_t>(node)};
    renderer.moveNodes(scene, moved, gpu::MovedBounds{before, nodeWorldBounds(scene, node)});
    gpu::Renderer fresh(sharedContext(), scene);
    for (size_t c = 0; c < cameras.size(); ++c) {
      SCOPED_TRACE("move " + std::to_string(edit) + " of " + name + ", " + cameras[c].first);
      const gpu::RenderResult first = renderer.accumulate(cameras[c].second, settings, *accumulators[c]);
      EXPECT_FALSE(first.accumulation.restarted);
      EXPECT_LT(first.accumulation.resetTargets, first.accumulation.targets);
      resetSum += first.accumulation.resetTargets;
      targetSum += first.accumulation.targets;
      const gpu::RenderResult kept = accumulateToConvergence(renderer, cameras[c].second, *accumulators[c], settings);
      gpu::Accumulator clean(policy);
      EXPECT_TRUE(sameBits(kept, accumulateToConvergence(fresh, cameras[c].second, clean, settings)))
          << "the partially restarted accumulation converged to another frame than a fresh one";
    }
  }
  EXPECT_GT(resetSum, 0u) << "no move touched a target: the test would be vacuous";
  EXPECT_LT(resetSum * 2, targetSum) << "moves of small objects restarted most targets";
}

// What an accumulation records per target of its primary segments (record_segments.comp; docs/REUSE.md §4 in
// streams), checked against its samples' rays (`rays`, raysPerTarget per target; sample k of a progressive target =
// sample k of a single frame of >= 3 samples) traced by the renderer, bit for bit: the reach is the farthest primary
// hit or miss (tmax), and the nearest and farthest hit distances are those of its hits.
void expectPrimaryBoundsAreThoseOfTheHits(gpu::Renderer& renderer, std::span<const std::uint32_t> masks,
                                          std::span<const std::uint32_t> samples,
                                          std::span<const gpu_shared::HtRay> rays, std::uint32_t raysPerTarget) {
  const std::size_t targets = samples.size();
  const std::vector<gpu_shared::HtHit> hits = renderer.traceClosest(rays);
  std::uint64_t checked = 0;
  const auto word = [&](std::uint32_t block, std::size_t t) { return masks[(gpu::kMaskWords + block) * targets + t]; };
  const auto bits = [](float v) {
    std::uint32_t b = 0;
    std::memcpy(&b, &v, sizeof(b));
    return b;
  };
  for (std::size_t t = 0; t < targets; ++t) {
    float reach = 0.0f, near = 3.4e38f, far = 0.0f;
    bool hit = false;
    for (std::uint32_t k = 0; k < samples[t]; ++k) {
      const gpu_shared::HtHit& h = hits[t * raysPerTarget + k];
      reach = std::max(reach, h.triId != gpu_shared::HT_MISS ? h.t : rays[t * raysPerTarget + k].tmax);
      if (h.triId == gpu_shared::HT_MISS) continue;
      hit = true;
      near = std::min(near, h.t);
      far = std::max(far, h.t);
    }
    // the same rays and the order-free closest hit: the same bits
    ASSERT_EQ(word(0, t), bits(reach)) << "target " << t;
    ASSERT_EQ(word(1, t), hit ? ~bits(near) : 0u) << "target " << t;
    ASSERT_EQ(word(2, t), hit ? bits(far) : 0u) << "target " << t;
    checked += samples[t];
  }
  EXPECT_GE(checked, targets * 4);
}

// CPU reference of an accumulation's restart after a node move (gpu::markAccumulatedTargets, docs/REUSE.md §4 in
// streams): the targets the marking pass restarted are those whose shadow and bounce cells (mask words 0-1) meet the
// moved bounds' cells, or whose primary cells (words 2-3) do and one of whose samples' primary rays (raygen's rays,
// traced: the recorded reach is their farthest hit) meets the padded bounds up to that reach, or a shadow ray from
// the box of their hit points does. Pinhole and lenticular (non-linear subpixel rays), the glow sphere and a box,
// under the showcase's point light and sun.
TEST(Accumulation, AMovesRestartedTargetsEqualTheirCpuReference) {
  Scene scene = loadScene("builtin:showcase");
  gpu::Renderer renderer(sharedContext(), scene, gpu::buildSceneBvh(scene, {}, gpu::BvhLayoutPolicy::TwoLevel));
  const gpu::AccumulationPolicy policy = movePolicy();
  const gpu::RenderSettings settings = moveSettings(4);
  DisplayConfig portrait = builtinDisplay("portrait");
  portrait.calibration->screenW = 48;  // 48 x 64 pixels, 3 subpixel targets each
  portrait.calibration->screenH = 64;
  const std::vector<std::pair<std::string, FrameCamera>> cameras = {
      {"pinhole", lookAt(glm::vec3(0.0f, 0.4f, 2.6f), glm::vec3(0.0f, 0.1f, 0.0f), 45.0f, 40, 30)},
      {"lenticular", gpu::makeDisplayCamera(portrait, scene.bounds()).camera}};
  std::uint64_t exactSum = 0, cellSum = 0;
  for (const auto& [cameraName, camera] : cameras) {
    for (const char* name : {"glow-sphere", "red-box"}) {
      SCOPED_TRACE(cameraName + ", " + name);
      gpu::Accumulator accumulator(policy);
      accumulateToConvergence(renderer, camera, accumulator, settings);
      const std::vector<std::uint32_t> masks = accumulator.downloadMasks();
      const std::vector<float> sums = accumulator.downloadSums();
      const std::size_t targets = sums.size() / 8;
      ASSERT_EQ(masks.size(), targets * (gpu::kMaskWords + gpu::kAccumulationBoundWords));
      std::vector<std::uint32_t> samples(targets);
      for (std::size_t t = 0; t < targets; ++t) samples[t] = static_cast<std::uint32_t>(sums[t * 8 + 3]);
      gpu::RenderSettings raySettings = settings;
      raySettings.spp = policy.maxSpp;
      const std::vector<gpu_shared::HtRay> rays =
          renderer.generateRays(camera, raySettings, 0, static_cast<std::uint32_t>(targets));
      expectPrimaryBoundsAreThoseOfTheHits(renderer, masks, samples, rays, policy.maxSpp);

      const std::size_t node = *findNode(scene, name);
      Bounds3 moved = nodeWorldBounds(scene, node);
      const Bounds3 before = moved;
      setNodeWorldMatrix(scene, name, glm::translate(scene.nodes[node].world, glm::dvec3(0.07, 0.02, -0.05)));
      const Bounds3 after = nodeWorldBounds(scene, node);
      moved.extend(after.lo);
      moved.extend(after.hi);
      const std::uint32_t movedNodes[] = {static_cast<std::uint32_t>(node)};
      renderer.moveNodes(scene, movedNodes, gpu::MovedBounds{before, after});
      const gpu::RenderResult frame = renderer.accumulate(camera, settings, accumulator);
      ASSERT_FALSE(frame.accumulation.restarted);

      const gpu_shared::SegmentGrid grid = renderer.reuseSnapshot().grid;
      const gpu_shared::uvec2 cellMask = gpu_shared::ht_grid_bounds_mask(moved.lo, moved.hi, grid);
      const std::uint32_t cells[2] = {cellMask.x, cellMask.y};
      const std::vector<std::uint32_t> expected = gpu::markAccumulatedTargets(
          masks, cells, gpu::paddedMovedBounds(moved, grid), samples, rays, policy.maxSpp, gpu::packLights(scene));
      std::vector<std::uint32_t> restarted = accumulator.lastResetTargets();
      std::sort(restarted.begin(), restarted.end());
      EXPECT_EQ(restarted, expected);
      EXPECT_EQ(frame.accumulation.resetTargets, expected.size());
      std::uint64_t byCells = 0;  // what the cells alone would restart
      for (std::size_t t = 0; t < targets; ++t) {
        const std::uint32_t* m = masks.data() + t * gpu::kMaskWords;
        byCells += (((m[0] | m[2]) & cells[0]) | ((m[1] | m[3]) & cells[1])) != 0 ? 1 : 0;
      }
      exactSum += expected.size();
      cellSum += byCells;
    }
  }
  std::printf("[ restart ] %llu targets restarted, %llu by cells alone\n", static_cast<unsigned long long>(exactSum),
              static_cast<unsigned long long>(cellSum));
  EXPECT_GT(exactSum, 0u) << "no move touched a target: the test would be vacuous";
  EXPECT_LT(exactSum * 3, cellSum * 2) << "the exact primary test spared few targets the cells would restart";
}

// The adaptive policy: after the first frame only targets above the target error get samples; the accumulation
// converges (every target below the error or at max spp) and a converged accumulation traces no more targets.
TEST(Accumulation, AdaptivePolicyConvergesAndThenTracesNothing) {
  const Scene scene = accumulationScene();
  gpu::Renderer renderer(sharedContext(), scene);
  const FrameCamera camera = lookAt(glm::vec3(0.0f, 0.2f, 2.0f), glm::vec3(0.0f), 40.0f, 16, 12);
  gpu::AccumulationPolicy policy;
  policy.targetError = 0.05f;
  policy.minSpp = 4;
  policy.maxSpp = 64;
  gpu::Accumulator accumulator(policy);
  gpu::RenderSettings settings;
  settings.spp = 4;
  gpu::RenderResult frame;
  std::uint64_t previousTraced = ~0ull;
  for (int k = 0; k < 40 && !frame.accumulation.converged; ++k) {
    frame = renderer.accumulate(camera, settings, accumulator);
    EXPECT_LE(frame.accumulation.tracedTargets, previousTraced);
    previousTraced = frame.accumulation.tracedTargets;
  }
  ASSERT_TRUE(frame.accumulation.converged);
  EXPECT_EQ(frame.accumulation.unconverged, 0u);
  EXPECT_LE(frame.accumulation.maxSamples, 64u);
  EXPECT_GE(frame.accumulation.minSamples, 4u);
  EXPECT_LT(frame.accumulation.minSamples, frame.accumulation.maxSamples) << "no target was refined adaptively";
  const gpu::RenderResult after = renderer.accumulate(camera, settings, accumulator);
  EXPECT_EQ(after.accumulation.tracedTargets, 0u);
  EXPECT_TRUE(sameBits(after, frame));
}

// What a progressive frame reports and shows, recomputed on the CPU from the downloaded sums of every target of a
// 20 x 14 pinhole frame (pixel targets): its shown rgb is the target's sum / n, and the count of targets that need
// samples, the largest error and the fewest and most samples are those of all targets.
void expectFrameIsItsSums(const gpu::RenderResult& frame, const gpu::Accumulator& accumulator,
                          const gpu::AccumulationPolicy& policy) {
  const std::vector<float> sums = accumulator.downloadSums();
  ASSERT_EQ(sums.size(), std::size_t(20 * 14 * 8));
  std::uint64_t unconverged = 0;
  float maxError = 0.0f;
  std::uint32_t fewest = ~0u, most = 0;
  for (std::size_t t = 0; t < sums.size() / 8; ++t) {
    const float* s = &sums[t * 8];
    const auto n = static_cast<std::uint32_t>(s[3]);
    const auto halfN = static_cast<std::uint32_t>(s[7]);
    const glm::vec3 mean = n > 0 ? glm::vec3(s[0], s[1], s[2]) / s[3] : glm::vec3(0.0f);
    const glm::vec3 halfMean = halfN > 0 ? glm::vec3(s[4], s[5], s[6]) / s[7] : glm::vec3(0.0f);
    const float error = gpu_shared::ht_accum_error(mean, halfMean, halfN, glm::vec3(1.0f));
    maxError = std::max(maxError, std::min(error, gpu_shared::HT_ACCUM_UNKNOWN_ERROR));
    if (gpu_shared::ht_accum_needs_samples(n, error, policy.minSpp, policy.maxSpp, policy.targetError)) ++unconverged;
    fewest = std::min(fewest, n);
    most = std::max(most, n);
    const std::size_t x = t % 20, y = t / 20, pixel = (13 - y) * 20 + x;  // rows of targets count from the bottom
    for (int c = 0; c < 3; ++c) ASSERT_EQ(frame.rgba[pixel * 4 + c], mean[c]) << "target " << t << " channel " << c;
  }
  EXPECT_EQ(frame.accumulation.unconverged, unconverged);
  EXPECT_NEAR(frame.accumulation.maxError, maxError, 1e-5f * maxError);
  EXPECT_EQ(frame.accumulation.minSamples, fewest);
  EXPECT_EQ(frame.accumulation.maxSamples, most);
}

// Under the adaptive policy a frame judges only the targets the last frame sampled and shows only the ones it samples
// (accumulation_pass.cpp; a target left out stays converged, and the subpixel buffer keeps its value). Every frame
// must still show and report what the sums of all targets say, also after the renderer drew something else in
// between: a single frame of another scene view, and a frame of a second accumulation.
TEST(Accumulation, AdaptiveFramesShowAndReportEveryTargetAsItsSumsSay) {
  const Scene scene = accumulationScene();
  gpu::Renderer renderer(sharedContext(), scene);
  const FrameCamera camera = lookAt(glm::vec3(0.0f, 0.2f, 2.0f), glm::vec3(0.0f), 40.0f, 20, 14);
  const FrameCamera other = lookAt(glm::vec3(0.4f, 0.6f, 1.5f), glm::vec3(0.0f), 50.0f, 20, 14);
  gpu::AccumulationPolicy policy;
  policy.targetError = 0.05f;
  policy.minSpp = 4;
  policy.maxSpp = 48;
  gpu::Accumulator accumulator(policy), second(policy);
  gpu::RenderSettings settings;
  settings.spp = 2;
  gpu::RenderResult frame;
  int frames = 0;
  std::uint64_t sampled = 0;
  for (; frames < 40 && !frame.accumulation.converged; ++frames) {
    SCOPED_TRACE("frame " + std::to_string(frames));
    if (frames == 4) renderer.render(other, settings);               // another image in the subpixel buffer
    if (frames == 6) renderer.accumulate(other, settings, second);   // another accumulation's show pass
    if (frames == 8) renderer.accumulate(camera, settings, second);  // ... of the same view
    frame = renderer.accumulate(camera, settings, accumulator);
    expectFrameIsItsSums(frame, accumulator, policy);
    if (frames > 0) sampled += frame.accumulation.tracedTargets;
  }
  ASSERT_TRUE(frame.accumulation.converged);
  EXPECT_EQ(accumulator.deviceBytes(), gpu::Accumulator::bytesFor(frameShape(camera)))
      << "the memory limit counts what an accumulation holds";
  EXPECT_GT(frames, 10);
  EXPECT_LT(sampled, std::uint64_t{20 * 14} * (frames - 1)) << "every frame sampled every target";
  EXPECT_LT(frame.accumulation.minSamples, frame.accumulation.maxSamples) << "no target was refined adaptively";
}

// CPU reference of the error estimate and the stop rule (gpu/accumulation_error.h, the same source): recomputed on
// the CPU from the downloaded sums of every target, the count of targets that need samples and the largest error
// equal what accum_show.comp reported; the sample and half counts are those of the sequence (n, and the indices
// below n with an odd popcount of i & 0xaaaaaaaa); the shown value of a target is its sum / n.
TEST(Accumulation, ErrorEstimateAndStopRuleMatchTheirCpuReference) {
  const Scene scene = accumulationScene();
  gpu::Renderer renderer(sharedContext(), scene);
  const FrameCamera camera = lookAt(glm::vec3(0.0f, 0.2f, 2.0f), glm::vec3(0.0f), 40.0f, 20, 14);
  gpu::AccumulationPolicy policy;
  policy.adaptive = false;
  policy.targetError = 0.05f;
  policy.minSpp = 4;
  policy.maxSpp = 64;
  gpu::Accumulator accumulator(policy);
  gpu::RenderSettings settings;
  settings.spp = 3;
  gpu::RenderResult frame;
  for (int k = 0; k < 3; ++k) frame = renderer.accumulate(camera, settings, accumulator);
  const std::vector<float> sums = accumulator.downloadSums();
  ASSERT_EQ(sums.size(), std::size_t(20 * 14 * 8));
  std::uint32_t halfCount = 0;
  for (std::uint32_t i = 0; i < 9; ++i) halfCount += gpu_shared::ht_accum_in_half(i) ? 1u : 0u;
  std::uint64_t unconverged = 0;
  float maxError = 0.0f;
  for (std::size_t t = 0; t < sums.size() / 8; ++t) {
    const float* s = &sums[t * 8];
    ASSERT_EQ(s[3], 9.0f);
    ASSERT_EQ(s[7], float(halfCount));
    const glm::vec3 mean = glm::vec3(s[0], s[1], s[2]) / s[3];
    const glm::vec3 halfMean = glm::vec3(s[4], s[5], s[6]) / s[7];
    const float error = gpu_shared::ht_accum_error(mean, halfMean, halfCount, glm::vec3(1.0f));
    maxError = std::max(maxError, error);
    if (gpu_shared::ht_accum_needs_samples(9, error, policy.minSpp, policy.maxSpp, policy.targetError)) ++unconverged;
    // Pinhole: pixel targets; row 0 of the frame is the top, targets count rows from the bottom.
    const std::size_t x = t % 20, y = t / 20, pixel = (13 - y) * 20 + x;
    EXPECT_EQ(frame.rgba[pixel * 4], mean.x) << "target " << t;
  }
  EXPECT_EQ(frame.accumulation.unconverged, unconverged);
  EXPECT_GT(unconverged, 0u);
  EXPECT_LT(unconverged, sums.size() / 8) << "the threshold should split the targets for a meaningful check";
  EXPECT_NEAR(frame.accumulation.maxError, maxError, 1e-5f * maxError);
}

}  // namespace
}  // namespace ht::test
