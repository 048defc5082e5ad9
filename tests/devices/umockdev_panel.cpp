// umockdev_panel.cpp - see umockdev_panel.h.
#include "tests/devices/umockdev_panel.h"

#include <cstdio>
#include <vector>

#include "devices/gen1_protocol.h"

namespace ht::devices::test {
namespace {

using Bytes = std::vector<std::uint8_t>;

std::string hex(const Bytes& bytes) {
  std::string out;
  char digits[3];
  for (std::uint8_t b : bytes) {
    std::snprintf(digits, sizeof digits, "%02X", b);
    out += digits;
  }
  return out;
}

// Device descriptor (USB 2.0, ep0 64 bytes, 04d8:ef7e, bcdDevice 1.00, one configuration), then the configuration:
// one HID interface with interrupt endpoints 0x84 IN and 0x03 OUT, 64-byte packets.
Bytes descriptors() {
  return {
      0x12, 0x01, 0x00, 0x02, 0x00, 0x00, 0x00, 0x40, 0xd8, 0x04, 0x7e, 0xef, 0x00, 0x01,
      0x01, 0x02, 0x03, 0x01, 0x09, 0x02, 0x29, 0x00, 0x01, 0x01, 0x00, 0x80, 0x32,  // configuration, 41 bytes in all
      0x09, 0x04, 0x00, 0x00, 0x02, 0x03, 0x00, 0x00, 0x00,  // interface 0, 2 endpoints, class HID
      0x09, 0x21, 0x11, 0x01, 0x00, 0x01, 0x22, 0x21, 0x00,  // HID 1.11, one report descriptor
      0x07, 0x05, 0x84, 0x03, 0x40, 0x00, 0x01,              // EP 0x84 IN, interrupt, 64
      0x07, 0x05, 0x03, 0x03, 0x40, 0x00, 0x01};             // EP 0x03 OUT, interrupt, 64
}

// One URB line: ret, type (1 interrupt, 2 control), endpoint, status, flags, buffer length, actual length, errors.
std::string urbLine(bool reply, int type, int endpoint, int status, std::size_t length, std::size_t actual,
                    const Bytes& data) {
  return std::string(reply ? " " : "") + "USBDEVFS_REAPURBNDELAY 0 " + std::to_string(type) + " " +
         std::to_string(endpoint) + " " + std::to_string(status) + " 0 " + std::to_string(length) + " " +
         std::to_string(actual) + " 0 " + hex(data) + "\n";
}

// SET_REPORT control transfer: setup packet (0x21, 9, wValue 0x0300, wIndex 0, wLength 67) + the read request.
std::string requestLine(std::uint16_t page) {
  Bytes urb = {0x21, 0x09, 0x00, 0x03, 0x00, 0x00, std::uint8_t(gen1::kRequestBytes), 0x00};
  const gen1::Request request = gen1::readRequest(page);
  urb.insert(urb.end(), request.begin(), request.end());
  return urbLine(false, 2, 0, 0, urb.size(), gen1::kRequestBytes, urb);
}

std::string replyLines(const EmulatedPanel& panel, std::uint16_t page, const Bytes& pageData) {
  constexpr int kIn = gen1::kInputEndpoint;
  if (page == panel.stallPage) return urbLine(true, 1, kIn, -32, gen1::kReplyBytes, 0, {});  // -EPIPE
  const std::uint16_t echoed = panel.echo.count(page) ? panel.echo.at(page) : page;
  Bytes reply = {0x00, gen1::kReadCommand, std::uint8_t(echoed >> 8), std::uint8_t(echoed & 0xff)};
  reply.insert(reply.end(), pageData.begin(), pageData.end());
  if (panel.cut.count(page)) {
    reply.resize(panel.cut.at(page));
    return urbLine(true, 1, kIn, 0, gen1::kReplyBytes, reply.size(), reply);
  }
  if (!panel.splitReplies) return urbLine(true, 1, kIn, 0, reply.size(), reply.size(), reply);
  const Bytes first(reply.begin(), reply.begin() + 64), rest(reply.begin() + 64, reply.end());
  return urbLine(true, 1, kIn, 0, reply.size(), first.size(), first) +
         urbLine(true, 1, kIn, 0, rest.size(), rest.size(), rest);
}

}  // namespace

std::string umockdevDeviceText() {
  return "P: /devices/pci0000:00/0000:00:14.0/usb1/1-1\n"
         "N: bus/usb/001/002\n"
         "E: DEVNAME=/dev/bus/usb/001/002\nE: DEVTYPE=usb_device\nE: DRIVER=usb\nE: PRODUCT=4d8/ef7e/100\n"
         "E: TYPE=0/0/0\nE: BUSNUM=001\nE: DEVNUM=002\nE: MAJOR=189\nE: MINOR=1\nE: SUBSYSTEM=usb\n"
         "A: busnum=1\nA: devnum=2\nA: speed=12\nA: idVendor=04d8\nA: idProduct=ef7e\nA: product=HoloPlay\n"
         "A: manufacturer=Looking Glass Factory\nA: bConfigurationValue=1\nA: bNumConfigurations=1\n"
         "A: bDeviceClass=00\nA: maxchild=0\n"
         "H: descriptors=" +
         hex(descriptors()) +
         "\n\n"
         // The root hub the panel hangs off.
         "P: /devices/pci0000:00/0000:00:14.0/usb1\n"
         "N: bus/usb/001/001\n"
         "E: DEVNAME=/dev/bus/usb/001/001\nE: DEVTYPE=usb_device\nE: DRIVER=usb\nE: PRODUCT=1d6b/2/600\n"
         "E: BUSNUM=001\nE: DEVNUM=001\nE: MAJOR=189\nE: MINOR=0\nE: SUBSYSTEM=usb\n"
         "A: busnum=1\nA: devnum=1\nA: speed=480\nA: idVendor=1d6b\nA: idProduct=0002\nA: bConfigurationValue=1\n"
         "A: bDeviceClass=09\nA: maxchild=1\n"
         "H: descriptors=12010002090001406B1D020000060302010109021900010100E0000904000001090000000705810304000C\n";
}

std::string umockdevIoctlText(const EmulatedPanel& panel) {
  Bytes eeprom = {std::uint8_t(panel.json.size() >> 24), std::uint8_t(panel.json.size() >> 16),
                  std::uint8_t(panel.json.size() >> 8), std::uint8_t(panel.json.size())};
  eeprom.insert(eeprom.end(), panel.json.begin(), panel.json.end());
  std::string text = std::string("@DEV ") + kEmulatedNode + " (usbdevfs)\n";
  const std::size_t pages = (eeprom.size() + gen1::kPageBytes - 1) / gen1::kPageBytes;
  for (std::size_t p = 0; p < pages; ++p) {
    Bytes data(gen1::kPageBytes, 0);
    for (std::size_t i = 0; i < gen1::kPageBytes && p * gen1::kPageBytes + i < eeprom.size(); ++i) {
      data[i] = eeprom[p * gen1::kPageBytes + i];
    }
    const auto page = static_cast<std::uint16_t>(p);
    text += requestLine(page) + replyLines(panel, page, data);
  }
  return text;
}

}  // namespace ht::devices::test
