// compute_pipeline.cpp
#include "gpu/compute_pipeline.h"

#include "gpu/frame_descriptors.h"
#include "gpu/wavefront_types.h"

namespace ht::gpu {

PipelineLayout::PipelineLayout(VulkanContext::Impl& vk) : vk_(vk) {
  VkDescriptorSetLayoutBinding bindings[gpu_shared::HT_BINDING_COUNT];
  for (std::uint32_t b = 0; b < gpu_shared::HT_BINDING_COUNT; ++b) {
    bindings[b] = {b, FrameDescriptors::bindingType(b), 1, VK_SHADER_STAGE_COMPUTE_BIT, nullptr};
  }
  VkDescriptorSetLayoutCreateInfo si{VK_STRUCTURE_TYPE_DESCRIPTOR_SET_LAYOUT_CREATE_INFO};
  si.bindingCount = gpu_shared::HT_BINDING_COUNT;
  si.pBindings = bindings;
  HT_VK(vkCreateDescriptorSetLayout(vk.device, &si, nullptr, &setLayout_));
  VkPushConstantRange range{VK_SHADER_STAGE_COMPUTE_BIT, 0, sizeof(gpu_shared::PassConstants)};
  VkPipelineLayoutCreateInfo ci{VK_STRUCTURE_TYPE_PIPELINE_LAYOUT_CREATE_INFO};
  ci.setLayoutCount = 1;
  ci.pSetLayouts = &setLayout_;
  ci.pushConstantRangeCount = 1;
  ci.pPushConstantRanges = &range;
  HT_VK(vkCreatePipelineLayout(vk.device, &ci, nullptr, &layout_));
}

PipelineLayout::~PipelineLayout() {
  vkDestroyPipelineLayout(vk_.device, layout_, nullptr);
  vkDestroyDescriptorSetLayout(vk_.device, setLayout_, nullptr);
}

ComputePipeline::ComputePipeline(VulkanContext::Impl& vk, const PipelineLayout& layout, ShaderId shader,
                                 const std::vector<std::uint32_t>& specialization)
    : vk_(vk) {
  const std::vector<std::uint32_t> code = makeFloatExact(embeddedSpirv(shader), vk.exactFloat);
  VkShaderModuleCreateInfo mci{VK_STRUCTURE_TYPE_SHADER_MODULE_CREATE_INFO};
  mci.codeSize = code.size() * sizeof(std::uint32_t);
  mci.pCode = code.data();
  VkShaderModule module = VK_NULL_HANDLE;
  HT_VK(vkCreateShaderModule(vk.device, &mci, nullptr, &module));

  std::vector<VkSpecializationMapEntry> entries;
  for (std::uint32_t i = 0; i < specialization.size(); ++i) {
    entries.push_back({i, static_cast<std::uint32_t>(i * sizeof(std::uint32_t)), sizeof(std::uint32_t)});
  }
  VkSpecializationInfo spec{static_cast<std::uint32_t>(entries.size()), entries.data(),
                            specialization.size() * sizeof(std::uint32_t), specialization.data()};
  VkComputePipelineCreateInfo ci{VK_STRUCTURE_TYPE_COMPUTE_PIPELINE_CREATE_INFO};
  ci.stage = {VK_STRUCTURE_TYPE_PIPELINE_SHADER_STAGE_CREATE_INFO};
  ci.stage.stage = VK_SHADER_STAGE_COMPUTE_BIT;
  ci.stage.module = module;
  ci.stage.pName = "main";
  ci.stage.pSpecializationInfo = entries.empty() ? nullptr : &spec;
  ci.layout = layout.handle();
  VkResult r = vkCreateComputePipelines(vk.device, VK_NULL_HANDLE, 1, &ci, nullptr, &pipeline_);
  vkDestroyShaderModule(vk.device, module, nullptr);
  if (r != VK_SUCCESS)
    throw GpuError(std::string("cannot create the ") + shaderName(shader) + " pipeline: " + vkResultName(r));
}

ComputePipeline::~ComputePipeline() { vkDestroyPipeline(vk_.device, pipeline_, nullptr); }

}  // namespace ht::gpu
