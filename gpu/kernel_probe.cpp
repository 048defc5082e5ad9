// kernel_probe.cpp - see kernel_probe.h. One compute pipeline with a push-constant-only layout (buffer device
// addresses, no descriptor sets), built per call: the probe is a test tool, not a hot path.
#include "gpu/kernel_probe.h"

#include <cstdint>

#include "gpu/device_buffer.h"
#include "gpu/vulkan_impl.h"
#include "spirv/offset_ray_probe.spv.h"

namespace ht::gpu {
namespace {

constexpr std::uint32_t kProbeGroupSize = 64;  // local_size_x of offset_ray_probe.comp

struct ProbeConstants {  // push_constant block of offset_ray_probe.comp (scalar layout)
  VkDeviceAddress inputAddress;
  VkDeviceAddress outputAddress;
  std::uint32_t count;
};

// A compute pipeline and its layout (push constants only), destroyed together.
class ProbePipeline {
 public:
  ProbePipeline(VulkanContext::Impl& vk, const std::uint32_t* code, std::size_t codeBytes) : vk_(vk) {
    VkPushConstantRange range{VK_SHADER_STAGE_COMPUTE_BIT, 0, sizeof(ProbeConstants)};
    VkPipelineLayoutCreateInfo li{VK_STRUCTURE_TYPE_PIPELINE_LAYOUT_CREATE_INFO};
    li.pushConstantRangeCount = 1;
    li.pPushConstantRanges = &range;
    HT_VK(vkCreatePipelineLayout(vk.device, &li, nullptr, &layout_));
    VkShaderModuleCreateInfo mi{VK_STRUCTURE_TYPE_SHADER_MODULE_CREATE_INFO};
    mi.codeSize = codeBytes;
    mi.pCode = code;
    VkShaderModule module = VK_NULL_HANDLE;
    HT_VK(vkCreateShaderModule(vk.device, &mi, nullptr, &module));
    VkComputePipelineCreateInfo ci{VK_STRUCTURE_TYPE_COMPUTE_PIPELINE_CREATE_INFO};
    ci.stage = {VK_STRUCTURE_TYPE_PIPELINE_SHADER_STAGE_CREATE_INFO};
    ci.stage.stage = VK_SHADER_STAGE_COMPUTE_BIT;
    ci.stage.module = module;
    ci.stage.pName = "main";
    ci.layout = layout_;
    const VkResult r = vkCreateComputePipelines(vk.device, VK_NULL_HANDLE, 1, &ci, nullptr, &pipeline_);
    vkDestroyShaderModule(vk.device, module, nullptr);
    HT_VK(r);
  }
  ~ProbePipeline() {
    vkDestroyPipeline(vk_.device, pipeline_, nullptr);
    vkDestroyPipelineLayout(vk_.device, layout_, nullptr);
  }
  ProbePipeline(const ProbePipeline&) = delete;
  ProbePipeline& operator=(const ProbePipeline&) = delete;
  VkPipeline pipeline() const { return pipeline_; }
  VkPipelineLayout layout() const { return layout_; }

 private:
  VulkanContext::Impl& vk_;
  VkPipelineLayout layout_ = VK_NULL_HANDLE;
  VkPipeline pipeline_ = VK_NULL_HANDLE;
};

}  // namespace

std::vector<glm::vec3> runOffsetRayProbe(VulkanContext& context, std::span<const OffsetRayProbeInput> inputs) {
  if (inputs.empty()) return {};
  VulkanContext::Impl& vk = context.impl();
  std::vector<glm::vec4> packed;
  packed.reserve(2 * inputs.size());
  for (const OffsetRayProbeInput& in : inputs) {
    packed.emplace_back(in.p, 0.0f);
    packed.emplace_back(in.n, 0.0f);
  }
  const VkDeviceSize inputBytes = packed.size() * sizeof(glm::vec4);
  const VkDeviceSize outputBytes = inputs.size() * sizeof(glm::vec4);
  DeviceBuffer input(vk, inputBytes, MemoryPlace::Device);
  DeviceBuffer output(vk, outputBytes, MemoryPlace::HostReadback);
  input.upload(packed.data(), inputBytes);

  ProbePipeline probe(vk, ht_spv_offset_ray_probe, sizeof(ht_spv_offset_ray_probe));
  const ProbeConstants constants{input.address(), output.address(), static_cast<std::uint32_t>(inputs.size())};
  OneShotCommands commands(vk);
  vkCmdBindPipeline(commands.cmd(), VK_PIPELINE_BIND_POINT_COMPUTE, probe.pipeline());
  vkCmdPushConstants(commands.cmd(), probe.layout(), VK_SHADER_STAGE_COMPUTE_BIT, 0, sizeof(constants), &constants);
  vkCmdDispatch(commands.cmd(), static_cast<std::uint32_t>((inputs.size() + kProbeGroupSize - 1) / kProbeGroupSize), 1,
                1);
  VkMemoryBarrier toHost{VK_STRUCTURE_TYPE_MEMORY_BARRIER, nullptr, VK_ACCESS_SHADER_WRITE_BIT,
                         VK_ACCESS_HOST_READ_BIT};
  vkCmdPipelineBarrier(commands.cmd(), VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT, VK_PIPELINE_STAGE_HOST_BIT, 0, 1, &toHost,
                       0, nullptr, 0, nullptr);
  commands.submitAndWait();

  std::vector<glm::vec4> results(inputs.size());
  output.download(results.data(), outputBytes);
  std::vector<glm::vec3> offsets;
  offsets.reserve(results.size());
  for (const glm::vec4& r : results) offsets.emplace_back(r);
  return offsets;
}

}  // namespace ht::gpu
