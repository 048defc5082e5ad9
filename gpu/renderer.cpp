// renderer.cpp - the wavefront frame loop (docs/BVH.md §7): batches of paths go through raygen, then per bounce
// trace_closest -> shade -> [trace_any -> gather_direct], then resolve; the frame ends with interleave.
// Batches are submitted one by one (bounded memory, progress reports); within a batch the GPU drives its own
// queues through indirect dispatches.
#include "gpu/renderer.h"

#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <cstddef>
#include <cstring>
#include <map>
#include <tuple>
#include <type_traits>
#include <utility>

#include "gpu/compute_pipeline.h"
#include "gpu/device_buffer.h"
#include "gpu/frame_descriptors.h"
#include "gpu/gpu_scene.h"
#include "gpu/pass_recorder.h"
#include "gpu/pipeline_library.h"
#include "gpu/vulkan_context.h"
#include "gpu/wavefront_types.h"

namespace ht::gpu {

using gpu_shared::FrameBlock;
using gpu_shared::GpuCounters;
using gpu_shared::HT_WORKGROUP_SIZE;
using gpu_shared::PassConstants;

static_assert(sizeof(gpu_shared::HtRay) == 32 && sizeof(gpu_shared::HtHit) == 16);
static_assert(sizeof(gpu_shared::GpuBvhNode) == 64);
static_assert(sizeof(GpuCounters) == 80 && offsetof(GpuCounters, dispatch) == 32);
static_assert(sizeof(PassConstants) == 40);
static_assert(offsetof(FrameBlock, dims) == 16 && sizeof(FrameBlock) % 16 == 0);  // std140 == C++ layout

namespace {

constexpr std::uint64_t kWorkMemoryBudget = 512ull << 20;  // per-batch path state
constexpr std::uint32_t kMaxPathsPerBatch = 1u << 20;
constexpr std::uint32_t kQueryCapacity = 4096;
constexpr std::uint32_t kMaxSpp = 4096;
constexpr std::uint32_t kMaxDepth = 32;
constexpr std::uint64_t kMaxChunkPixels = 8ull << 20;  // pixels of all views rendered by one chunk (output buffers)
constexpr std::uint32_t kMaxImageSide = 32768;

using StageTimes = std::array<double, static_cast<size_t>(Stage::Count)>;

// `spec` (a kernel's own constants, ids 0..) with constant `id` set to `value`, the ids between left 0: the
// constants common to several kernels sit at fixed high ids (trace_*: 10, shade / gather_direct: 20).
std::vector<std::uint32_t> withConstant(std::vector<std::uint32_t> spec, std::uint32_t id, std::uint32_t value) {
  spec.resize(std::max<std::size_t>(spec.size(), id + 1), 0u);
  spec[id] = value;
  return spec;
}

std::uint32_t groupsFor(std::uint64_t n) {
  return static_cast<std::uint32_t>((n + HT_WORKGROUP_SIZE - 1) / HT_WORKGROUP_SIZE);
}

double msSince(std::chrono::steady_clock::time_point t0) {
  return std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
}

}  // namespace

// Path state for one batch of `capacity` paths; reallocated only when a frame needs more.
struct WorkBuffers {
  std::uint32_t capacity = 0;
  std::uint32_t lightSlots = 0;  // shadow slots per path
  std::uint64_t generation = 0;  // bumped on every reallocation
  DeviceBuffer rays[2], queuePath[2], hits, radiance, throughput, shadowRays, shadowContrib, shadowQueue;

  void ensure(VulkanContext::Impl& vk, std::uint32_t paths, std::uint32_t lights) {
    std::uint32_t slots = std::max(lights, 1u);
    if (paths <= capacity && slots <= lightSlots) return;
    capacity = std::max(paths, capacity);
    lightSlots = std::max(slots, lightSlots);
    ++generation;
    VkDeviceSize n = capacity, s = static_cast<VkDeviceSize>(capacity) * lightSlots;
    for (int q = 0; q < 2; ++q) {
      rays[q] = DeviceBuffer(vk, n * sizeof(gpu_shared::HtRay), MemoryPlace::Device);
      queuePath[q] = DeviceBuffer(vk, n * 4, MemoryPlace::Device);
    }
    hits = DeviceBuffer(vk, n * sizeof(gpu_shared::HtHit), MemoryPlace::Device);
    radiance = DeviceBuffer(vk, n * 16, MemoryPlace::Device);
    throughput = DeviceBuffer(vk, n * 16, MemoryPlace::Device);
    shadowRays = DeviceBuffer(vk, s * sizeof(gpu_shared::HtRay), MemoryPlace::Device);
    shadowContrib = DeviceBuffer(vk, s * 16, MemoryPlace::Device);
    shadowQueue = DeviceBuffer(vk, s * 4, MemoryPlace::Device);
  }
  static std::uint64_t bytesPerPath(std::uint32_t lights) {
    return 2 * (sizeof(gpu_shared::HtRay) + 4) + sizeof(gpu_shared::HtHit) + 32 +
           std::max(lights, 1u) * (sizeof(gpu_shared::HtRay) + 16 + 4);
  }
};

// The frame's outputs, kept across frames of the same size (a daemon streams many) instead of reallocated.
struct OutputBuffers {
  std::uint32_t width = 0, height = 0;
  std::uint64_t generation = 0;  // bumped on every reallocation
  DeviceBuffer subpixels, image;

  void ensure(VulkanContext::Impl& vk, std::uint32_t w, std::uint32_t h) {
    if (w == width && h == height) return;
    subpixels = DeviceBuffer(vk, static_cast<VkDeviceSize>(w) * h * 3 * sizeof(float), MemoryPlace::Device);
    image = DeviceBuffer(vk, static_cast<VkDeviceSize>(w) * h * 16, MemoryPlace::HostReadback);
    width = w;
    height = h;
    ++generation;
  }
};

struct Renderer::Impl {
  VulkanContext::Impl& vk;
  GpuScene scene;
  const PipelineLayout& layout;  // the device's (PipelineLibrary), shared with every Renderer
  FrameDescriptors descriptors;
  bool bvhTexelsCover = true;
  std::uint64_t boundWorkGeneration = 0;
  std::uint64_t boundOutputGeneration = 0;
  DeviceBuffer frame;     // FrameBlock, host visible
  DeviceBuffer counters;  // GpuCounters, host visible
  WorkBuffers work;
  OutputBuffers outputs;
  VkQueryPool queryPool = VK_NULL_HANDLE;
  VkCommandBuffer cmd = VK_NULL_HANDLE;
  VkFence fence = VK_NULL_HANDLE;
  FrameCamera camera;
  DeviceBuffer refineBuffer;    // adaptive refinement: per-subgroup counts, staging, target list (refine_select.comp)
  DeviceBuffer rayTableTexels;  // the current ray table (2 texels per entry) or a 1-entry dummy
  std::shared_ptr<const RayTable> boundRayTable;  // which table rayTableTexels holds

  bvh::BuildOptions buildOptions;

  Impl(VulkanContext::Impl& v, const Scene& s, const bvh::BuildOptions& o)
      : vk(v),
        scene(v, s, o),
        layout(v.pipelines->layout()),
        descriptors(v, layout.setLayout()),
        frame(v, sizeof(FrameBlock), MemoryPlace::HostReadback),
        counters(v, sizeof(GpuCounters), MemoryPlace::HostReadback),
        buildOptions(o) {
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
    bindRayTable();
  }

  ~Impl() {
    vkDeviceWaitIdle(vk.device);
    vkDestroyFence(vk.device, fence, nullptr);
    vkFreeCommandBuffers(vk.device, vk.commandPool, 1, &cmd);
    vkDestroyQueryPool(vk.device, queryPool, nullptr);
  }

  const ComputePipeline& pipeline(ShaderId id, const std::vector<std::uint32_t>& spec = {}) {
    return vk.pipelines->get(id, spec);
  }

  // Specialisation of raygen: the camera model, then a lenticular panel's Gen3 cell mode and count, so the cell code
  // folds to the panel's own pattern (lenticular_model.h HT_LENTICULAR_CELL_MODE; a CPU driver pays for untaken code),
  // then REFINING for the pass over listed targets.
  std::vector<std::uint32_t> raygenSpec(const FrameShape& shape, bool refining = false) const {
    const auto* lenticular = std::get_if<gpu_shared::LenticularParams>(&camera);
    if (!lenticular) return {shape.model, 0u, 0u, refining};
    return {shape.model, static_cast<std::uint32_t>(lenticular->flags.x),
            static_cast<std::uint32_t>(lenticular->flags.y), refining};
  }

  // Specialisation of the kernels that continue paths (shade, gather_direct): their own constants, then
  // constant_id 20 = PRIMARY_DEPTH, true for the dispatches at depth 0 (common.glsl queue_path).
  static std::vector<std::uint32_t> depthSpec(std::vector<std::uint32_t> own, std::uint32_t depth) {
    return withConstant(std::move(own), 20, depth == 0 ? 1u : 0u);
  }

  // Specialisation of the trace kernels: their own constants, then constant_id 10 = TEXEL_FETCH.
  std::vector<std::uint32_t> traceSpec(std::vector<std::uint32_t> own) const {
    return withConstant(std::move(own), 10, bvhTexelsCover ? 1u : 0u);
  }

  // Binding HT_BINDING_RAY_TABLE: the ray-table camera's entries (uploaded when the table object changes), else a
  // dummy entry so the descriptor is valid.
  void bindRayTable() {
    const auto* tableCamera = std::get_if<RayTableCamera>(&camera);
    std::shared_ptr<const RayTable> table = tableCamera ? tableCamera->table : nullptr;
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
      throw GpuError("ray table of " + std::to_string(texels.size() / 2) +
                     " entries exceeds the device's texel buffers");
    }
    descriptors.flush();
    boundRayTable = table;
  }

  // A new BVH and scene records, built and uploaded before the current ones are released (a failure leaves them);
  // pipelines, work and output buffers stay. Every frame waits for its own work, so nothing in flight reads them.
  void replaceScene(const Scene& s) {
    GpuScene next(vk, s, buildOptions);
    HT_VK(vkQueueWaitIdle(vk.queue));
    scene = std::move(next);
    bindScene();
    descriptors.flush();
  }

  // New light values (same count) into the bound light buffer: no BVH build, no descriptor change.
  void updateLights(const Scene& s) {
    HT_VK(vkQueueWaitIdle(vk.queue));
    scene.updateLights(s);
  }

  FrameBlock& frameBlock() { return *static_cast<FrameBlock*>(frame.mapped()); }
  GpuCounters& counterBlock() { return *static_cast<GpuCounters*>(counters.mapped()); }

  // Scene records and BVH views: written at construction and again by replaceScene, whose new buffers were created
  // while the bound ones still existed, so their handles differ and every view is rebuilt.
  void bindScene() {
    using namespace gpu_shared;
    bool nodes = descriptors.setUniformTexels(HT_BINDING_BVH_FIRST + 0, scene.nodes, VK_FORMAT_R32G32B32A32_SFLOAT);
    descriptors.setUniformTexels(HT_BINDING_BVH_FIRST + 1, scene.nodes, VK_FORMAT_R32G32B32A32_UINT);
    bool tris =
        descriptors.setUniformTexels(HT_BINDING_BVH_FIRST + 2, scene.bvhTriangles, VK_FORMAT_R32G32B32A32_SFLOAT);
    descriptors.setUniformTexels(HT_BINDING_BVH_FIRST + 3, scene.bvhTriangles, VK_FORMAT_R32G32B32A32_UINT);
    bvhTexelsCover = nodes && tris;  // else the trace kernels read the BVH by device address
    descriptors.setUniformBuffer(HT_BINDING_FRAME, frame);
    const std::pair<const DeviceBuffer*, VkFormat> records[] = {
        {&scene.vertices, VK_FORMAT_R32G32B32A32_SFLOAT},  {&scene.normals, VK_FORMAT_R32G32B32A32_SFLOAT},
        {&scene.texcoords, VK_FORMAT_R32G32_SFLOAT},       {&scene.triangles, VK_FORMAT_R32G32B32A32_UINT},
        {&scene.materials, VK_FORMAT_R32G32B32A32_SFLOAT}, {&scene.lights, VK_FORMAT_R32G32B32A32_SFLOAT},
        {&scene.textures, VK_FORMAT_R32G32B32A32_UINT},    {&scene.texels, VK_FORMAT_R32G32B32A32_SFLOAT}};
    for (std::uint32_t k = 0; k < 8; ++k) {
      if (!descriptors.setUniformTexels(HT_BINDING_SCENE_FIRST + k, *records[k].first, records[k].second)) {
        throw GpuError("scene too large for the device's texel buffers (" +
                       std::to_string(vk.info.maxTexelBufferElements) + " elements)");
      }
    }
  }

  // Per-path state of the current work buffers, plus the frame's outputs.
  void bindState() {
    using namespace gpu_shared;
    const std::uint32_t b = HT_BINDING_STATE_FIRST;
    const bool freshWork = boundWorkGeneration != work.generation;
    boundWorkGeneration = work.generation;
    const std::pair<const DeviceBuffer*, VkFormat> state[] = {{&work.rays[0], VK_FORMAT_R32G32B32A32_SFLOAT},
                                                              {&work.rays[1], VK_FORMAT_R32G32B32A32_SFLOAT},
                                                              {&work.queuePath[0], VK_FORMAT_R32_UINT},
                                                              {&work.queuePath[1], VK_FORMAT_R32_UINT},
                                                              {&work.hits, VK_FORMAT_R32G32B32A32_UINT},
                                                              {&work.radiance, VK_FORMAT_R32G32B32A32_SFLOAT},
                                                              {&work.throughput, VK_FORMAT_R32G32B32A32_SFLOAT},
                                                              {&work.shadowRays, VK_FORMAT_R32G32B32A32_SFLOAT},
                                                              {&work.shadowContrib, VK_FORMAT_R32G32B32A32_SFLOAT},
                                                              {&work.shadowQueue, VK_FORMAT_R32_UINT}};
    for (std::uint32_t k = 0; k < 10; ++k)
      descriptors.setStorageTexels(b + k, *state[k].first, state[k].second, freshWork);
    const bool freshOutputs = boundOutputGeneration != outputs.generation;
    boundOutputGeneration = outputs.generation;
    descriptors.setStorageTexels(b + 10, outputs.subpixels, VK_FORMAT_R32_SFLOAT, freshOutputs);
    descriptors.setUniformTexels(HT_BINDING_SUBPIXEL_TEXELS, outputs.subpixels, VK_FORMAT_R32_SFLOAT, freshOutputs);
    descriptors.setStorageTexels(b + 11, outputs.image, VK_FORMAT_R32G32B32A32_SFLOAT, freshOutputs);
    descriptors.flush();
  }

  void fillFrameBasics(FrameBlock& f) {
    f.counters = counters.address();
    f.flags = glm::uvec4(scene.hasNormals ? 1u : 0u, scene.hasTexcoords ? 1u : 0u, 0u, 0u);
  }

  PassConstants passConstants(std::uint32_t first, std::uint32_t count, std::uint32_t depth,
                              std::uint32_t queue) const {
    return PassConstants{
        frame.address(), scene.nodes.address(), scene.bvhTriangles.address(), first, count, depth, queue};
  }

  void beginCommands() {
    HT_VK(vkResetCommandBuffer(cmd, 0));
    VkCommandBufferBeginInfo bi{VK_STRUCTURE_TYPE_COMMAND_BUFFER_BEGIN_INFO};
    bi.flags = VK_COMMAND_BUFFER_USAGE_ONE_TIME_SUBMIT_BIT;
    HT_VK(vkBeginCommandBuffer(cmd, &bi));
  }

  void submitAndWait() {
    HT_VK(vkEndCommandBuffer(cmd));
    VkSubmitInfo si{VK_STRUCTURE_TYPE_SUBMIT_INFO};
    si.commandBufferCount = 1;
    si.pCommandBuffers = &cmd;
    HT_VK(vkResetFences(vk.device, 1, &fence));
    HT_VK(vkQueueSubmit(vk.queue, 1, &si, fence));
    HT_VK(vkWaitForFences(vk.device, 1, &fence, VK_TRUE, UINT64_MAX));
  }

  void checkCounters(const char* what) {
    const GpuCounters& c = counterBlock();
    if (c.overflowCount > 0) {
      throw GpuError(std::string(what) + ": " + std::to_string(c.overflowCount) +
                     " ray(s) exceeded the BVH traversal step limit of " + std::to_string(frameBlock().scene.z) +
                     " steps, so hits could be missing (lavapipe stops shader loops after 65,535 iterations). "
                     "The scene's BVH is pathological (huge overlapping triangles?); results were discarded.");
    }
  }

  // Writes the camera block and the frame-wide values of a frame of `shape` covering views [viewFirst, +viewCount).
  void fillFrame(const FrameShape& shape, std::uint32_t viewFirst, std::uint32_t viewCount,
                 const RenderSettings& settings);
  RenderResult render(const RenderSettings& settings);
  void renderChunk(const FrameShape& shape, std::uint32_t viewFirst, std::uint32_t viewCount,
                   const RenderSettings& settings, StageTimes& stageMs, RenderResult& result);
  // Traces paths [0, totalPaths) of `spp` samples per target in batches of perBatch (a multiple of spp) and resolves
  // them into the subpixel buffer. refining: the listed targets of FrameBlock.refine (refineInfo.w = the base spp),
  // through the REFINING pipelines of raygen and resolve; else the chunk's base pass, its first call, which clears
  // the shadow slots (gather_direct leaves every slot it used cleared for later batches).
  void tracePaths(const FrameShape& shape, std::uint32_t spp, std::uint64_t totalPaths, std::uint64_t perBatch,
                  bool refining, const RenderSettings& settings, StageTimes& stageMs,
                  const std::function<void(double)>& progress);
  std::uint64_t selectRefinedTargets(const FrameShape& shape, std::uint64_t targets, float contrast,
                                     StageTimes& stageMs);
  std::vector<gpu_shared::HtRay> generateRays(const RenderSettings& settings, std::uint64_t firstTarget,
                                              std::uint32_t targetCount, TraceStats* stats);
  std::vector<gpu_shared::HtHit> traceBatch(std::span<const gpu_shared::HtRay> rays, bool occlusion, TraceStats* stats);
};

namespace {

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
}

void checkShape(const FrameShape& shape, std::uint32_t spp) {
  if (shape.width == 0 || shape.height == 0 || shape.width > kMaxImageSide || shape.height > kMaxImageSide) {
    throw GpuError("image size " + std::to_string(shape.width) + "x" + std::to_string(shape.height) +
                   " out of range [1, 32768]");
  }
  if (shape.views == 0) throw GpuError("camera has no views");
  if (shape.targets() * spp >= (1ull << 32)) {
    throw GpuError("frame of " + std::to_string(shape.targets()) + " targets x spp " + std::to_string(spp) +
                   " exceeds 2^32 rays per frame: lower --spp to at most " +
                   std::to_string(((1ull << 32) - 1) / shape.targets()));
  }
}

}  // namespace

FrameShape frameShape(const FrameCamera& camera) {
  using namespace gpu_shared;
  FrameShape shape;
  shape.model = static_cast<std::uint32_t>(camera.index());
  static_assert(std::variant_size_v<FrameCamera> == HT_MODEL_COUNT);
  static_assert(std::is_same_v<std::variant_alternative_t<HT_MODEL_LENTICULAR, FrameCamera>, LenticularParams>);
  static_assert(std::is_same_v<std::variant_alternative_t<HT_MODEL_PINHOLE, FrameCamera>, PinholeParams>);
  static_assert(std::is_same_v<std::variant_alternative_t<HT_MODEL_QUILT, FrameCamera>, QuiltParams>);
  static_assert(
      std::is_same_v<std::variant_alternative_t<HT_MODEL_PROJECTOR_ARRAY, FrameCamera>, ProjectorArrayParams>);
  static_assert(std::is_same_v<std::variant_alternative_t<HT_MODEL_INTEGRAL, FrameCamera>, IntegralParams>);
  static_assert(std::is_same_v<std::variant_alternative_t<HT_MODEL_CAPTURE_GRID, FrameCamera>, CaptureGridParams>);
  static_assert(std::is_same_v<std::variant_alternative_t<HT_MODEL_OBLIQUE, FrameCamera>, ObliqueParams>);
  static_assert(std::is_same_v<std::variant_alternative_t<HT_MODEL_RAY_TABLE, FrameCamera>, RayTableCamera>);
  auto size = [](float w, float h) { return std::pair{static_cast<std::uint32_t>(w), static_cast<std::uint32_t>(h)}; };
  switch (shape.model) {
    case HT_MODEL_LENTICULAR: {
      const auto& p = std::get<LenticularParams>(camera);
      std::tie(shape.width, shape.height) = size(p.panel.x, p.panel.y);
      shape.targetsPerPixel = 3;
      break;
    }
    case HT_MODEL_PINHOLE: {
      const auto& p = std::get<PinholeParams>(camera);
      std::tie(shape.width, shape.height) = size(p.lens.z, p.lens.w);
      break;
    }
    case HT_MODEL_QUILT: {
      const auto& p = std::get<QuiltParams>(camera);
      shape.width = static_cast<std::uint32_t>(p.tiles.z);
      shape.height = static_cast<std::uint32_t>(p.tiles.w);
      shape.views = static_cast<std::uint32_t>(p.views.x);
      break;
    }
    case HT_MODEL_PROJECTOR_ARRAY: {
      const auto& p = std::get<ProjectorArrayParams>(camera);
      std::tie(shape.width, shape.height) = size(p.projector[0][0].w, p.projector[0][1].w);
      shape.views = static_cast<std::uint32_t>(p.observer.w);
      if (shape.views > HT_MAX_PROJECTORS)
        throw GpuError("projector array of " + std::to_string(shape.views) + " projectors exceeds 128");
      break;
    }
    case HT_MODEL_INTEGRAL: {
      const auto& p = std::get<IntegralParams>(camera);
      std::tie(shape.width, shape.height) = size(p.panel.x, p.panel.y);
      shape.targetsPerPixel = 3;
      break;
    }
    case HT_MODEL_CAPTURE_GRID: {
      const auto& p = std::get<CaptureGridParams>(camera);
      shape.width = static_cast<std::uint32_t>(p.grid.z);
      shape.height = static_cast<std::uint32_t>(p.grid.w);
      shape.views = static_cast<std::uint32_t>(p.grid.x) * static_cast<std::uint32_t>(p.grid.y);
      break;
    }
    case HT_MODEL_OBLIQUE: {
      const auto& p = std::get<ObliqueParams>(camera);
      shape.width = static_cast<std::uint32_t>(p.grid.z);
      shape.height = static_cast<std::uint32_t>(p.grid.w);
      shape.views = static_cast<std::uint32_t>(p.grid.x) * static_cast<std::uint32_t>(p.grid.y);
      break;
    }
    default: {
      const auto& p = std::get<RayTableCamera>(camera);
      if (!p.table) throw GpuError("ray-table camera without a table");
      shape.width = p.table->width;
      shape.height = p.table->height;
      break;
    }
  }
  return shape;
}

void Renderer::Impl::fillFrame(const FrameShape& shape, std::uint32_t viewFirst, std::uint32_t viewCount,
                               const RenderSettings& settings) {
  FrameBlock& f = frameBlock();
  std::memset(&f, 0, sizeof(f));
  fillFrameBasics(f);
  const std::uint64_t chunkTargets =
      static_cast<std::uint64_t>(shape.width) * shape.height * viewCount * shape.targetsPerPixel;
  f.dims = glm::uvec4(shape.width, shape.height, settings.spp, static_cast<std::uint32_t>(chunkTargets));
  f.views = glm::uvec4(viewCount, viewFirst, static_cast<std::uint32_t>(settings.filter), 0u);
  f.scene =
      glm::uvec4(scene.lightCount(), scene.textureCount(), gpu_shared::HT_TRAVERSAL_STEP_LIMIT, settings.maxDepth);
  f.frame = glm::uvec4(settings.seed, 0u, 0u, 0u);
  f.background = glm::vec4(scene.background(), 0.0f);
  f.ambient = glm::vec4(scene.ambient(), 0.0f);
  std::visit(
      [&f](const auto& p) {
        using T = std::decay_t<decltype(p)>;
        if constexpr (std::is_same_v<T, gpu_shared::LenticularParams>)
          f.lenticular = p;
        else if constexpr (std::is_same_v<T, gpu_shared::PinholeParams>)
          f.pinhole = p;
        else if constexpr (std::is_same_v<T, gpu_shared::QuiltParams>)
          f.quilt = p;
        else if constexpr (std::is_same_v<T, gpu_shared::ProjectorArrayParams>)
          f.projectors = p;
        else if constexpr (std::is_same_v<T, gpu_shared::IntegralParams>)
          f.integral = p;
        else if constexpr (std::is_same_v<T, gpu_shared::CaptureGridParams>)
          f.captureGrid = p;
        else if constexpr (std::is_same_v<T, gpu_shared::ObliqueParams>)
          f.oblique = p;
        else
          f.rayTable = p.params;
      },
      camera);
  bindRayTable();
}

RenderResult Renderer::Impl::render(const RenderSettings& settings) {
  auto t0 = std::chrono::steady_clock::now();
  checkSettings(settings);
  const FrameShape shape = frameShape(camera);
  checkShape(shape, std::max(settings.spp, settings.refineSpp));
  RenderResult result;
  result.width = shape.width;
  result.height = shape.height;
  result.views = shape.views;
  const std::uint64_t viewPixels = static_cast<std::uint64_t>(shape.width) * shape.height;
  result.rgba.resize(static_cast<size_t>(viewPixels * shape.views * 4));
  const auto chunkViews =
      static_cast<std::uint32_t>(std::clamp<std::uint64_t>(kMaxChunkPixels / viewPixels, 1, shape.views));
  std::array<double, static_cast<size_t>(Stage::Count)> stageMs{};
  double readbackMs = 0.0;
  for (std::uint32_t first = 0; first < shape.views; first += chunkViews) {
    const std::uint32_t count = std::min(chunkViews, shape.views - first);
    RenderSettings chunkSettings = settings;
    if (settings.progress) {
      chunkSettings.progress = [&settings, first, count, views = shape.views](double done) {
        settings.progress((first + done * count) / views);
      };
    }
    renderChunk(shape, first, count, chunkSettings, stageMs, result);
    auto tRead = std::chrono::steady_clock::now();
    outputs.image.download(result.rgba.data() + viewPixels * first * 4, viewPixels * count * 16);
    readbackMs += msSince(tRead);
  }
  const bool lights = scene.lightCount() > 0 && (scene.features().lights || settings.forceAllFeatures);
  for (size_t s = 0; s < stageMs.size(); ++s) {
    auto stage = static_cast<Stage>(s);
    if (stage == Stage::Shadow && !lights) continue;
    if (stage == Stage::Refine && settings.refineSpp == 0) continue;
    result.stages.push_back({stageName(stage), stageMs[s]});
  }
  result.stages.push_back({"readback", readbackMs});
  result.totalMs = msSince(t0);
  return result;
}

void Renderer::Impl::renderChunk(const FrameShape& shape, std::uint32_t viewFirst, std::uint32_t viewCount,
                                 const RenderSettings& settings, StageTimes& stageMs, RenderResult& result) {
  const std::uint64_t targets =
      static_cast<std::uint64_t>(shape.width) * shape.height * viewCount * shape.targetsPerPixel;
  // Batch size: whole targets, bounded by the path-state memory budget.
  const std::uint32_t maxSpp = std::max(settings.spp, settings.refineSpp);
  std::uint64_t perBatch =
      std::min<std::uint64_t>(kMaxPathsPerBatch, kWorkMemoryBudget / WorkBuffers::bytesPerPath(scene.lightCount()));
  perBatch = std::max<std::uint64_t>(maxSpp, perBatch / maxSpp * maxSpp);
  perBatch = std::min(perBatch, targets * maxSpp);
  work.ensure(vk, static_cast<std::uint32_t>(perBatch), scene.lightCount());
  outputs.ensure(vk, shape.width, shape.height * viewCount);
  bindState();
  fillFrame(shape, viewFirst, viewCount, settings);
  std::memset(counters.mapped(), 0, sizeof(GpuCounters));

  const double share = settings.refineSpp > 0 ? 0.8 : 1.0;  // progress: the refinement takes the rest
  tracePaths(shape, settings.spp, targets * settings.spp, perBatch, false, settings, stageMs, [&](double done) {
    if (settings.progress) settings.progress(done * share);
  });
  if (settings.refineSpp > 0) {
    const std::uint64_t refined = selectRefinedTargets(shape, targets, settings.refineContrast, stageMs);
    result.refinedTargets += refined;
    if (refined > 0) {
      FrameBlock& f = frameBlock();
      f.dims.z = settings.refineSpp;
      f.refineInfo.w = settings.spp;  // != 0: trace the listed targets, and keep the base samples in their mean
      const std::uint64_t refineBatch =
          std::min(perBatch / settings.refineSpp * settings.refineSpp, refined * settings.refineSpp);
      tracePaths(shape, settings.refineSpp, refined * settings.refineSpp, refineBatch, true, settings, stageMs,
                 [&](double done) {
                   if (settings.progress) settings.progress(share + done * (1.0 - share));
                 });
    }
  }
  const ComputePipeline& interleave = pipeline(ShaderId::Interleave);
  beginCommands();
  PassRecorder rec(cmd, layout.handle(), descriptors.set(), queryPool, kQueryCapacity);
  rec.dispatch(interleave, passConstants(0, 0, 0, 0),
               groupsFor(static_cast<std::uint64_t>(shape.width) * shape.height * viewCount), Stage::Interleave);
  submitAndWait();
  rec.collect(vk.device, vk.info.timestampPeriodNs, stageMs);
  const GpuCounters& c = counterBlock();
  result.raysTraced += c.raysTraced;
  result.maxTraversalSteps = std::max(result.maxTraversalSteps, c.maxSteps);
  result.nonFiniteSamples += c.nanCount;
}

void Renderer::Impl::tracePaths(const FrameShape& shape, std::uint32_t spp, std::uint64_t totalPaths,
                                std::uint64_t perBatch, bool refining, const RenderSettings& settings,
                                StageTimes& stageMs, const std::function<void(double)>& progress) {
  const SceneFeatures& feat = scene.features();
  const bool all = settings.forceAllFeatures;
  const bool lights = scene.lightCount() > 0 && (feat.lights || all);
  const bool mirror = feat.mirrors || all, glass = feat.glass || all,
             textures = (feat.textures && scene.textureCount() > 0) || all;
  const std::uint32_t depthPasses = (mirror || glass) ? settings.maxDepth + 1 : 1;

  const ComputePipeline& raygen = pipeline(ShaderId::Raygen, raygenSpec(shape, refining));
  const ComputePipeline& traceClosest = pipeline(ShaderId::TraceClosest, traceSpec({}));
  const ComputePipeline& traceAny = pipeline(ShaderId::TraceAny, traceSpec({1u}));
  const std::vector<std::uint32_t> shadeFeatures = {lights, mirror, glass, textures};
  const ComputePipeline& afterShade = pipeline(ShaderId::Prepare, {0u});
  const ComputePipeline& endDepth = pipeline(ShaderId::Prepare, {1u});
  const ComputePipeline& resolve = pipeline(ShaderId::Resolve, {shape.model, refining});

  const VkBuffer args = counters.handle();
  bool clear = !refining;
  for (std::uint64_t begin = 0; begin < totalPaths; begin += perBatch) {
    const auto count = static_cast<std::uint32_t>(std::min<std::uint64_t>(perBatch, totalPaths - begin));
    const auto batchFirst = static_cast<std::uint32_t>(begin);
    beginCommands();
    if (clear) {  // live flags of the shadow slots start cleared; gather_direct clears them after use
      vkCmdFillBuffer(cmd, work.shadowContrib.handle(), 0, VK_WHOLE_SIZE, 0);
      VkMemoryBarrier b{VK_STRUCTURE_TYPE_MEMORY_BARRIER, nullptr, VK_ACCESS_TRANSFER_WRITE_BIT,
                        VK_ACCESS_SHADER_READ_BIT | VK_ACCESS_SHADER_WRITE_BIT};
      vkCmdPipelineBarrier(cmd, VK_PIPELINE_STAGE_TRANSFER_BIT, VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT, 0, 1, &b, 0,
                           nullptr, 0, nullptr);
      clear = false;
    }
    PassRecorder rec(cmd, layout.handle(), descriptors.set(), queryPool, kQueryCapacity);
    rec.dispatch(raygen, passConstants(batchFirst, count, 0, 0), groupsFor(count), Stage::Raygen);
    for (std::uint32_t depth = 0; depth < depthPasses; ++depth) {
      const std::uint32_t q = depth % 2;
      PassConstants pc = passConstants(batchFirst, count, depth, q);
      const VkDeviceSize queueArgs = offsetof(GpuCounters, dispatch) + q * sizeof(glm::uvec4);
      const ComputePipeline& shade = pipeline(ShaderId::Shade, depthSpec(shadeFeatures, depth));
      const ComputePipeline& gather = pipeline(ShaderId::GatherDirect, depthSpec({}, depth));
      if (depth == 0) {
        rec.dispatch(traceClosest, pc, groupsFor(count), Stage::Trace);
        rec.dispatch(shade, pc, groupsFor(count), Stage::Shade);
      } else {
        rec.dispatchIndirect(traceClosest, pc, args, queueArgs, Stage::Trace);
        rec.dispatchIndirect(shade, pc, args, queueArgs, Stage::Shade);
      }
      rec.dispatch(afterShade, pc, 1, Stage::Queues);
      if (lights) {
        rec.dispatchIndirect(traceAny, pc, args, offsetof(GpuCounters, dispatch) + 2 * sizeof(glm::uvec4),
                             Stage::Shadow);
        if (depth == 0)
          rec.dispatch(gather, pc, groupsFor(count), Stage::Shadow);
        else
          rec.dispatchIndirect(gather, pc, args, queueArgs, Stage::Shadow);
      }
      rec.dispatch(endDepth, pc, 1, Stage::Queues);
    }
    rec.dispatch(resolve, passConstants(batchFirst, count, 0, 0), groupsFor(count / spp), Stage::Resolve);
    submitAndWait();
    rec.collect(vk.device, vk.info.timestampPeriodNs, stageMs);
    checkCounters("render");
    progress(static_cast<double>(begin + count) / static_cast<double>(totalPaths));
  }
}

// Lists the chunk's targets to refine (refine_select.comp) in target order; returns how many. Two passes around a
// host-side exclusive scan of one count per subgroup, so the list, and with it the frame, is the same whatever order
// the device runs the workgroups in.
std::uint64_t Renderer::Impl::selectRefinedTargets(const FrameShape& shape, std::uint64_t targets, float contrast,
                                                   StageTimes& stageMs) {
  const glm::uvec3 grid(
      groupsFor(shape.width), shape.height,
      static_cast<std::uint32_t>(targets / (std::uint64_t{shape.width} * shape.height * shape.targetsPerPixel)));
  const std::uint32_t subgroup = std::clamp(vk.info.subgroupSize, 1u, HT_WORKGROUP_SIZE);
  const std::uint64_t slots = std::uint64_t{grid.x} * grid.y * grid.z * ((HT_WORKGROUP_SIZE + subgroup - 1) / subgroup);
  const std::uint32_t stride = subgroup * shape.targetsPerPixel;  // staging per slot: a subgroup of pixels' targets
  const std::uint64_t listFirst = slots + 1 + slots * stride;
  if (listFirst + targets >= (1ull << 32)) throw GpuError("too many targets for adaptive refinement in one chunk");
  const VkDeviceSize bytes = (listFirst + targets) * sizeof(std::uint32_t);
  if (refineBuffer.size() < bytes) refineBuffer = DeviceBuffer(vk, bytes, MemoryPlace::HostReadback);
  FrameBlock& f = frameBlock();
  f.refine = refineBuffer.address();
  f.refineInfo = glm::uvec4(glm::floatBitsToUint(contrast), static_cast<std::uint32_t>(listFirst), stride, 0u);

  auto run = [&](std::uint32_t mode, glm::uvec3 groups, std::uint32_t count) {
    beginCommands();
    PassRecorder rec(cmd, layout.handle(), descriptors.set(), queryPool, kQueryCapacity);
    rec.dispatch(pipeline(ShaderId::RefineSelect, {shape.model, mode}), passConstants(0, count, 0, 0), groups,
                 Stage::Refine);
    submitAndWait();
    rec.collect(vk.device, vk.info.timestampPeriodNs, stageMs);
  };
  run(0, grid, 0);
  if (counterBlock().subgroupSize != subgroup) {
    throw GpuError("adaptive refinement: the device ran subgroups of " + std::to_string(counterBlock().subgroupSize) +
                   " invocations, not the " + std::to_string(subgroup) + " it reports; render without --refine-spp");
  }
  auto* counts = static_cast<std::uint32_t*>(refineBuffer.mapped());
  std::uint64_t total = 0;
  for (std::uint64_t s = 0; s < slots; ++s) {  // exclusive scan in place, the total after the last slot
    const std::uint32_t n = counts[s];
    counts[s] = static_cast<std::uint32_t>(total);
    total += n;
  }
  counts[slots] = static_cast<std::uint32_t>(total);
  if (total > 0) run(1, glm::uvec3(groupsFor(slots), 1u, 1u), static_cast<std::uint32_t>(slots));
  return total;
}

std::vector<gpu_shared::HtRay> Renderer::Impl::generateRays(const RenderSettings& settings, std::uint64_t firstTarget,
                                                            std::uint32_t targetCount, TraceStats* stats) {
  checkSettings(settings);
  const FrameShape shape = frameShape(camera);
  checkShape(shape, settings.spp);
  if (firstTarget + targetCount > shape.targets()) {
    throw GpuError("targets [" + std::to_string(firstTarget) + ", " + std::to_string(firstTarget + targetCount) +
                   ") outside the camera's " + std::to_string(shape.targets()));
  }
  const std::uint64_t totalPaths = static_cast<std::uint64_t>(targetCount) * settings.spp;
  std::vector<gpu_shared::HtRay> rays(totalPaths);
  const std::uint64_t perBatch = std::max<std::uint64_t>(settings.spp, kMaxPathsPerBatch / settings.spp * settings.spp);
  work.ensure(vk, static_cast<std::uint32_t>(std::min(perBatch, std::max<std::uint64_t>(totalPaths, 1))), 1);
  if (outputs.generation == 0) outputs.ensure(vk, 1, 1);  // raygen writes no outputs; the views need a buffer
  bindState();
  fillFrame(shape, 0, shape.views, settings);
  const ComputePipeline& raygen = pipeline(ShaderId::Raygen, raygenSpec(shape));
  std::array<double, static_cast<size_t>(Stage::Count)> stageMs{};
  for (std::uint64_t begin = 0; begin < totalPaths; begin += perBatch) {
    const auto count = static_cast<std::uint32_t>(std::min(perBatch, totalPaths - begin));
    const auto batchFirst = static_cast<std::uint32_t>(firstTarget * settings.spp + begin);
    beginCommands();
    PassRecorder rec(cmd, layout.handle(), descriptors.set(), queryPool, kQueryCapacity);
    rec.dispatch(raygen, passConstants(batchFirst, count, 0, 0), groupsFor(count), Stage::Raygen);
    submitAndWait();
    rec.collect(vk.device, vk.info.timestampPeriodNs, stageMs);
    work.rays[0].download(rays.data() + begin, count * sizeof(gpu_shared::HtRay));
  }
  if (stats) stats->gpuMs = stageMs[static_cast<size_t>(Stage::Raygen)];
  return rays;
}

std::vector<gpu_shared::HtHit> Renderer::Impl::traceBatch(std::span<const gpu_shared::HtRay> rays, bool occlusion,
                                                          TraceStats* stats) {
  std::vector<gpu_shared::HtHit> hits(rays.size());
  const auto chunk =
      static_cast<std::uint32_t>(std::min<std::uint64_t>(kMaxPathsPerBatch * 4ull, std::max<size_t>(rays.size(), 1)));
  work.ensure(vk, chunk, 1);
  if (outputs.generation == 0) outputs.ensure(vk, 1, 1);  // the trace kernels write no outputs; views need a buffer
  const ComputePipeline& trace =
      occlusion ? pipeline(ShaderId::TraceAny, traceSpec({0u})) : pipeline(ShaderId::TraceClosest, traceSpec({}));
  FrameBlock& f = frameBlock();
  std::memset(&f, 0, sizeof(f));
  fillFrameBasics(f);
  bindState();
  f.scene = glm::uvec4(0u, 0u, gpu_shared::HT_TRAVERSAL_STEP_LIMIT, 0u);
  std::array<double, static_cast<size_t>(Stage::Count)> stageMs{};
  std::uint32_t maxSteps = 0;
  for (size_t begin = 0; begin < rays.size(); begin += chunk) {
    const auto count = static_cast<std::uint32_t>(std::min<size_t>(chunk, rays.size() - begin));
    work.rays[0].upload(rays.data() + begin, count * sizeof(gpu_shared::HtRay));
    std::memset(counters.mapped(), 0, sizeof(GpuCounters));
    counterBlock().queueCount[0] = count;
    beginCommands();
    PassRecorder rec(cmd, layout.handle(), descriptors.set(), queryPool, kQueryCapacity);
    rec.dispatch(trace, passConstants(0, count, 0, 0), groupsFor(count), Stage::Trace);
    submitAndWait();
    rec.collect(vk.device, vk.info.timestampPeriodNs, stageMs);
    checkCounters(occlusion ? "traceOccluded" : "traceClosest");
    maxSteps = std::max(maxSteps, counterBlock().maxSteps);
    work.hits.download(hits.data() + begin, count * sizeof(gpu_shared::HtHit));
  }
  if (stats) {
    stats->gpuMs = stageMs[static_cast<size_t>(Stage::Trace)];
    stats->maxSteps = maxSteps;
  }
  return hits;
}

Renderer::Renderer(VulkanContext& context, const Scene& scene, const bvh::BuildOptions& buildOptions)
    : impl_(std::make_unique<Impl>(context.impl(), scene, buildOptions)) {}

Renderer::~Renderer() = default;

const bvh::BuildReport& Renderer::bvhReport() const { return impl_->scene.bvhReport(); }
void Renderer::replaceScene(const Scene& scene) { impl_->replaceScene(scene); }
void Renderer::updateLights(const Scene& scene) { impl_->updateLights(scene); }
const SceneFeatures& Renderer::features() const { return impl_->scene.features(); }

RenderResult Renderer::render(const FrameCamera& camera, const RenderSettings& settings) {
  impl_->camera = camera;
  return impl_->render(settings);
}

RenderResult Renderer::renderLenticular(const gpu_shared::LenticularParams& params, const RenderSettings& settings) {
  return render(params, settings);
}

RenderResult Renderer::renderPinhole(const gpu_shared::PinholeParams& params, const RenderSettings& settings) {
  return render(params, settings);
}

RenderResult Renderer::renderQuilt(const gpu_shared::QuiltParams& params, const RenderSettings& settings) {
  return render(params, settings);
}

std::vector<gpu_shared::HtRay> Renderer::generateRays(const FrameCamera& camera, const RenderSettings& settings,
                                                      std::uint64_t firstTarget, std::uint32_t targetCount,
                                                      TraceStats* stats) {
  impl_->camera = camera;
  return impl_->generateRays(settings, firstTarget, targetCount, stats);
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
