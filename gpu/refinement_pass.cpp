// refinement_pass.cpp - adaptive refinement (gpu/adaptive_refinement.h): lists the targets whose contrast with a
// neighbour calls for more samples, in target order, for the wavefront loop to trace again; and the same selection
// by the stop rule of progressive accumulation (gpu/accumulator.h), over a frame or over its last list.
#include <algorithm>
#include <optional>

#include "gpu/renderer_impl.h"

namespace ht::gpu {

namespace {

// The layout of the selection's buffer (refine_select.comp): `slots` subgroup slots of `stride` staged targets.
struct SelectionLayout {
  glm::uvec3 groups;
  std::uint64_t slots = 0;
  std::uint32_t stride = 0;
  std::uint64_t listFirst() const { return slots + 1 + slots * stride; }
};

}  // namespace

// Lists the selected targets (refine_select.comp) in target order; returns how many. Two passes around a host-side
// exclusive scan of one count per subgroup, so the list, and with it the frame, is the same whatever order the device
// runs the workgroups in.
std::uint64_t Renderer::Impl::selectTargets(const FrameShape& shape, std::uint64_t targets, float contrast,
                                            std::optional<std::uint64_t> listed, bool byError, StageTimes& stageMs) {
  const std::uint32_t subgroup = std::clamp(vk.info.subgroupSize, 1u, HT_WORKGROUP_SIZE);
  const std::uint64_t subgroupsPerGroup = (HT_WORKGROUP_SIZE + subgroup - 1) / subgroup;
  SelectionLayout l;
  if (listed) {  // MODE 2: an invocation per list entry
    if (*listed == 0) return 0;
    l.groups = glm::uvec3(groupsFor(*listed), 1u, 1u);
    l.stride = subgroup;
  } else {  // MODE 0: an invocation per pixel on a grid of rows x views
    l.groups = glm::uvec3(
        groupsFor(shape.width), shape.height,
        static_cast<std::uint32_t>(targets / (std::uint64_t{shape.width} * shape.height * shape.targetsPerPixel)));
    l.stride = subgroup * shape.targetsPerPixel;  // staging per slot: a subgroup of pixels' targets
  }
  l.slots = std::uint64_t{l.groups.x} * l.groups.y * l.groups.z * subgroupsPerGroup;
  const std::uint64_t listFirst = l.listFirst();
  if (listFirst + targets >= (1ull << 32)) throw GpuError("too many targets for adaptive refinement in one chunk");
  const VkDeviceSize bytes = (listFirst + targets) * sizeof(std::uint32_t);
  if (refineBuffer.size() < bytes) refineBuffer = DeviceBuffer(vk, bytes, MemoryPlace::HostReadback);
  FrameBlock& f = frameBlock();
  f.refine = refineBuffer.address();
  f.refineInfo = glm::uvec4(glm::floatBitsToUint(contrast), static_cast<std::uint32_t>(listFirst), l.stride, 0u);

  auto run = [&](std::uint32_t mode, glm::uvec3 groups, std::uint32_t count) {
    beginCommands();
    PassRecorder rec(cmd, layout.handle(), descriptors.set(), queryPool, kQueryCapacity);
    std::vector<std::uint32_t> spec{shape.model, mode};
    if (byError) spec.push_back(1u);  // BY_ERROR (only when set: the contrast pipelines stay as they were)
    rec.dispatch(pipeline(ShaderId::RefineSelect, spec), passConstants(0, count, 0, 0), groups, Stage::Refine);
    submitAndWait();
    rec.collect(vk.device, vk.info.timestampPeriodNs, stageMs);
  };
  run(listed ? 2u : 0u, l.groups, listed ? static_cast<std::uint32_t>(*listed) : 0u);
  if (counterBlock().subgroupSize != subgroup) {
    throw GpuError("adaptive refinement: the device ran subgroups of " + std::to_string(counterBlock().subgroupSize) +
                   " invocations, not the " + std::to_string(subgroup) + " it reports; render without --refine-spp");
  }
  auto* counts = static_cast<std::uint32_t*>(refineBuffer.mapped());
  std::uint64_t total = 0;
  for (std::uint64_t s = 0; s < l.slots; ++s) {  // exclusive scan in place, the total after the last slot
    const std::uint32_t n = counts[s];
    counts[s] = static_cast<std::uint32_t>(total);
    total += n;
  }
  counts[l.slots] = static_cast<std::uint32_t>(total);
  if (total > 0) run(1, glm::uvec3(groupsFor(l.slots), 1u, 1u), static_cast<std::uint32_t>(l.slots));
  return total;
}

std::uint64_t Renderer::Impl::selectRefinedTargets(const FrameShape& shape, std::uint64_t targets, float contrast,
                                                   StageTimes& stageMs) {
  return selectTargets(shape, targets, contrast, std::nullopt, false, stageMs);
}

std::uint64_t Renderer::Impl::selectUnconvergedTargets(const FrameShape& shape, std::uint64_t targets,
                                                       std::optional<std::uint64_t> listed, StageTimes& stageMs) {
  return selectTargets(shape, targets, 0.0f, listed, true, stageMs);
}

}  // namespace ht::gpu
