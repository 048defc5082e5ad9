// fake_holoplay.h - an in-memory Gen1 Looking Glass behind the HidTransport interface: an EEPROM image answered page
// by page as the real device does (devices/gen1_protocol.h), with injectable faults. Used by the unit tests and the
// page reassembly fuzz target; the libusb path is tested against umockdev (devices_umockdev_test.cpp).
#pragma once
#include <cstdint>
#include <deque>
#include <map>
#include <span>
#include <string>
#include <vector>

#include "devices/device_error.h"
#include "devices/gen1_protocol.h"
#include "devices/hid_transport.h"

namespace ht::devices::test {

// An EEPROM image: 4-byte big-endian length, then the JSON.
inline std::vector<std::uint8_t> eepromImage(const std::string& json, std::uint32_t length) {
  std::vector<std::uint8_t> image = {std::uint8_t(length >> 24), std::uint8_t(length >> 16), std::uint8_t(length >> 8),
                                     std::uint8_t(length)};
  image.insert(image.end(), json.begin(), json.end());
  return image;
}
inline std::vector<std::uint8_t> eepromImage(const std::string& json) {
  return eepromImage(json, static_cast<std::uint32_t>(json.size()));
}

class FakeHoloPlay : public HidTransport {
 public:
  explicit FakeHoloPlay(std::vector<std::uint8_t> eeprom) : eeprom_(std::move(eeprom)) {}

  // Faults, keyed by page.
  std::map<std::uint16_t, int> staleRepliesBefore;     // replies echoing another page before the right one
  std::map<std::uint16_t, std::size_t> cutReplyAfter;  // the reply stops after this many bytes, then times out
  std::uint16_t stallAtPage = 0xffff;                  // the interrupt endpoint stalls when this page is asked for
  std::size_t chunkBytes = gen1::kReplyBytes;          // replies arrive in parts of at most this many bytes

  std::vector<std::uint16_t> requestedPages;

  std::string name() const override { return "fake HoloPlay"; }

  void sendFeatureReport(std::span<const std::uint8_t> payload, std::chrono::milliseconds) override {
    if (payload.size() != gen1::kRequestBytes || payload[0] != gen1::kReadCommand) {
      throw DeviceError(name(), DeviceFault::Transport, "unexpected request");
    }
    const auto page = static_cast<std::uint16_t>((payload[1] << 8) | payload[2]);
    requestedPages.push_back(page);
    if (page == stallAtPage) stalled_ = true;
    for (int i = 0; i < staleRepliesBefore[page]; ++i) queueReply(static_cast<std::uint16_t>(page + 1), page + 1);
    std::size_t cut = gen1::kReplyBytes;
    if (auto it = cutReplyAfter.find(page); it != cutReplyAfter.end()) cut = it->second;
    queueReply(page, page, cut);
  }

  std::size_t readInput(std::span<std::uint8_t> buffer, std::chrono::milliseconds) override {
    if (stalled_) throw DeviceError(name(), DeviceFault::Stall, "endpoint 0x84 stalled");
    if (pending_.empty()) throw DeviceError(name(), DeviceFault::Timeout, "no reply");
    std::vector<std::uint8_t>& front = pending_.front();
    const std::size_t n = std::min({buffer.size(), chunkBytes, front.size()});
    std::copy_n(front.begin(), n, buffer.begin());
    front.erase(front.begin(), front.begin() + static_cast<std::ptrdiff_t>(n));
    if (front.empty()) pending_.pop_front();
    return n;
  }

 private:
  void queueReply(std::uint16_t echoedPage, std::uint16_t dataPage, std::size_t bytes = gen1::kReplyBytes) {
    std::vector<std::uint8_t> reply(gen1::kReplyBytes, 0);
    reply[1] = gen1::kReadCommand;
    reply[2] = std::uint8_t(echoedPage >> 8);
    reply[3] = std::uint8_t(echoedPage & 0xff);
    const std::size_t start = std::size_t{dataPage} * gen1::kPageBytes;
    for (std::size_t i = 0; i < gen1::kPageBytes && start + i < eeprom_.size(); ++i) reply[4 + i] = eeprom_[start + i];
    reply.resize(bytes);
    if (!reply.empty()) pending_.push_back(std::move(reply));
  }

  std::vector<std::uint8_t> eeprom_;
  std::deque<std::vector<std::uint8_t>> pending_;
  bool stalled_ = false;
};

}  // namespace ht::devices::test
