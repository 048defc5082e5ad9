// pipeline_library.h - the compute pipelines of one device, shared by every Renderer on it: one layout, and each
// (shader, specialisation constants) pair compiled once per VulkanContext instead of once per Renderer. lavapipe
// JIT-compiles a pipeline in tens to hundreds of ms, and holotraced makes a Renderer per loaded or edited scene, so
// without sharing every new scene's first frame paid for all its shaders again.
#pragma once
#include <cstdint>
#include <map>
#include <memory>
#include <mutex>
#include <vector>

#include "gpu/compute_pipeline.h"

namespace ht::gpu {

class PipelineLibrary {
 public:
  explicit PipelineLibrary(VulkanContext::Impl& vk) : vk_(vk), layout_(vk) {}
  PipelineLibrary(const PipelineLibrary&) = delete;
  PipelineLibrary& operator=(const PipelineLibrary&) = delete;

  const PipelineLayout& layout() const { return layout_; }
  // The pipeline of `shader` with `specialization`, compiled at its first request (thread-safe). Pipelines are
  // immutable, so command buffers of any Renderer may bind them at once.
  const ComputePipeline& get(ShaderId shader, const std::vector<std::uint32_t>& specialization);

 private:
  VulkanContext::Impl& vk_;
  PipelineLayout layout_;
  std::mutex mutex_;
  std::map<std::vector<std::uint32_t>, std::unique_ptr<ComputePipeline>> pipelines_;
};

}  // namespace ht::gpu
