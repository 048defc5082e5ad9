// frame_transfer_test.cpp - the choice of how frames enter a swapchain image (present/frame_transfer.h) on flag
// combinations: copy when TRANSFER_DST is offered, storage write when only STORAGE is (with a storage-capable format
// and the write-without-format feature), a refusal naming the flags otherwise; forcing the storage write.
#include <gtest/gtest.h>

#include "present/frame_transfer.h"
#include "present/present_error.h"

namespace ht::present {
namespace {

constexpr VkImageUsageFlags kDst = VK_IMAGE_USAGE_TRANSFER_DST_BIT;
constexpr VkImageUsageFlags kStorage = VK_IMAGE_USAGE_STORAGE_BIT;
constexpr VkImageUsageFlags kColor = VK_IMAGE_USAGE_COLOR_ATTACHMENT_BIT;

TransferAbilities abilities(VkImageUsageFlags usage, bool storageFormat = true, bool withoutFormat = true) {
  return TransferAbilities{usage, storageFormat, withoutFormat};
}

std::string refusal(const TransferAbilities& a, FrameTransferChoice choice = FrameTransferChoice::Auto) {
  try {
    chooseFrameTransfer(a, choice);
  } catch (const PresentError& e) { return e.what(); }
  return "";
}

TEST(FrameTransfer, CopyWheneverTransferDstIsOffered) {
  for (VkImageUsageFlags extra : {VkImageUsageFlags(0), kStorage, kColor, kStorage | kColor}) {
    EXPECT_EQ(chooseFrameTransfer(abilities(kDst | extra), FrameTransferChoice::Auto), FrameTransfer::Copy);
    EXPECT_EQ(chooseFrameTransfer(abilities(kDst | extra, false, false), FrameTransferChoice::Auto),
              FrameTransfer::Copy);
  }
}

TEST(FrameTransfer, StorageWriteWithoutTransferDst) {
  EXPECT_EQ(chooseFrameTransfer(abilities(kStorage | kColor), FrameTransferChoice::Auto), FrameTransfer::StorageWrite);
  EXPECT_EQ(chooseFrameTransfer(abilities(kStorage), FrameTransferChoice::Auto), FrameTransfer::StorageWrite);
}

TEST(FrameTransfer, NeitherPathIsRefusedNamingTheFlags) {
  const std::string onlyColor = refusal(abilities(kColor));
  EXPECT_NE(onlyColor.find("allow COLOR_ATTACHMENT;"), std::string::npos) << onlyColor;
  EXPECT_NE(onlyColor.find("needs TRANSFER_DST"), std::string::npos) << onlyColor;
  EXPECT_NE(onlyColor.find("no STORAGE usage"), std::string::npos) << onlyColor;
  EXPECT_NE(refusal(abilities(0)).find("allow none;"), std::string::npos);
  EXPECT_NE(refusal(abilities(kStorage | kColor, false)).find("not usable as a storage image"), std::string::npos);
  EXPECT_NE(refusal(abilities(kStorage | kColor, true, false)).find("shaderStorageImageWriteWithoutFormat"),
            std::string::npos);
  EXPECT_NE(refusal(abilities(kStorage | kColor, true, false)).find("allow STORAGE|COLOR_ATTACHMENT"),
            std::string::npos);
}

TEST(FrameTransfer, ForcingTheStorageWrite) {
  EXPECT_EQ(chooseFrameTransfer(abilities(kDst | kStorage), FrameTransferChoice::ForceStorageWrite),
            FrameTransfer::StorageWrite);
  const std::string cannot = refusal(abilities(kDst | kColor), FrameTransferChoice::ForceStorageWrite);
  EXPECT_NE(cannot.find("forced"), std::string::npos) << cannot;
  EXPECT_NE(cannot.find("TRANSFER_DST|COLOR_ATTACHMENT"), std::string::npos) << cannot;
}

TEST(FrameTransfer, EnvironmentChoice) {
  unsetenv("HOLOTRACE_PANEL_TRANSFER");
  EXPECT_EQ(frameTransferFromEnvironment(), FrameTransferChoice::Auto);
  setenv("HOLOTRACE_PANEL_TRANSFER", "storage", 1);
  EXPECT_EQ(frameTransferFromEnvironment(), FrameTransferChoice::ForceStorageWrite);
  setenv("HOLOTRACE_PANEL_TRANSFER", "blit", 1);
  EXPECT_THROW(frameTransferFromEnvironment(), PresentError);
  unsetenv("HOLOTRACE_PANEL_TRANSFER");
}

}  // namespace
}  // namespace ht::present
