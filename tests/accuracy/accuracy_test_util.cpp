#include "accuracy_test_util.h"

namespace ht::accuracy::test {

gpu::VulkanContext& sharedContext() {
  static gpu::VulkanContext context(gpu::VulkanContext::Options{});
  return context;
}

}  // namespace ht::accuracy::test
