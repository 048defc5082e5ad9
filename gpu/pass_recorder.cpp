// pass_recorder.cpp
#include "gpu/pass_recorder.h"

#include "gpu/vulkan_impl.h"

namespace ht::gpu {

const char* stageName(Stage stage) {
  switch (stage) {
    case Stage::Raygen: return "raygen";
    case Stage::Trace: return "trace";
    case Stage::Shade: return "shade";
    case Stage::Shadow: return "shadow";
    case Stage::Queues: return "queues";
    case Stage::Resolve: return "resolve";
    case Stage::Refine: return "refine";
    case Stage::Interleave: return "interleave";
    case Stage::Record: return "record";  // segment cells of frames that keep reuse state (gpu/frame_reuse.h)
    case Stage::Mark: return "mark";      // the marking pass of a partial re-render
    case Stage::Count: break;
  }
  return "?";
}

PassRecorder::PassRecorder(VkCommandBuffer cmd, VkPipelineLayout layout, VkDescriptorSet bvhSet, VkQueryPool pool,
                           std::uint32_t queryCapacity)
    : cmd_(cmd), layout_(layout), bvhSet_(bvhSet), pool_(pool), capacity_(queryCapacity) {
  restart();
}

void PassRecorder::restart() {
  next_ = 0;
  stages_.clear();
  vkCmdResetQueryPool(cmd_, pool_, 0, capacity_);
  vkCmdBindDescriptorSets(cmd_, VK_PIPELINE_BIND_POINT_COMPUTE, layout_, 0, 1, &bvhSet_, 0, nullptr);
}

void PassRecorder::begin(const ComputePipeline& pipeline, const gpu_shared::PassConstants& pc, Stage stage) {
  if (next_ + 2 > capacity_) throw GpuError("internal: timestamp query pool too small for this frame");
  vkCmdBindPipeline(cmd_, VK_PIPELINE_BIND_POINT_COMPUTE, pipeline.handle());
  vkCmdPushConstants(cmd_, layout_, VK_SHADER_STAGE_COMPUTE_BIT, 0, sizeof(pc), &pc);
  vkCmdWriteTimestamp(cmd_, VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT, pool_, next_++);
  stages_.push_back(stage);
}

void PassRecorder::end() {
  vkCmdWriteTimestamp(cmd_, VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT, pool_, next_++);
  // Every pass reads what the previous ones wrote, including indirect arguments.
  VkMemoryBarrier barrier{VK_STRUCTURE_TYPE_MEMORY_BARRIER};
  barrier.srcAccessMask = VK_ACCESS_SHADER_WRITE_BIT | VK_ACCESS_SHADER_READ_BIT;
  barrier.dstAccessMask = VK_ACCESS_SHADER_READ_BIT | VK_ACCESS_SHADER_WRITE_BIT | VK_ACCESS_INDIRECT_COMMAND_READ_BIT;
  vkCmdPipelineBarrier(cmd_, VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT,
                       VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT | VK_PIPELINE_STAGE_DRAW_INDIRECT_BIT, 0, 1, &barrier, 0,
                       nullptr, 0, nullptr);
}

void PassRecorder::dispatch(const ComputePipeline& pipeline, const gpu_shared::PassConstants& pc, std::uint32_t groups,
                            Stage stage) {
  dispatch(pipeline, pc, glm::uvec3(groups, 1u, 1u), stage);
}

void PassRecorder::dispatch(const ComputePipeline& pipeline, const gpu_shared::PassConstants& pc, glm::uvec3 groups,
                            Stage stage) {
  if (groups.x == 0 || groups.y == 0 || groups.z == 0) return;
  begin(pipeline, pc, stage);
  vkCmdDispatch(cmd_, groups.x, groups.y, groups.z);
  end();
}

void PassRecorder::dispatchIndirect(const ComputePipeline& pipeline, const gpu_shared::PassConstants& pc, VkBuffer args,
                                    VkDeviceSize offset, Stage stage) {
  begin(pipeline, pc, stage);
  vkCmdDispatchIndirect(cmd_, args, offset);
  end();
}

void PassRecorder::collect(VkDevice device, float timestampPeriodNs,
                           std::array<double, static_cast<size_t>(Stage::Count)>& ms) const {
  if (next_ == 0) return;
  std::vector<std::uint64_t> ticks(next_);
  HT_VK(vkGetQueryPoolResults(device, pool_, 0, next_, ticks.size() * sizeof(std::uint64_t), ticks.data(),
                              sizeof(std::uint64_t), VK_QUERY_RESULT_64_BIT | VK_QUERY_RESULT_WAIT_BIT));
  for (size_t pass = 0; pass < stages_.size(); ++pass) {
    std::uint64_t t0 = ticks[2 * pass], t1 = ticks[2 * pass + 1];
    if (t1 > t0) ms[static_cast<size_t>(stages_[pass])] += static_cast<double>(t1 - t0) * timestampPeriodNs * 1e-6;
  }
}

}  // namespace ht::gpu
