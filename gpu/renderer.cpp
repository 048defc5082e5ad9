// renderer.cpp - the Renderer's resources and their bindings (scene records, BVH views, path state, outputs, ray
// table), the frame block, settings checks and the public API. The frame loop is in wavefront_loop.cpp, adaptive
// refinement in refinement_pass.cpp, ray batches in ray_batches.cpp (docs/BVH.md §7 for the passes).
#include "gpu/renderer.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstddef>
#include <cstring>
#include <string>
#include <utility>

#include "common/image_limits.h"
#include "gpu/renderer_impl.h"

namespace ht::gpu {

static_assert(sizeof(gpu_shared::HtRay) == 32 && sizeof(gpu_shared::HtHit) == 16);
static_assert(sizeof(gpu_shared::GpuBvhNode) == 64);
static_assert(sizeof(GpuCounters) == 80 && offsetof(GpuCounters, dispatch) == 32);
static_assert(sizeof(PassConstants) == 40);
static_assert(sizeof(gpu_shared::AccumTarget) == 32 && sizeof(gpu_shared::AccumStats) == 16);  // std430 == C++
static_assert(offsetof(FrameBlock, dims) == 16 && sizeof(FrameBlock) % 16 == 0);               // std140 == C++ layout

namespace {

// A buffer bound as a texel buffer: which binding, which buffer, which texel format.
struct TexelBinding {
  std::uint32_t binding;
  const DeviceBuffer* buffer;
  VkFormat format;
};

double msSince(std::chrono::steady_clock::time_point start) {
  return std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
}

}  // namespace

std::vector<std::uint32_t> withConstant(std::vector<std::uint32_t> spec, std::uint32_t id, std::uint32_t value) {
  spec.resize(std::max<std::size_t>(spec.size(), id + 1), 0u);
  spec[id] = value;
  return spec;
}

void checkSettings(const RenderSettings& settings) {
  if (settings.spp < 1 || settings.spp > kMaxSpp)
    throw GpuError("spp " + std::to_string(settings.spp) + " out of range [1, 4096]");
  if (settings.maxDepth > kMaxDepth)
    throw GpuError("depth " + std::to_string(settings.maxDepth) + " out of range [0, 32]");
  if (static_cast<std::uint32_t>(settings.filter) > 2) throw GpuError("unknown sample filter");
  if (settings.refineSpp > kMaxSpp) {
    throw GpuError("refinement spp " + std::to_string(settings.refineSpp) + " out of range [0, 4096]");
  }
  if (!(settings.refineContrast >= 0.0f) || !std::isfinite(settings.refineContrast)) {
    throw GpuError("refinement contrast " + std::to_string(settings.refineContrast) +
                   " must be a finite number >= 0 (0 refines every target, above 1 none)");
  }
  if (!(settings.reuseMaxDirtyShare >= 0.0 && settings.reuseMaxDirtyShare <= 1.0)) {
    throw GpuError("reuse max dirty share " + std::to_string(settings.reuseMaxDirtyShare) +
                   " out of range [0, 1] (the share of a frame's targets a partial re-render may trace)");
  }
}

void checkShape(const FrameShape& shape, std::uint32_t spp) {
  if (shape.width == 0 || shape.height == 0 || shape.width > kMaxImageSide || shape.height > kMaxImageSide) {
    throw GpuError("image size " + std::to_string(shape.width) + "x" + std::to_string(shape.height) +
                   " out of range [1, " + std::to_string(kMaxImageSide) + "]");
  }
  if (shape.views == 0) throw GpuError("camera has no views");
  if (shape.targets() * spp >= (1ull << 32)) {
    throw GpuError("frame of " + std::to_string(shape.targets()) + " targets x spp " + std::to_string(spp) +
                   " exceeds 2^32 rays per frame: lower --spp to at most " +
                   std::to_string(((1ull << 32) - 1) / shape.targets()));
  }
}

Renderer::Impl::Impl(VulkanContext::Impl& v, GpuScene&& s, const bvh::BuildOptions& o, const Bounds3& sceneBounds)
    : vk(v),
      scene(std::move(s)),
      layout(v.pipelines->layout()),
      descriptors(v, layout.setLayout()),
      frame(v, sizeof(FrameBlock), MemoryPlace::HostReadback),
      counters(v, sizeof(GpuCounters), MemoryPlace::HostReadback),
      buildOptions(o),
      reuse(v, sceneBounds) {
  VkQueryPoolCreateInfo qi{VK_STRUCTURE_TYPE_QUERY_POOL_CREATE_INFO};
  qi.queryType = VK_QUERY_TYPE_TIMESTAMP;
  qi.queryCount = kQueryCapacity;
  HT_VK(vkCreateQueryPool(vk.device, &qi, nullptr, &queryPool));
  VkCommandBufferAllocateInfo ai{VK_STRUCTURE_TYPE_COMMAND_BUFFER_ALLOCATE_INFO};
  ai.commandPool = vk.commandPool;
  ai.level = VK_COMMAND_BUFFER_LEVEL_PRIMARY;
  ai.commandBufferCount = 1;
  HT_VK(vkAllocateCommandBuffers(vk.device, &ai, &cmd));
  VkFenceCreateInfo fci{VK_STRUCTURE_TYPE_FENCE_CREATE_INFO};
  HT_VK(vkCreateFence(vk.device, &fci, nullptr, &fence));
  bindScene();
  reuseTexelDummy = DeviceBuffer(vk, sizeof(glm::vec4), MemoryPlace::Device);
  bindReuseTexels(reuseTexelDummy, false, false);
  bindAccumulation(nullptr);
  bindRayTable(nullptr);
  bvhStats.layout = scene.layout();
  bvhStats.fullBuilds = 1;
}

Renderer::Impl::~Impl() {
  vkDeviceWaitIdle(vk.device);
  vkDestroyFence(vk.device, fence, nullptr);
  vkFreeCommandBuffers(vk.device, vk.commandPool, 1, &cmd);
  vkDestroyQueryPool(vk.device, queryPool, nullptr);
}

void Renderer::Impl::bindRayTable(const std::shared_ptr<const RayTable>& table) {
  if (rayTableTexels.size() != 0 && (!table || table == boundRayTable)) return;
  std::vector<glm::vec4> texels(2);
  if (table) {
    texels.resize(std::size_t(table->width) * table->height * 2);
    for (std::size_t i = 0; i < texels.size() / 2; ++i) {
      texels[2 * i] = glm::vec4(table->origins[i], 0.0f);
      texels[2 * i + 1] = glm::vec4(table->directions[i], 0.0f);
    }
  }
  rayTableTexels = DeviceBuffer(vk, texels.size() * sizeof(glm::vec4), MemoryPlace::Device);
  rayTableTexels.upload(texels.data(), texels.size() * sizeof(glm::vec4));
  if (!descriptors.setUniformTexels(gpu_shared::HT_BINDING_RAY_TABLE, rayTableTexels, VK_FORMAT_R32G32B32A32_SFLOAT,
                                    true)) {
    throw GpuError("ray table of " + std::to_string(texels.size() / 2) + " entries exceeds the device's texel buffers");
  }
  descriptors.flush();
  boundRayTable = table;
}

void Renderer::Impl::bindReuseTexels(const DeviceBuffer& masks, bool primaryCached, bool bouncesCached) {
  using namespace gpu_shared;
  // `fresh`: the reuse buffers are reallocated as frames change shape, and a new buffer may reuse a freed handle (the
  // dummy stays: frames without reuse state keep their views).
  const struct {
    std::uint32_t binding;
    const DeviceBuffer& buffer;
    VkFormat format;
  } views[] = {
      {HT_BINDING_REUSE_MASKS, masks, VK_FORMAT_R32G32B32A32_UINT},
      {HT_BINDING_REUSE_PRIMARY_RAYS, primaryCached ? reuse.primaryRays : reuseTexelDummy,
       VK_FORMAT_R32G32B32A32_SFLOAT},
      {HT_BINDING_REUSE_PRIMARY_HITS, primaryCached ? reuse.primaryHits : reuseTexelDummy, VK_FORMAT_R32G32B32A32_UINT},
      {HT_BINDING_REUSE_BOUNCES, bouncesCached ? reuse.secondaryCache : reuseTexelDummy, VK_FORMAT_R32G32B32A32_UINT}};
  // A view is clamped to the device's maxTexelBufferElements; what the shaders read lies within it
  // (FrameReuseState::plan and the accumulation's masks keep to that limit, a buffer kept from a larger frame may
  // exceed it).
  for (const auto& v : views)
    descriptors.setUniformTexels(v.binding, v.buffer, v.format, &v.buffer != &reuseTexelDummy);
  descriptors.flush();
}

void Renderer::Impl::bindAccumulation(const Accumulator::State* st) {
  using namespace gpu_shared;
  // `fresh` for the sums: an accumulation's buffers may take the handles of another's freed ones
  descriptors.setStorageTexels(HT_BINDING_ACCUM_SUMS, st ? st->sums : reuseTexelDummy, VK_FORMAT_R32G32B32A32_UINT,
                               st != nullptr);
  descriptors.setStorageTexels(HT_BINDING_ACCUM_HALVES, st ? st->halves : reuseTexelDummy, VK_FORMAT_R32G32B32A32_UINT,
                               st != nullptr);
  descriptors.flush();
}

void Renderer::Impl::sceneChanged(std::optional<Bounds3> moved) {
  ++sceneGeneration;
  sceneChanges.push_back({sceneGeneration, moved});
  if (sceneChanges.size() > kSceneChangeLog) sceneChanges.pop_front();
}

std::optional<Bounds3> Renderer::Impl::movedSince(std::uint64_t generation) const {
  if (generation >= sceneGeneration) return Bounds3{};
  if (sceneChanges.empty() || sceneChanges.front().generation > generation + 1) return std::nullopt;  // log too short
  Bounds3 all;
  for (const SceneChange& c : sceneChanges) {
    if (c.generation <= generation) continue;
    if (!c.moved) return std::nullopt;
    if (c.moved->empty()) continue;
    all.extend(c.moved->lo);
    all.extend(c.moved->hi);
  }
  return all;
}

void Renderer::Impl::replaceScene(const Scene& s, BvhLayoutPolicy policy) {
  const auto start = std::chrono::steady_clock::now();
  installScene(s, buildSceneBvh(s, buildOptions, policy));
  sceneChanged(std::nullopt);
  bvhStats.lastUpdateMs = msSince(start);
}

void Renderer::Impl::installScene(const Scene& s, SceneBvh bvh) {
  GpuScene next(vk, s, std::move(bvh));
  HT_VK(vkQueueWaitIdle(vk.queue));
  scene = std::move(next);
  bindScene();
  descriptors.flush();
  bvhStats.layout = scene.layout();
  bvhStats.fullBuilds++;
}

std::vector<std::uint32_t> Renderer::Impl::moveNodes(const Scene& s, std::span<const std::uint32_t> movedNodes,
                                                     const std::optional<MovedBounds>& bounds) {
  const auto start = std::chrono::steady_clock::now();
  std::vector<std::uint32_t> moved;  // instance indices (Scene::instances order = the TwoLevelBvh's)
  const std::vector<SceneInstance> instances = s.instances();
  for (std::uint32_t i = 0; i < instances.size(); ++i) {
    const auto node = instances[i].node;
    if (node >= 0 &&
        std::find(movedNodes.begin(), movedNodes.end(), static_cast<std::uint32_t>(node)) != movedNodes.end())
      moved.push_back(i);
  }
  if (scene.layout() != bvh::BvhLayout::TwoLevel) {
    installScene(s, buildSceneBvh(s, buildOptions, BvhLayoutPolicy::TwoLevel));
  } else {
    HT_VK(vkQueueWaitIdle(vk.queue));
    if (scene.moveInstances(s, moved)) bindScene();
    descriptors.flush();
    bvhStats.instanceUpdates++;
    bvhStats.lastRefitMs = scene.twoLevel()->timings().refitMs;
    bvhStats.lastTopLevelMs = scene.twoLevel()->timings().topLevelMs;
    bvhStats.lastUploadMs = scene.lastUploadMs();
  }
  // Another scene version on either path: accumulations restart, or only their targets near the moved bounds.
  std::optional<Bounds3> changed;
  if (bounds) {
    changed = Bounds3{};
    for (const Bounds3& b : {bounds->before, bounds->after}) {
      if (b.empty()) continue;
      changed->extend(b.lo);
      changed->extend(b.hi);
    }
  }
  sceneChanged(changed);
  bvhStats.lastUpdateMs = msSince(start);
  return moved;
}

void Renderer::Impl::updateLights(const Scene& s) {
  HT_VK(vkQueueWaitIdle(vk.queue));
  const std::uint32_t raysChanged = scene.updateLights(s);
  sceneChanged(std::nullopt);
  reuse.lightsEdited(raysChanged);
}

void Renderer::Impl::bindScene() {
  using namespace gpu_shared;
  bool nodes = descriptors.setUniformTexels(HT_BINDING_BVH_NODES, scene.nodes, VK_FORMAT_R32G32B32A32_SFLOAT);
  descriptors.setUniformTexels(HT_BINDING_BVH_NODE_UINTS, scene.nodes, VK_FORMAT_R32G32B32A32_UINT);
  bool tris = descriptors.setUniformTexels(HT_BINDING_BVH_TRIS, scene.bvhTriangles, VK_FORMAT_R32G32B32A32_SFLOAT);
  descriptors.setUniformTexels(HT_BINDING_BVH_TRI_UINTS, scene.bvhTriangles, VK_FORMAT_R32G32B32A32_UINT);
  bvhTexelsCover = nodes && tris;  // else the trace kernels read the BVH by device address
  // The top level and the instance table are read through texel fetches only (bvh_access.glsl).
  const bool top = descriptors.setUniformTexels(HT_BINDING_TOP_NODES, scene.topNodes, VK_FORMAT_R32G32B32A32_SFLOAT);
  descriptors.setUniformTexels(HT_BINDING_TOP_NODE_UINTS, scene.topNodes, VK_FORMAT_R32G32B32A32_UINT);
  const bool table = descriptors.setUniformTexels(HT_BINDING_INSTANCES, scene.instances, VK_FORMAT_R32G32B32A32_UINT);
  if (!top || !table) {
    throw GpuError("two-level BVH: the top level over " + std::to_string(scene.twoLevel()->instanceCount()) +
                   " instances exceeds the device's texel buffers (" + std::to_string(vk.info.maxTexelBufferElements) +
                   " elements)");
  }
  descriptors.setUniformBuffer(HT_BINDING_FRAME, frame);
  const TexelBinding records[] = {{HT_BINDING_VERTICES, &scene.vertices, VK_FORMAT_R32G32B32A32_SFLOAT},
                                  {HT_BINDING_NORMALS, &scene.normals, VK_FORMAT_R32G32B32A32_SFLOAT},
                                  {HT_BINDING_TEXCOORDS, &scene.texcoords, VK_FORMAT_R32G32_SFLOAT},
                                  {HT_BINDING_TRIANGLES, &scene.triangles, VK_FORMAT_R32G32B32A32_UINT},
                                  {HT_BINDING_MATERIALS, &scene.materials, VK_FORMAT_R32G32B32A32_SFLOAT},
                                  {HT_BINDING_LIGHTS, &scene.lights, VK_FORMAT_R32G32B32A32_SFLOAT},
                                  {HT_BINDING_TEXTURES, &scene.textures, VK_FORMAT_R32G32B32A32_UINT},
                                  {HT_BINDING_TEXELS, &scene.texels, VK_FORMAT_R32G32B32A32_SFLOAT}};
  for (const TexelBinding& record : records) {
    if (!descriptors.setUniformTexels(record.binding, *record.buffer, record.format)) {
      throw GpuError("scene too large for the device's texel buffers (" +
                     std::to_string(vk.info.maxTexelBufferElements) + " elements)");
    }
  }
}

void Renderer::Impl::bindState() {
  using namespace gpu_shared;
  const bool freshWork = boundWorkGeneration != work.generation;
  boundWorkGeneration = work.generation;
  const TexelBinding state[] = {{HT_BINDING_RAY_QUEUE_0, &work.rays[0], VK_FORMAT_R32G32B32A32_SFLOAT},
                                {HT_BINDING_RAY_QUEUE_1, &work.rays[1], VK_FORMAT_R32G32B32A32_SFLOAT},
                                {HT_BINDING_QUEUE_PATH_0, &work.queuePath[0], VK_FORMAT_R32_UINT},
                                {HT_BINDING_QUEUE_PATH_1, &work.queuePath[1], VK_FORMAT_R32_UINT},
                                {HT_BINDING_QUEUE_LEAVES, &work.queueLeaves, VK_FORMAT_R32_UINT},
                                {HT_BINDING_HITS, &work.hits, VK_FORMAT_R32G32B32A32_UINT},
                                {HT_BINDING_RADIANCE, &work.radiance, VK_FORMAT_R32G32B32A32_SFLOAT},
                                {HT_BINDING_THROUGHPUT, &work.throughput, VK_FORMAT_R32G32B32A32_SFLOAT},
                                {HT_BINDING_SHADOW_RAYS, &work.shadowRays, VK_FORMAT_R32G32B32A32_SFLOAT},
                                {HT_BINDING_SHADOW_CONTRIB, &work.shadowContrib, VK_FORMAT_R32G32B32A32_SFLOAT},
                                {HT_BINDING_SHADOW_QUEUE, &work.shadowQueue, VK_FORMAT_R32G32_UINT}};
  for (const TexelBinding& s : state) descriptors.setStorageTexels(s.binding, *s.buffer, s.format, freshWork);
  const bool freshOutputs = boundOutputGeneration != outputs.generation;
  boundOutputGeneration = outputs.generation;
  descriptors.setStorageTexels(HT_BINDING_SUBPIXELS, outputs.subpixels, VK_FORMAT_R32_SFLOAT, freshOutputs);
  descriptors.setUniformTexels(HT_BINDING_SUBPIXEL_TEXELS, outputs.subpixels, VK_FORMAT_R32_SFLOAT, freshOutputs);
  descriptors.setStorageTexels(HT_BINDING_OUTPUT_IMAGE, outputs.image, VK_FORMAT_R32G32B32A32_SFLOAT, freshOutputs);
  descriptors.flush();
}

void Renderer::Impl::beginCommands() {
  HT_VK(vkResetCommandBuffer(cmd, 0));
  VkCommandBufferBeginInfo bi{VK_STRUCTURE_TYPE_COMMAND_BUFFER_BEGIN_INFO};
  bi.flags = VK_COMMAND_BUFFER_USAGE_ONE_TIME_SUBMIT_BIT;
  HT_VK(vkBeginCommandBuffer(cmd, &bi));
}

void Renderer::Impl::submitAndWait() {
  HT_VK(vkEndCommandBuffer(cmd));
  VkSubmitInfo si{VK_STRUCTURE_TYPE_SUBMIT_INFO};
  si.commandBufferCount = 1;
  si.pCommandBuffers = &cmd;
  HT_VK(vkResetFences(vk.device, 1, &fence));
  HT_VK(vkQueueSubmit(vk.queue, 1, &si, fence));
  HT_VK(vkWaitForFences(vk.device, 1, &fence, VK_TRUE, UINT64_MAX));
}

void Renderer::Impl::checkCounters(const char* what) {
  const GpuCounters& c = counterBlock();
  if (c.overflowCount > 0) {
    throw GpuError(std::string(what) + ": " + std::to_string(c.overflowCount) +
                   " ray(s) exceeded the BVH traversal step limit of " + std::to_string(frameBlock().scene.z) +
                   " steps, so hits could be missing (lavapipe stops shader loops after 65,535 iterations). "
                   "The scene's BVH is pathological (huge overlapping triangles?); results were discarded.");
  }
}

void Renderer::Impl::fillFrame(const FrameCamera& camera, const FrameShape& shape, const RowBand& band,
                               std::uint32_t viewFirst, std::uint32_t viewCount, const RenderSettings& settings) {
  FrameBlock& f = frameBlock();
  std::memset(&f, 0, sizeof(f));
  fillFrameBasics(f);
  const std::uint64_t chunkTargets =
      static_cast<std::uint64_t>(shape.width) * shape.height * viewCount * shape.targetsPerPixel;
  f.dims = glm::uvec4(shape.width, shape.height, settings.spp, static_cast<std::uint32_t>(chunkTargets));
  f.views = glm::uvec4(viewCount, viewFirst, static_cast<std::uint32_t>(settings.filter), band.first);
  f.scene =
      glm::uvec4(scene.lightCount(), scene.textureCount(), gpu_shared::HT_TRAVERSAL_STEP_LIMIT, settings.maxDepth);
  f.frame = glm::uvec4(settings.seed, band.viewRows, shape.targetsPerPixel, 0u);
  f.background = glm::vec4(scene.background(), 0.0f);
  f.ambient = glm::vec4(scene.ambient(), 0.0f);
  f.camera = cameraBlock(camera);
  const auto* tableCamera = std::get_if<RayTableCamera>(&camera);
  bindRayTable(tableCamera ? tableCamera->table : nullptr);
}

Renderer::Renderer(VulkanContext& context, const Scene& scene, const bvh::BuildOptions& buildOptions)
    : impl_(std::make_unique<Impl>(context.impl(), GpuScene(context.impl(), scene, buildOptions), buildOptions,
                                   scene.bounds())) {}

Renderer::Renderer(VulkanContext& context, const Scene& scene, bvh::GpuBvh bvh, const bvh::BuildOptions& buildOptions)
    : impl_(std::make_unique<Impl>(context.impl(), GpuScene(context.impl(), scene, std::move(bvh)), buildOptions,
                                   scene.bounds())) {}

Renderer::Renderer(VulkanContext& context, const Scene& scene, SceneBvh bvh, const bvh::BuildOptions& buildOptions)
    : impl_(std::make_unique<Impl>(context.impl(), GpuScene(context.impl(), scene, std::move(bvh)), buildOptions,
                                   scene.bounds())) {}

Renderer::~Renderer() = default;

const bvh::BuildReport& Renderer::bvhReport() const { return impl_->scene.bvhReport(); }
void Renderer::replaceScene(const Scene& scene, BvhLayoutPolicy policy) {
  impl_->replaceScene(scene, policy);
  impl_->reuse.invalidate();
}
void Renderer::updateLights(const Scene& scene) { impl_->updateLights(scene); }
void Renderer::moveNodes(const Scene& scene, std::span<const std::uint32_t> nodes, std::optional<MovedBounds> moved) {
  const std::vector<std::uint32_t> instances = impl_->moveNodes(scene, nodes, moved);
  if (moved) {
    impl_->reuse.geometryMoved(moved->before, moved->after, instances,
                               std::array<glm::vec4, 2>{moved->beforeBall, moved->afterBall});
  } else {
    impl_->reuse.invalidate();
  }
}
void Renderer::replaceSceneAfterMove(const Scene& scene, const Bounds3& oldBounds, const Bounds3& newBounds) {
  impl_->replaceScene(scene, BvhLayoutPolicy::Automatic);
  impl_->reuse.geometryMoved(oldBounds, newBounds);
  Bounds3 moved;  // the change is a move: accumulations restart only near it
  for (const Bounds3& b : {oldBounds, newBounds}) {
    if (b.empty()) continue;
    moved.extend(b.lo);
    moved.extend(b.hi);
  }
  impl_->sceneChanges.back().moved = moved;
}
BvhStats Renderer::bvhStats() const { return impl_->bvhStats; }
const SceneFeatures& Renderer::features() const { return impl_->scene.features(); }

RenderResult Renderer::render(const FrameCamera& camera, const RenderSettings& settings) {
  return impl_->render(camera, settings);
}

RenderResult Renderer::accumulate(const FrameCamera& camera, const RenderSettings& settings, Accumulator& accumulator) {
  return impl_->accumulate(camera, settings, accumulator);
}

void Renderer::recycle(std::vector<float>&& rgba) {
  std::vector<float> oldest;  // freed after the lock
  std::lock_guard lock(impl_->spareMutex);
  if (impl_->spareRgba.size() == Impl::kSpareFrames) {
    oldest = std::move(impl_->spareRgba.front());
    impl_->spareRgba.erase(impl_->spareRgba.begin());
  }
  impl_->spareRgba.push_back(std::move(rgba));
}

std::vector<gpu_shared::HtRay> Renderer::generateRays(const FrameCamera& camera, const RenderSettings& settings,
                                                      std::uint64_t firstTarget, std::uint32_t targetCount,
                                                      TraceStats* stats) {
  return impl_->generateRays(camera, settings, firstTarget, targetCount, stats);
}

std::vector<gpu_shared::HtHit> Renderer::traceClosest(std::span<const gpu_shared::HtRay> rays, TraceStats* stats) {
  return impl_->traceBatch(rays, false, stats);
}

std::vector<std::uint32_t> Renderer::traceOccluded(std::span<const gpu_shared::HtRay> rays, TraceStats* stats) {
  std::vector<gpu_shared::HtHit> hits = impl_->traceBatch(rays, true, stats);
  std::vector<std::uint32_t> occluded(hits.size());
  for (size_t i = 0; i < hits.size(); ++i) occluded[i] = hits[i].triId != gpu_shared::HT_MISS ? 1u : 0u;
  return occluded;
}

}  // namespace ht::gpu
