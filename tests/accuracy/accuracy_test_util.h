// accuracy_test_util.h - what the accuracy tests share: one Vulkan context, ray counts scaled for sanitizer
// builds.
#pragma once
#include <cstdint>

#include "gpu/vulkan_context.h"

namespace ht::accuracy::test {

// One Vulkan context for the whole test program (device creation costs ~100 ms on lavapipe).
gpu::VulkanContext& sharedContext();

#ifdef HT_SANITIZED_BUILD
constexpr bool kSanitized = true;
#else
constexpr bool kSanitized = false;
#endif
// Release count, or a twentieth of it (at least 1000) under ASan+UBSan.
constexpr uint32_t scaledCount(uint32_t release) {
  return kSanitized ? (release / 20 > 1000 ? release / 20 : 1000) : release;
}

}  // namespace ht::accuracy::test
