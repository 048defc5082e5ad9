// pipeline_library.cpp - see pipeline_library.h.
#include "gpu/pipeline_library.h"

namespace ht::gpu {

const ComputePipeline& PipelineLibrary::get(ShaderId shader, const std::vector<std::uint32_t>& specialization) {
  std::vector<std::uint32_t> key = specialization;
  key.insert(key.begin(), static_cast<std::uint32_t>(shader));
  std::lock_guard lock(mutex_);  // held while compiling: a second Renderer asking for the same pipeline waits for it
  std::unique_ptr<ComputePipeline>& slot = pipelines_[key];
  if (!slot) slot = std::make_unique<ComputePipeline>(vk_, layout_, shader, specialization);
  return *slot;
}

}  // namespace ht::gpu
