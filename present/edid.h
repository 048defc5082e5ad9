// edid.h - the parts of an EDID 1.x base block (VESA E-EDID, 128 bytes) the display sink uses: the monitor name
// (display descriptor tag 0xFC) and the serial text (tag 0xFF). Looking Glass panels name themselves "LKG..." in the
// monitor name descriptor (docs/DISPLAY.md "Presenting to the panel").
//
// Layout: bytes 0-7 the header 00 FF FF FF FF FF FF 00; four 18-byte descriptors at 54, 72, 90, 108; a display
// descriptor starts 00 00 00 <tag> 00 and holds 13 text bytes ended by 0x0A and padded with 0x20; byte 127 makes the
// sum of the 128 bytes 0 mod 256.
#pragma once
#include <cstdint>
#include <span>
#include <string>
#include <vector>

#include "present/present_error.h"

namespace ht::present {

struct EdidInfo {
  std::string monitorName;  // tag 0xFC, "" if the block has none
  std::string serialText;   // tag 0xFF, "" if none
};

// Throws PresentError naming the fault (short block, bad header, bad checksum).
EdidInfo parseEdid(std::span<const std::uint8_t> bytes);

// A valid 128-byte base block carrying `monitorName` (at most 13 characters) in a 0xFC descriptor: the synthetic EDID
// tests and the Xvfb recipe attach to an output.
std::vector<std::uint8_t> makeEdid(const std::string& monitorName);

}  // namespace ht::present
