// fuzz_hid_pages.cpp - libFuzzer target: the Gen1 USB HID calibration reader and its page reassembly
// (devices/gen1_calibration_reader.h) against arbitrary device behaviour. Only DeviceError may come out; a success
// must hold at most the cap's bytes of validated JSON.
//
// Input byte 0 picks the device:
//  - even: a raw reply stream. The rest is records [k][data...]: k = 0 -> the read times out, k = 255 -> the endpoint
//    stalls, else the read returns min(k, asked) bytes taken from the data (headers, echoes, lengths all arbitrary).
//  - odd: the in-memory panel (tests/devices/fake_holoplay.h) holding the rest as its EEPROM image, with byte 1
//    choosing how replies are split (1-68 bytes) and byte 2 how many stale replies page (byte 2 % 5) gets first.
#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <span>
#include <vector>

#include "devices/device_error.h"
#include "devices/gen1_calibration_reader.h"
#include "tests/devices/fake_holoplay.h"

namespace {

using ht::devices::DeviceError;
using ht::devices::DeviceFault;

class ReplyStream : public ht::devices::HidTransport {
 public:
  explicit ReplyStream(std::span<const std::uint8_t> script) : script_(script) {}
  std::string name() const override { return "fuzzed HoloPlay"; }
  void sendFeatureReport(std::span<const std::uint8_t>, std::chrono::milliseconds) override {}
  std::size_t readInput(std::span<std::uint8_t> buffer, std::chrono::milliseconds) override {
    if (script_.empty()) throw DeviceError(name(), DeviceFault::Timeout, "script exhausted");
    const std::uint8_t k = script_[0];
    script_ = script_.subspan(1);
    if (k == 0) throw DeviceError(name(), DeviceFault::Timeout, "scripted timeout");
    if (k == 255) throw DeviceError(name(), DeviceFault::Stall, "scripted stall");
    const std::size_t n = std::min({std::size_t{k}, buffer.size(), script_.size()});
    std::copy_n(script_.begin(), n, buffer.begin());
    script_ = script_.subspan(n);
    return n;
  }

 private:
  std::span<const std::uint8_t> script_;
};

constexpr std::size_t kCap = 4096;

void read(ht::devices::HidTransport& device) {
  ht::devices::HidReadOptions options;
  options.maxJsonBytes = kCap;
  try {
    const ht::devices::LoadedCalibration loaded = ht::devices::readGen1Calibration(device, options);
    if (loaded.json.size() > kCap || loaded.calibration.screenW == 0) {
      std::fprintf(stderr, "accepted %zu bytes of calibration (cap %zu, screenW %u)\n", loaded.json.size(), kCap,
                   loaded.calibration.screenW);
      std::abort();
    }
  } catch (const DeviceError&) {}
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  if (size < 3) return 0;
  const std::span<const std::uint8_t> input(data, size);
  if (input[0] % 2 == 0) {
    ReplyStream device(input.subspan(1));
    read(device);
  } else {
    ht::devices::test::FakeHoloPlay device(std::vector<std::uint8_t>(input.begin() + 3, input.end()));
    device.chunkBytes = 1 + input[1] % ht::devices::gen1::kReplyBytes;
    device.staleRepliesBefore[static_cast<std::uint16_t>(input[2] % 5)] = input[2] / 5 % 5;
    read(device);
  }
  return 0;
}
