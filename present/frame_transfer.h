// frame_transfer.h - how a frame gets into a swapchain image, chosen from what the surface allows (its
// supportedUsageFlags; the specification guarantees only COLOR_ATTACHMENT):
//   - Copy: vkCmdCopyBufferToImage from the staging buffer (needs TRANSFER_DST) - the default;
//   - StorageWrite: a compute shader stores each pixel (needs STORAGE, a UNORM format usable as a storage image and
//     the device feature shaderStorageImageWriteWithoutFormat) - used when TRANSFER_DST is missing, or when forced;
//   - else the surface is refused with a PresentError naming the flags found.
// A pure function, unit-tested on flag combinations (docs/DISPLAY.md "Presenting to the panel" §4).
#pragma once
#include <vulkan/vulkan.h>

#include <string>

namespace ht::present {

enum class FrameTransfer { Copy, StorageWrite };
enum class FrameTransferChoice { Auto, ForceStorageWrite };  // sink option / HOLOTRACE_PANEL_TRANSFER=storage

struct TransferAbilities {
  VkImageUsageFlags surfaceUsage = 0;  // VkSurfaceCapabilitiesKHR::supportedUsageFlags
  bool storageFormat = false;          // the swapchain format has STORAGE_IMAGE in optimalTilingFeatures
  bool writeWithoutFormat = false;     // shaderStorageImageWriteWithoutFormat enabled on the device
};

// Throws PresentError naming the usage flags found (and what the storage path lacks) when neither path works.
FrameTransfer chooseFrameTransfer(const TransferAbilities& abilities, FrameTransferChoice choice);

// "TRANSFER_DST|STORAGE|COLOR_ATTACHMENT", "none".
std::string imageUsageNames(VkImageUsageFlags usage);

// "copy" / "storage write" (Status, logs).
const char* frameTransferName(FrameTransfer transfer);

// FrameTransferChoice from the environment variable HOLOTRACE_PANEL_TRANSFER ("storage" forces the storage write;
// unset, "" or "auto" = Auto). Throws PresentError naming the value otherwise.
FrameTransferChoice frameTransferFromEnvironment();

}  // namespace ht::present
