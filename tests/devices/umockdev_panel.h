// umockdev_panel.h - writes the two files umockdev needs to emulate a Gen1 Looking Glass on USB: the sysfs device
// (.umockdev: attributes plus the descriptor blob libusb parses) and the URBs it answers (.ioctl), generated from
// the calibration JSON the emulated EEPROM holds. Formats: docs/DISPLAY.md "Testing without a panel".
#pragma once
#include <cstdint>
#include <filesystem>
#include <map>
#include <string>

namespace ht::devices::test {

struct EmulatedPanel {
  std::string json;                             // the EEPROM's calibration
  bool splitReplies = false;                    // every reply as 64 + 4 bytes (two interrupt transfers)
  std::map<std::uint16_t, std::uint16_t> echo;  // page -> page number the reply claims (a corrupted echo)
  std::map<std::uint16_t, std::size_t> cut;     // page -> bytes of its reply before nothing more matches
  int stallPage = -1;                           // the interrupt endpoint stalls (-EPIPE) on this page's reply
};

// The USB device node both files describe.
inline constexpr const char* kEmulatedNode = "/dev/bus/usb/001/002";

std::string umockdevDeviceText();
std::string umockdevIoctlText(const EmulatedPanel& panel);

}  // namespace ht::devices::test
