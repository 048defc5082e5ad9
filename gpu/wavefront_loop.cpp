// wavefront_loop.cpp - the wavefront frame loop (docs/BVH.md §7): batches of paths go through raygen, then per bounce
// trace_closest -> shade -> [trace_any -> gather_direct], then resolve; the frame ends with interleave. Large view
// arrays are rendered in chunks of views. Batches are submitted one by one (bounded memory, progress reports);
// within a batch the GPU drives its own queues through indirect dispatches.
#include <algorithm>
#include <chrono>
#include <cstddef>
#include <cstring>
#include <string>

#include "gpu/renderer_impl.h"

namespace ht::gpu {

namespace {

double msSince(std::chrono::steady_clock::time_point t0) {
  return std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
}

// The region of a frame of `shape` that `settings` asks for, counts resolved; throws GpuError when it lies outside
// the frame, or is a band of rows while adaptive refinement (which compares neighbour rows) is on.
RenderRegion resolveRegion(const RenderSettings& settings, const FrameShape& shape) {
  RenderRegion r = settings.region;
  if (r.viewFirst >= shape.views || r.rowFirst >= shape.height) {
    throw GpuError("render region from view " + std::to_string(r.viewFirst) + ", row " + std::to_string(r.rowFirst) +
                   " lies outside the frame of " + std::to_string(shape.views) + " views of " +
                   std::to_string(shape.height) + " rows");
  }
  if (r.viewCount == 0) r.viewCount = shape.views - r.viewFirst;
  if (r.rowCount == 0) r.rowCount = shape.height - r.rowFirst;
  if (r.viewCount > shape.views - r.viewFirst || r.rowCount > shape.height - r.rowFirst) {
    throw GpuError("render region of " + std::to_string(r.viewCount) + " views x " + std::to_string(r.rowCount) +
                   " rows from view " + std::to_string(r.viewFirst) + ", row " + std::to_string(r.rowFirst) +
                   " exceeds the frame of " + std::to_string(shape.views) + " views of " +
                   std::to_string(shape.height) + " rows");
  }
  if (r.rowCount < shape.height && settings.refineSpp > 0) {
    throw GpuError("adaptive refinement compares neighbour rows, so it renders whole views, not a band of rows " +
                   std::to_string(r.rowFirst) + "-" + std::to_string(r.rowFirst + r.rowCount - 1));
  }
  return r;
}

}  // namespace

std::vector<float> Renderer::Impl::frameBuffer(std::size_t floats) {
  std::vector<float> buffer;
  {
    std::lock_guard lock(spareMutex);
    for (auto it = spareRgba.begin(); it != spareRgba.end(); ++it) {
      if (it->capacity() >= floats && it->capacity() / 2 <= floats) {
        buffer = std::move(*it);
        spareRgba.erase(it);
        break;
      }
    }
  }
  buffer.resize(floats);
  return buffer;
}

RenderResult Renderer::Impl::render(const FrameCamera& camera, const RenderSettings& settings) {
  auto t0 = std::chrono::steady_clock::now();
  checkSettings(settings);
  const FrameShape frame = frameShape(camera);
  checkShape(frame, std::max(settings.spp, settings.refineSpp));
  const RenderRegion region = resolveRegion(settings, frame);
  FrameShape shape = frame;  // of the region
  shape.height = region.rowCount;
  shape.views = region.viewCount;
  const RowBand band{frame.height - region.rowFirst - region.rowCount, frame.height};
  RenderResult result;
  result.width = shape.width;
  result.height = shape.height;
  result.views = shape.views;
  const std::uint64_t viewPixels = static_cast<std::uint64_t>(shape.width) * shape.height;
  result.rgba = frameBuffer(static_cast<size_t>(viewPixels * shape.views * 4));  // every value downloaded below
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
    const bool reusable = count == shape.views && settings.refineSpp == 0;
    renderChunk(camera, shape, band, region.viewFirst + first, count, chunkSettings, reusable, stageMs, result);
    auto tRead = std::chrono::steady_clock::now();
    outputs.image.download(result.rgba.data() + viewPixels * first * 4, viewPixels * count * 16);
    readbackMs += msSince(tRead);
  }
  const bool lights = scene.lightCount() > 0 && (scene.features().lights || settings.forceAllFeatures);
  for (size_t s = 0; s < stageMs.size(); ++s) {
    auto stage = static_cast<Stage>(s);
    if (stage == Stage::Shadow && !lights) continue;
    if (stage == Stage::Refine && settings.refineSpp == 0 && !accumulating) continue;
    if ((stage == Stage::Record || stage == Stage::Mark) && !settings.reuse && !accumulating) continue;
    result.stages.push_back({stageName(stage), stageMs[s]});
  }
  result.stages.push_back({"readback", readbackMs});
  result.totalMs = msSince(t0);
  return result;
}

void Renderer::Impl::renderChunk(const FrameCamera& camera, const FrameShape& shape, const RowBand& band,
                                 std::uint32_t viewFirst, std::uint32_t viewCount, const RenderSettings& settings,
                                 bool reusable, StageTimes& stageMs, RenderResult& result) {
  const std::uint64_t targets =
      static_cast<std::uint64_t>(shape.width) * shape.height * viewCount * shape.targetsPerPixel;
  // Batch size: whole targets, bounded by the path-state memory budget.
  const std::uint32_t maxSpp = std::max(settings.spp, settings.refineSpp);
  std::uint64_t perBatch =
      std::min<std::uint64_t>(kMaxPathsPerBatch, kWorkMemoryBudget / PathBuffers::bytesPerPath(scene.lightCount()));
  if (settings.maxPathsPerBatch > 0) perBatch = std::min<std::uint64_t>(perBatch, settings.maxPathsPerBatch);
  perBatch = std::max<std::uint64_t>(maxSpp, perBatch / maxSpp * maxSpp);
  perBatch = std::min(perBatch, targets * maxSpp);
  work.ensure(vk, static_cast<std::uint32_t>(perBatch), scene.lightCount());
  outputs.ensure(vk, shape.width, shape.height * viewCount);
  ++chunksRendered;
  bindState();
  fillFrame(camera, shape, band, viewFirst, viewCount, settings);
  std::memset(counters.mapped(), 0, sizeof(GpuCounters));
  const ReuseKey key = reuseKey(settings);
  // Frame reuse is for single frames: an accumulation step keeps no reuse state (and drops what was kept).
  const auto plan = [&] {
    framePlan = reuse.plan(key, settings.reuse && !accumulating, reusable && !accumulating, targets * settings.spp,
                           targets, depthPasses(settings) - 1, perBatch);
    applyFramePlan(result);
  };
  plan();
  std::uint64_t dirty = 0;
  if (framePlan.mode == FrameReuse::PartialRetrace) {
    dirty = markMovedTargets(targets, stageMs);
    if (static_cast<double>(dirty) > settings.reuseMaxDirtyShare * static_cast<double>(targets)) {
      // A partial re-render of this many targets costs more than the whole frame: render that. The plan just made
      // left the reuse state invalid until frameDone, so planning again gives a full frame that records afresh.
      plan();
      frameBlock().movedLo = frameBlock().movedHi = glm::vec4(0.0f);  // as fillFrame left them
      frameBlock().moved = frameBlock().movedInstanceIds = glm::uvec4(0u);
    }
  }

  if (accumulating) {
    accumulateChunk(camera, shape, band, viewFirst, viewCount, settings, perBatch, stageMs, result);
  } else {
    renderChunkSamples(camera, shape, targets, dirty, perBatch, settings, stageMs, result);
  }
  beginCommands();
  PassRecorder rec(cmd, layout.handle(), descriptors.set(), queryPool, kQueryCapacity);
  if (framePlan.mode == FrameReuse::PartialRetrace) {
    recordDirtyInterleave(rec, shape);
  } else {
    rec.dispatch(pipeline(ShaderId::Interleave), passConstants(0, 0, 0, 0),
                 groupsFor(static_cast<std::uint64_t>(shape.width) * shape.height * viewCount), Stage::Interleave);
  }
  submitAndWait();
  frameBlock().refine = 0;  // recordDirtyInterleave's list
  frameBlock().refineInfo = glm::uvec4(0u);
  rec.collect(vk.device, vk.info.timestampPeriodNs, stageMs);
  const GpuCounters& c = counterBlock();
  result.raysTraced += c.raysTraced;
  result.maxTraversalSteps = std::max(result.maxTraversalSteps, c.maxSteps);
  result.nonFiniteSamples += c.nanCount;
  reuse.frameDone(key, framePlan);
}

void Renderer::Impl::applyFramePlan(RenderResult& result) {
  FrameBlock& f = frameBlock();
  f.segmentMasks = framePlan.recordSegments ? reuse.segmentMasks.address() : 0;
  if (framePlan.recordSegments) f.grid = reuse.grid();
  f.primaryRays = framePlan.primaryCached ? reuse.primaryRays.address() : 0;
  f.primaryHits = framePlan.primaryCached ? reuse.primaryHits.address() : 0;
  f.shadowOcclusion = framePlan.primaryCached ? reuse.shadowOcclusion.address() : 0;
  // The marking pass views the rest; a partial re-render reads the bounce cache's links (trace_closest REUSE_BOUNCES).
  bindReuseTexels(reuseTexelDummy, framePlan.primaryCached, framePlan.bounceLinks);
  const bool linking = framePlan.recordSecondary || framePlan.bounceLinks;
  f.bounceFirst = linking ? reuse.bounceFirst.address() : 0;
  f.bounceNext = 0;  // set per depth while a frame fills the cache (it may grow)
  f.bounceLinks = glm::uvec4(0u);
  result.reuse = framePlan.mode;
  f.frame.w = framePlan.keptLightRays;  // after reuseKey: not part of the frame's identity
}

void Renderer::Impl::renderChunkSamples(const FrameCamera& camera, const FrameShape& shape, std::uint64_t targets,
                                        std::uint64_t dirty, std::uint64_t perBatch, const RenderSettings& settings,
                                        StageTimes& stageMs, RenderResult& result) {
  const double share = settings.refineSpp > 0 ? 0.8 : 1.0;  // progress: the refinement takes the rest
  auto baseProgress = [&](double done) {
    if (settings.progress) settings.progress(done * share);
  };
  if (framePlan.mode == FrameReuse::PartialRetrace) {
    retraceDirty(camera, shape, dirty, perBatch, settings, stageMs, baseProgress);
    result.tracedTargets += dirty;
  } else {
    tracePaths(camera, shape, settings.spp, targets * settings.spp, perBatch, TracedTargets::All, settings, stageMs,
               baseProgress);
    result.tracedTargets += targets;
  }
  if (settings.refineSpp > 0) {
    const std::uint64_t refined = selectRefinedTargets(shape, targets, settings.refineContrast, stageMs);
    result.refinedTargets += refined;
    if (refined > 0) {
      FrameBlock& f = frameBlock();
      f.dims.z = settings.refineSpp;
      f.refineInfo.w = settings.spp;  // != 0: trace the listed targets, and keep the base samples in their mean
      const std::uint64_t refineBatch =
          std::min(perBatch / settings.refineSpp * settings.refineSpp, refined * settings.refineSpp);
      tracePaths(camera, shape, settings.refineSpp, refined * settings.refineSpp, refineBatch, TracedTargets::Refined,
                 settings, stageMs, [&](double done) {
                   if (settings.progress) settings.progress(share + done * (1.0 - share));
                 });
    }
  }
}

void Renderer::Impl::tracePaths(const FrameCamera& camera, const FrameShape& shape, std::uint32_t spp,
                                std::uint64_t totalPaths, std::uint64_t perBatch, TracedTargets which,
                                const RenderSettings& settings, StageTimes& stageMs,
                                const std::function<void(double)>& progress) {
  const SceneFeatures& feat = scene.features();
  const bool all = settings.forceAllFeatures;
  const bool lights = scene.lightCount() > 0 && (feat.lights || all);
  const bool mirror = feat.mirrors || all, glass = feat.glass || all,
             textures = (feat.textures && scene.textureCount() > 0) || all;
  const std::uint32_t depthPasses = this->depthPasses(settings);
  const bool listed = which != TracedTargets::All;
  // Frame reuse (gpu/frame_reuse.h): the base pass loads the cached primary rays and hits instead of running raygen
  // and the primary trace, or saves them; every pass but refinement records its segment cells.
  const bool loadHits = which == TracedTargets::All && framePlan.mode == FrameReuse::CachedPrimaryHits;
  const bool saveHits = which == TracedTargets::All && framePlan.recordHits;
  const bool loadSecondary = loadHits && framePlan.loadSecondary;
  const bool saveSecondary = which == TracedTargets::All && framePlan.recordSecondary;
  // The frame's queues of depths >= 1 stay in (or go to) the secondary cache: the marking pass tests those entries
  // and their shadow rays exactly (mark_dirty.comp MARK_SECONDARY_ENTRIES), so they record no cells, and words 0-1
  // of the masks stay zero for every path traced here (nonzero words 0-1 mark a target re-traced since).
  const bool secondaryCached = saveSecondary || loadSecondary;
  // (An accumulation records every pass, its listed ones too, into its own masks: accumulation_pass.cpp.)
  const bool record = (which != TracedTargets::Refined || accumulating) && framePlan.recordSegments;

  const bool progressive = accumulating != nullptr;
  const ComputePipeline& traceClosest = pipeline(ShaderId::TraceClosest, traceSpec({}));
  // A partial re-render's primary rays are copied from the cache (raygen.comp FROM_CACHE) and take their cached
  // hits where the move cannot have changed them.
  const bool reusePrimary =
      which == TracedTargets::Dirty && framePlan.mode == FrameReuse::PartialRetrace && framePlan.primaryCached;
  std::vector<std::uint32_t> raygenConstants = raygenSpec(camera, shape, listed, progressive);
  if (reusePrimary) raygenConstants = withConstant(std::move(raygenConstants), 5, 1u);
  const ComputePipeline& raygen = pipeline(ShaderId::Raygen, raygenConstants);
  const ComputePipeline& tracePrimary = reusePrimary ? pipeline(ShaderId::TraceClosest, traceSpec({1u})) : traceClosest;
  // ... and its bounce rays take their cached hits where they are the cached rays (trace_closest REUSE_BOUNCES); the
  // first links of its paths are cleared as they are resolved (resolve CLEAR_BOUNCE_LINKS), whether or not it used
  // them. A frame that fills the bounce cache links its entries (shade LINK_BOUNCES).
  const bool clearLinks =
      which == TracedTargets::Dirty && framePlan.mode == FrameReuse::PartialRetrace && framePlan.bounceLinks;
  const ComputePipeline& traceBounce =
      clearLinks && bounceHitReuse ? pipeline(ShaderId::TraceClosest, traceSpec({0u, 1u})) : traceClosest;
  // The shadow-occlusion cache (ReusePlan::occlusionDepths): shade.comp's OCCLUSION mode at each depth -- record, take
  // the recorded occlusion of the lights a light edit kept, or (depth 0 of a partial re-render) of the segments a
  // move kept -- and trace_any.comp's SHADOW_CACHE, which records what it traces.
  auto occlusionMode = [&](std::uint32_t depth) -> std::uint32_t {
    using namespace gpu_shared;
    if (!lights || accumulating || which == TracedTargets::Refined || depth >= framePlan.occlusionDepths) {
      return HT_OCCLUSION_OFF;
    }
    if (which == TracedTargets::Dirty) {
      return depth == 0 && reusePrimary ? HT_OCCLUSION_KEPT_SEGMENTS : HT_OCCLUSION_OFF;
    }
    return depth < framePlan.occlusionKeptDepths ? HT_OCCLUSION_KEPT_LIGHTS : HT_OCCLUSION_RECORD;
  };
  const std::vector<std::uint32_t> shadeFeatures = {lights, mirror, glass, textures};
  const ComputePipeline& afterShade = pipeline(ShaderId::Prepare, {0u});
  const ComputePipeline& endDepth = pipeline(ShaderId::Prepare, {1u});
  std::vector<std::uint32_t> resolveSpec{shape.model, listed};
  if (progressive) resolveSpec.push_back(1u);  // PROGRESSIVE, only when set (single frames keep their pipeline)
  if (clearLinks) resolveSpec = withConstant(std::move(resolveSpec), 3, 1u);  // CLEAR_BOUNCE_LINKS, likewise
  const ComputePipeline& resolve = pipeline(ShaderId::Resolve, resolveSpec);

  const VkBuffer args = counters.handle();
  bool clear = which != TracedTargets::Refined || accumulating;  // a progressive frame may trace only a list
  for (std::uint64_t begin = 0; begin < totalPaths; begin += perBatch) {
    const auto count = static_cast<std::uint32_t>(std::min<std::uint64_t>(perBatch, totalPaths - begin));
    const auto batchFirst = static_cast<std::uint32_t>(begin);
    beginCommands();
    if (clear) {  // live flags of the shadow slots start cleared; gather_direct clears them after use
      vkCmdFillBuffer(cmd, work.shadowContrib.handle(), 0, VK_WHOLE_SIZE, 0);
      // A full frame records every target's cells afresh; an accumulation's masks are cleared when it restarts.
      if (record && which == TracedTargets::All && !loadHits && !accumulating) {
        vkCmdFillBuffer(cmd, reuse.segmentMasks.handle(), 0, totalPaths / spp * kMaskWords * sizeof(std::uint32_t), 0);
      }
      VkMemoryBarrier b{VK_STRUCTURE_TYPE_MEMORY_BARRIER, nullptr, VK_ACCESS_TRANSFER_WRITE_BIT,
                        VK_ACCESS_SHADER_READ_BIT | VK_ACCESS_SHADER_WRITE_BIT};
      vkCmdPipelineBarrier(cmd, VK_PIPELINE_STAGE_TRANSFER_BIT, VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT, 0, 1, &b, 0,
                           nullptr, 0, nullptr);
      clear = false;
    }
    const VkDeviceSize rayBytes = VkDeviceSize{count} * sizeof(gpu_shared::HtRay);
    const VkDeviceSize hitBytes = VkDeviceSize{count} * sizeof(gpu_shared::HtHit);
    PassRecorder rec(cmd, layout.handle(), descriptors.set(), queryPool, kQueryCapacity);
    if (saveSecondary) setBounceLinks(0, batchFirst);
    if (loadHits) {  // what raygen's first invocation writes: queue 0 holds the batch, the others are empty
      // (shade reads the cached rays and hits in place: HITS_FROM_CACHE)
      const std::uint32_t queues[3] = {count, 0u, 0u};
      vkCmdUpdateBuffer(cmd, counters.handle(), offsetof(GpuCounters, queueCount), sizeof(queues), queues);
      VkMemoryBarrier b{VK_STRUCTURE_TYPE_MEMORY_BARRIER, nullptr, VK_ACCESS_TRANSFER_WRITE_BIT,
                        VK_ACCESS_SHADER_READ_BIT | VK_ACCESS_SHADER_WRITE_BIT};
      vkCmdPipelineBarrier(cmd, VK_PIPELINE_STAGE_TRANSFER_BIT, VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT, 0, 1, &b, 0,
                           nullptr, 0, nullptr);
    } else {
      rec.dispatch(raygen, passConstants(batchFirst, count, 0, 0), groupsFor(count), Stage::Raygen);
    }
    for (std::uint32_t depth = 0; depth < depthPasses; ++depth) {
      const std::uint32_t q = depth % 2;
      PassConstants pc = passConstants(batchFirst, count, depth, q);
      const VkDeviceSize queueArgs = offsetof(GpuCounters, dispatch) + q * sizeof(glm::uvec4);
      const std::uint32_t occlusion = occlusionMode(depth);
      // shade.comp's reuse constants OCCLUSION and HITS_FROM_CACHE only when set: other frames keep their pipelines.
      std::vector<std::uint32_t> shadeConstants = shadeFeatures;
      if (occlusion != gpu_shared::HT_OCCLUSION_OFF) {
        shadeConstants = withConstant(std::move(shadeConstants), 4, occlusion);
      }
      if (depth == 0 && loadHits) shadeConstants = withConstant(std::move(shadeConstants), 5, 1u);
      if (saveSecondary) shadeConstants = withConstant(std::move(shadeConstants), 6, 1u);  // LINK_BOUNCES
      const ComputePipeline& shade = pipeline(ShaderId::Shade, depthSpec(std::move(shadeConstants), depth));
      const std::uint32_t shadowCache = occlusion == gpu_shared::HT_OCCLUSION_OFF ? gpu_shared::HT_SHADOW_CACHE_OFF
                                        : which == TracedTargets::Dirty ? gpu_shared::HT_SHADOW_CACHE_RECORD_LISTED
                                                                        : gpu_shared::HT_SHADOW_CACHE_RECORD;
      const ComputePipeline& traceAny = pipeline(ShaderId::TraceAny, traceSpec({1u, shadowCache}));
      const ComputePipeline& gather = pipeline(ShaderId::GatherDirect, depthSpec({}, depth));
      auto overQueue = [&](const ComputePipeline& pass, Stage stage) {  // one invocation per entry of queue q
        if (depth == 0)
          rec.dispatch(pass, pc, groupsFor(count), stage);
        else
          rec.dispatchIndirect(pass, pc, args, queueArgs, stage);
      };
      const VkDeviceSize shadowArgs = offsetof(GpuCounters, dispatch) + 2 * sizeof(glm::uvec4);
      auto recordSegments = [&] {
        // Segments of depths >= 1 that stay in (or go to) the secondary cache are tested there, not recorded. A
        // frame re-shaded from cached hits adds the shadow rays it traced: one invocation per shadow-queue entry.
        if (!record || (secondaryCached && depth > 0)) return;
        // record_segments.comp: LISTED, SHADOWS_ONLY, and ACCUMULATING only when set (frames keep their pipelines)
        std::vector<std::uint32_t> spec{listed, loadHits};
        if (progressive) spec.push_back(1u);
        const ComputePipeline& pass = pipeline(ShaderId::RecordSegments, depthSpec(std::move(spec), depth));
        if (loadHits) {
          rec.dispatchIndirect(pass, pc, args, shadowArgs, Stage::Record);
        } else {
          overQueue(pass, Stage::Record);
        }
      };
      if (depth == 0 ? !loadHits : !loadSecondary) overQueue(depth == 0 ? tracePrimary : traceBounce, Stage::Trace);
      if (depth == 0 && saveHits) {
        recordComputeCopy(cmd, work.rays[0], 0, reuse.primaryRays, batchFirst * sizeof(gpu_shared::HtRay), rayBytes);
        recordComputeCopy(cmd, work.hits, 0, reuse.primaryHits, batchFirst * sizeof(gpu_shared::HtHit), hitBytes);
      }
      if (depth > 0 && loadSecondary) copySecondary(depth, batchFirst, true);
      if (depth > 0 && saveSecondary) {
        // The queue's size (for its place in the cache, and the marking pass's secondary entries): the commands so
        // far run before the queue is copied to the next free entries of the cache.
        recordComputeCopy(cmd, counters, offsetof(GpuCounters, queueCount) + q * sizeof(std::uint32_t),
                          reuse.secondaryCounts, reuse.secondaryCountOffset(batchFirst, depth), sizeof(std::uint32_t));
        submitAndWait();
        rec.collect(vk.device, vk.info.timestampPeriodNs, stageMs);
        checkCounters("render");
        beginCommands();
        rec.restart();
        copySecondary(depth, batchFirst, false);
        setBounceLinks(depth, batchFirst);
      }
      overQueue(shade, Stage::Shade);
      rec.dispatch(afterShade, pc, 1, Stage::Queues);
      if (lights) {
        rec.dispatchIndirect(traceAny, pc, args, shadowArgs, Stage::Shadow);
        recordSegments();  // before gather_direct clears the shadow slots
        overQueue(gather, Stage::Shadow);
      } else {
        recordSegments();
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

}  // namespace ht::gpu
