// gen1_calibration_reader.cpp - see gen1_calibration_reader.h.
#include "devices/gen1_calibration_reader.h"

#include <algorithm>
#include <span>

#include "devices/device_error.h"
#include "devices/gen1_protocol.h"
#include "devices/page_assembler.h"

namespace ht::devices {
namespace {

using Clock = std::chrono::steady_clock;

class PageReader {
 public:
  PageReader(HidTransport& transport, const HidReadOptions& options)
      : transport_(transport), options_(options), deadline_(Clock::now() + options.totalTimeout) {}

  // The 64 data bytes of `page`, from the first reply that echoes it.
  gen1::Reply readPage(std::uint16_t page) {
    const gen1::Request request = gen1::readRequest(page);
    transport_.sendFeatureReport(request, transferTimeout(page));
    gen1::Reply reply{};
    for (std::uint32_t attempt = 0; attempt < options_.maxRepliesPerPage; ++attempt) {
      reply = readReply(page);
      if (gen1::replyEchoes(reply, page)) return reply;
    }
    throw DeviceError(transport_.name(), DeviceFault::EchoMismatch,
                      "asked for page " + std::to_string(page) + ", the device answered " +
                          std::to_string(options_.maxRepliesPerPage) + " times for another (last: command " +
                          std::to_string(reply[1]) + ", page " + std::to_string(gen1::replyPage(reply)) + ")");
  }

 private:
  // One 68-byte input report, possibly arriving in parts.
  gen1::Reply readReply(std::uint16_t page) {
    gen1::Reply reply{};
    std::size_t got = 0;
    while (got < reply.size()) {
      const std::span<std::uint8_t> rest = std::span(reply).subspan(got);
      std::size_t n = 0;
      std::string cause = "nothing more arrived";
      try {
        n = transport_.readInput(rest, transferTimeout(page));
      } catch (const DeviceError& e) {
        if (got == 0 || e.fault() == DeviceFault::Disconnected) throw;
        cause = std::string(deviceFaultName(e.fault())) + ": " + e.detail();
      }
      if (n == 0 && got > 0) {
        throw DeviceError(transport_.name(), DeviceFault::TruncatedReport,
                          "page " + std::to_string(page) + ": the reply stopped after " + std::to_string(got) + " of " +
                              std::to_string(reply.size()) + " bytes (" + cause + ")");
      }
      if (n == 0) {
        throw DeviceError(transport_.name(), DeviceFault::Timeout, "page " + std::to_string(page) + ": an empty reply");
      }
      if (n > rest.size()) {
        throw DeviceError(transport_.name(), DeviceFault::Transport,
                          "the transport returned " + std::to_string(n) + " bytes for a " +
                              std::to_string(rest.size()) + "-byte read");
      }
      got += n;
    }
    return reply;
  }

  std::chrono::milliseconds transferTimeout(std::uint16_t page) const {
    const auto left = std::chrono::duration_cast<std::chrono::milliseconds>(deadline_ - Clock::now());
    if (left.count() <= 0) {
      throw DeviceError(transport_.name(), DeviceFault::Timeout,
                        "page " + std::to_string(page) + ": the calibration read took longer than " +
                            std::to_string(options_.totalTimeout.count()) + " ms");
    }
    return std::min(left, options_.transferTimeout);
  }

  HidTransport& transport_;
  const HidReadOptions& options_;
  Clock::time_point deadline_;
};

}  // namespace

LoadedCalibration readGen1Calibration(HidTransport& transport, const HidReadOptions& options) {
  PageReader reader(transport, options);
  PageAssembler pages(transport.name(), options.maxJsonBytes);
  while (!pages.complete()) {
    const gen1::Reply reply = reader.readPage(pages.nextPage());
    pages.addPage(std::span(reply).subspan<gen1::kReplyHeaderBytes, gen1::kPageBytes>());
  }
  return checkCalibrationText(pages.takeJson(), transport.name());
}

}  // namespace ht::devices
