// frame_transfer.cpp - see frame_transfer.h.
#include "present/frame_transfer.h"

#include <cstdlib>

#include "present/present_error.h"

namespace ht::present {
namespace {

// Why the storage path cannot be used; "" when it can.
std::string storageProblem(const TransferAbilities& a) {
  if (!(a.surfaceUsage & VK_IMAGE_USAGE_STORAGE_BIT)) return "no STORAGE usage";
  if (!a.storageFormat) return "the swapchain format is not usable as a storage image";
  if (!a.writeWithoutFormat) return "the device lacks shaderStorageImageWriteWithoutFormat";
  return "";
}

}  // namespace

std::string imageUsageNames(VkImageUsageFlags usage) {
  std::string text;
  auto add = [&](VkImageUsageFlags bit, const char* name) {
    if (usage & bit) text += (text.empty() ? "" : "|") + std::string(name);
  };
  add(VK_IMAGE_USAGE_TRANSFER_SRC_BIT, "TRANSFER_SRC");
  add(VK_IMAGE_USAGE_TRANSFER_DST_BIT, "TRANSFER_DST");
  add(VK_IMAGE_USAGE_SAMPLED_BIT, "SAMPLED");
  add(VK_IMAGE_USAGE_STORAGE_BIT, "STORAGE");
  add(VK_IMAGE_USAGE_COLOR_ATTACHMENT_BIT, "COLOR_ATTACHMENT");
  add(VK_IMAGE_USAGE_INPUT_ATTACHMENT_BIT, "INPUT_ATTACHMENT");
  return text.empty() ? "none" : text;
}

FrameTransfer chooseFrameTransfer(const TransferAbilities& abilities, FrameTransferChoice choice) {
  const std::string storage = storageProblem(abilities);
  const bool copy = (abilities.surfaceUsage & VK_IMAGE_USAGE_TRANSFER_DST_BIT) != 0;
  if (choice == FrameTransferChoice::ForceStorageWrite) {
    if (storage.empty()) return FrameTransfer::StorageWrite;
    throw PresentError("the storage write was forced (HOLOTRACE_PANEL_TRANSFER=storage) but cannot be used: " +
                       storage + " (the surface's images allow " + imageUsageNames(abilities.surfaceUsage) +
                       "); unset it to let holotrace choose");
  }
  if (copy) return FrameTransfer::Copy;
  if (storage.empty()) return FrameTransfer::StorageWrite;
  throw PresentError("the display surface's images allow " + imageUsageNames(abilities.surfaceUsage) +
                     "; holotrace writes frames into them with a copy (needs TRANSFER_DST) or a compute storage "
                     "write (" +
                     storage + "); a draw-based path is not implemented (docs/DISPLAY.md)");
}

const char* frameTransferName(FrameTransfer transfer) {
  return transfer == FrameTransfer::Copy ? "copy" : "storage write";
}

FrameTransferChoice frameTransferFromEnvironment() {
  const char* value = std::getenv("HOLOTRACE_PANEL_TRANSFER");
  const std::string text = value ? value : "";
  if (text.empty() || text == "auto") return FrameTransferChoice::Auto;
  if (text == "storage") return FrameTransferChoice::ForceStorageWrite;
  throw PresentError("HOLOTRACE_PANEL_TRANSFER='" + text + "': expected \"auto\" or \"storage\"");
}

}  // namespace ht::present
