// gen1_calibration_reader.h - reads a Gen1 Looking Glass calibration from its EEPROM over any HidTransport:
// one read request per 64-byte page, replies reassembled from partial reads, page echo checked (stale replies for
// another page are skipped a bounded number of times), every transfer and the whole read under a timeout, and the
// JSON validated before anything is returned (docs/DISPLAY.md "Calibration from the device").
#pragma once
#include <chrono>
#include <cstddef>
#include <cstdint>

#include "devices/hid_transport.h"
#include "devices/loaded_calibration.h"

namespace ht::devices {

struct HidReadOptions {
  std::chrono::milliseconds transferTimeout{500};  // per USB transfer
  std::chrono::milliseconds totalTimeout{10'000};  // the whole calibration
  std::size_t maxJsonBytes = 64 * 1024;            // real files are ~0.3-1 KiB
  std::uint32_t maxRepliesPerPage = 4;             // replies read for one request before EchoMismatch
};

// The validated calibration. Throws DeviceError naming transport.name() and the fault; nothing is half-loaded.
LoadedCalibration readGen1Calibration(HidTransport& transport, const HidReadOptions& options = {});

}  // namespace ht::devices
