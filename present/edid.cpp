// edid.cpp - EDID base block: header and checksum check, display descriptor text (edid.h has the layout).
#include "present/edid.h"

#include <algorithm>
#include <array>
#include <numeric>

namespace ht::present {
namespace {

constexpr std::size_t kBlockSize = 128;
constexpr std::array<std::uint8_t, 8> kHeader = {0x00, 0xFF, 0xFF, 0xFF, 0xFF, 0xFF, 0xFF, 0x00};
constexpr std::array<std::size_t, 4> kDescriptorOffsets = {54, 72, 90, 108};
constexpr std::size_t kDescriptorTextBytes = 13;
constexpr std::uint8_t kTagMonitorName = 0xFC;
constexpr std::uint8_t kTagSerialText = 0xFF;

// The 13 text bytes of a display descriptor, up to the 0x0A terminator, trailing spaces removed.
std::string descriptorText(std::span<const std::uint8_t> descriptor) {
  std::string text;
  for (std::size_t i = 5; i < 5 + kDescriptorTextBytes; ++i) {
    std::uint8_t c = descriptor[i];
    if (c == 0x0A || c == 0x00) break;
    text += (c >= 0x20 && c < 0x7F) ? static_cast<char>(c) : '?';
  }
  while (!text.empty() && text.back() == ' ') text.pop_back();
  return text;
}

bool isDisplayDescriptor(std::span<const std::uint8_t> d) { return d[0] == 0 && d[1] == 0 && d[2] == 0; }

}  // namespace

EdidInfo parseEdid(std::span<const std::uint8_t> bytes) {
  if (bytes.size() < kBlockSize) {
    throw PresentError("EDID: " + std::to_string(bytes.size()) + " bytes, a base block needs 128");
  }
  if (!std::equal(kHeader.begin(), kHeader.end(), bytes.begin()))
    throw PresentError("EDID: header is not 00 FF FF FF FF FF FF 00");
  unsigned sum = std::accumulate(bytes.begin(), bytes.begin() + kBlockSize, 0u);
  if (sum % 256 != 0)
    throw PresentError("EDID: checksum of the base block is " + std::to_string(sum % 256) + ", not 0");
  EdidInfo info;
  for (std::size_t offset : kDescriptorOffsets) {
    auto d = bytes.subspan(offset, 18);
    if (!isDisplayDescriptor(d)) continue;
    if (d[3] == kTagMonitorName && info.monitorName.empty()) info.monitorName = descriptorText(d);
    if (d[3] == kTagSerialText && info.serialText.empty()) info.serialText = descriptorText(d);
  }
  return info;
}

std::vector<std::uint8_t> makeEdid(const std::string& monitorName) {
  if (monitorName.size() > kDescriptorTextBytes) {
    throw PresentError("EDID monitor name '" + monitorName + "' is longer than 13 characters");
  }
  std::vector<std::uint8_t> edid(kBlockSize, 0);
  std::copy(kHeader.begin(), kHeader.end(), edid.begin());
  edid[18] = 1;  // EDID 1.4
  edid[19] = 4;
  // Descriptor 1 (offset 54) would be the preferred timing; left as a dummy descriptor (tag 0x10).
  for (std::size_t offset : {std::size_t(54), std::size_t(90), std::size_t(108)}) edid[offset + 3] = 0x10;
  std::size_t name = kDescriptorOffsets[1];
  edid[name + 3] = kTagMonitorName;
  std::fill(edid.begin() + name + 5, edid.begin() + name + 18, 0x20);
  std::copy(monitorName.begin(), monitorName.end(), edid.begin() + name + 5);
  if (monitorName.size() < kDescriptorTextBytes) edid[name + 5 + monitorName.size()] = 0x0A;
  unsigned sum = std::accumulate(edid.begin(), edid.end() - 1, 0u);
  edid[kBlockSize - 1] = static_cast<std::uint8_t>((256 - sum % 256) % 256);
  return edid;
}

}  // namespace ht::present
