// kernel_probe.cpp - see kernel_probe.h. One compute pipeline with a push-constant-only layout (buffer device
// addresses, no descriptor sets), built per call: the probe is a test tool, not a hot path.
#include "gpu/kernel_probe.h"

#include <algorithm>
#include <cstdint>

#include "gpu/device_buffer.h"
#include "gpu/vulkan_impl.h"
#include "spirv/exact_math_probe.spv.h"
#include "spirv/offset_ray_probe.spv.h"
#include "spirv/two_level_probe.spv.h"

namespace ht::gpu {
namespace {

constexpr std::uint32_t kProbeGroupSize = 64;  // local_size_x of the probe kernels

struct ProbeConstants {  // push_constant block of offset_ray_probe.comp (scalar layout)
  VkDeviceAddress inputAddress;
  VkDeviceAddress outputAddress;
  std::uint32_t count;
};

struct TwoLevelProbeConstants {  // push_constant block of two_level_probe.comp (scalar layout)
  VkDeviceAddress topNodes, instances, blasNodes, triangles, rays, outputs;
  std::uint32_t count, stepLimit;
};

// A compute pipeline and its layout (push constants only, `pushBytes` of them), destroyed together.
class ProbePipeline {
 public:
  ProbePipeline(VulkanContext::Impl& vk, const std::uint32_t* code, std::size_t codeBytes, std::uint32_t pushBytes)
      : vk_(vk) {
    VkPushConstantRange range{VK_SHADER_STAGE_COMPUTE_BIT, 0, pushBytes};
    VkPipelineLayoutCreateInfo li{VK_STRUCTURE_TYPE_PIPELINE_LAYOUT_CREATE_INFO};
    li.pushConstantRangeCount = 1;
    li.pPushConstantRanges = &range;
    HT_VK(vkCreatePipelineLayout(vk.device, &li, nullptr, &layout_));
    const std::vector<std::uint32_t> exact =
        makeFloatExact(std::span<const std::uint32_t>(code, codeBytes / sizeof(std::uint32_t)), vk.exactFloat);
    VkShaderModuleCreateInfo mi{VK_STRUCTURE_TYPE_SHADER_MODULE_CREATE_INFO};
    mi.codeSize = exact.size() * sizeof(std::uint32_t);
    mi.pCode = exact.data();
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

// Records the probe's dispatch over `count` invocations with its push constants, waits, and makes the shader
// writes visible to the host.
template <class Constants>
void dispatchProbe(VulkanContext::Impl& vk, const std::uint32_t* code, std::size_t codeBytes,
                   const Constants& constants, std::size_t count) {
  ProbePipeline probe(vk, code, codeBytes, sizeof(Constants));
  OneShotCommands commands(vk);
  vkCmdBindPipeline(commands.cmd(), VK_PIPELINE_BIND_POINT_COMPUTE, probe.pipeline());
  vkCmdPushConstants(commands.cmd(), probe.layout(), VK_SHADER_STAGE_COMPUTE_BIT, 0, sizeof(constants), &constants);
  vkCmdDispatch(commands.cmd(), static_cast<std::uint32_t>((count + kProbeGroupSize - 1) / kProbeGroupSize), 1, 1);
  VkMemoryBarrier toHost{VK_STRUCTURE_TYPE_MEMORY_BARRIER, nullptr, VK_ACCESS_SHADER_WRITE_BIT,
                         VK_ACCESS_HOST_READ_BIT};
  vkCmdPipelineBarrier(commands.cmd(), VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT, VK_PIPELINE_STAGE_HOST_BIT, 0, 1, &toHost,
                       0, nullptr, 0, nullptr);
  commands.submitAndWait();
}

// A device buffer holding `values` (at least 16 bytes, so an empty list still has an address).
template <class T>
DeviceBuffer uploadBuffer(VulkanContext::Impl& vk, const std::vector<T>& values) {
  const VkDeviceSize bytes = std::max<VkDeviceSize>(16, values.size() * sizeof(T));
  DeviceBuffer buffer(vk, bytes, MemoryPlace::Device);
  if (!values.empty()) buffer.upload(values.data(), values.size() * sizeof(T));
  return buffer;
}

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

  const ProbeConstants constants{input.address(), output.address(), static_cast<std::uint32_t>(inputs.size())};
  dispatchProbe(vk, ht_spv_offset_ray_probe, sizeof(ht_spv_offset_ray_probe), constants, inputs.size());

  std::vector<glm::vec4> results(inputs.size());
  output.download(results.data(), outputBytes);
  std::vector<glm::vec3> offsets;
  offsets.reserve(results.size());
  for (const glm::vec4& r : results) offsets.emplace_back(r);
  return offsets;
}

std::vector<glm::vec4> runExactMathProbe(VulkanContext& context, std::span<const glm::vec4> inputs) {
  if (inputs.empty()) return {};
  VulkanContext::Impl& vk = context.impl();
  const DeviceBuffer input = uploadBuffer(vk, std::vector<glm::vec4>(inputs.begin(), inputs.end()));
  const VkDeviceSize outputBytes = inputs.size() * sizeof(glm::vec4);
  DeviceBuffer output(vk, outputBytes, MemoryPlace::HostReadback);
  const ProbeConstants constants{input.address(), output.address(), static_cast<std::uint32_t>(inputs.size())};
  dispatchProbe(vk, ht_spv_exact_math_probe, sizeof(ht_spv_exact_math_probe), constants, inputs.size());
  std::vector<glm::vec4> results(inputs.size());
  output.download(results.data(), outputBytes);
  return results;
}

std::vector<gpu_shared::HtTraceResult> runTwoLevelProbe(VulkanContext& context, const bvh::TwoLevelBvh& bvh,
                                                        std::span<const gpu_shared::HtRay> rays,
                                                        std::uint32_t stepLimit) {
  if (rays.empty()) return {};
  VulkanContext::Impl& vk = context.impl();
  const DeviceBuffer topNodes = uploadBuffer(vk, bvh.topNodes());
  const DeviceBuffer instances = uploadBuffer(vk, bvh.instanceTable());
  const DeviceBuffer blasNodes = uploadBuffer(vk, bvh.blasNodes());
  const DeviceBuffer triangles = uploadBuffer(vk, bvh.blasTriangles());
  const DeviceBuffer rayBuffer = uploadBuffer(vk, std::vector<gpu_shared::HtRay>(rays.begin(), rays.end()));
  const VkDeviceSize outputBytes = 2 * rays.size() * sizeof(glm::uvec4);
  DeviceBuffer output(vk, outputBytes, MemoryPlace::HostReadback);
  const TwoLevelProbeConstants constants{topNodes.address(),
                                         instances.address(),
                                         blasNodes.address(),
                                         triangles.address(),
                                         rayBuffer.address(),
                                         output.address(),
                                         static_cast<std::uint32_t>(rays.size()),
                                         stepLimit};
  dispatchProbe(vk, ht_spv_two_level_probe, sizeof(ht_spv_two_level_probe), constants, rays.size());

  std::vector<glm::uvec4> words(2 * rays.size());
  output.download(words.data(), outputBytes);
  std::vector<gpu_shared::HtTraceResult> results(rays.size());
  for (std::size_t i = 0; i < rays.size(); ++i) {
    const glm::uvec4 hit = words[2 * i], info = words[2 * i + 1];
    results[i].hit =
        gpu_shared::HtHit{glm::uintBitsToFloat(hit.x), hit.y, glm::uintBitsToFloat(hit.z), glm::uintBitsToFloat(hit.w)};
    results[i].steps = info.x;
    results[i].overflow = info.y != 0;
  }
  return results;
}

}  // namespace ht::gpu
