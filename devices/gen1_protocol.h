// gen1_protocol.h - the Gen1 Looking Glass ("HoloPlay", USB 04d8:ef7e) EEPROM read protocol: constants and the
// byte layout of requests and replies (docs/DISPLAY.md "Calibration from the device", with its sources).
//
// Per 64-byte page: a feature report (id 0) [command 0 = read, page (u16 big endian), 64 zero bytes]; the device
// answers with a 68-byte input report [buttons, command, page (u16 big endian), 64 data bytes]. Page 0's data starts
// with the JSON length (u32 big endian); the JSON follows, spanning ceil((4 + length) / 64) pages.
#pragma once
#include <array>
#include <cstddef>
#include <cstdint>

namespace ht::devices::gen1 {

constexpr std::uint16_t kVendorId = 0x04d8;  // Microchip: shared with other products, so the product is checked too
constexpr std::uint16_t kProductId = 0xef7e;
constexpr const char* kProductName = "HoloPlay";
constexpr std::uint8_t kInterface = 0;
constexpr std::uint8_t kInputEndpoint = 0x84;

constexpr std::uint8_t kReadCommand = 0x00;
constexpr std::size_t kPageBytes = 64;
constexpr std::size_t kRequestBytes = 3 + kPageBytes;  // feature report payload without the report id
constexpr std::size_t kReplyHeaderBytes = 4;           // buttons, command, page hi, page lo
constexpr std::size_t kReplyBytes = kReplyHeaderBytes + kPageBytes;
constexpr std::size_t kLengthPrefixBytes = 4;
constexpr std::uint32_t kNoCalibration = 0xffffffffu;  // an erased EEPROM

using Request = std::array<std::uint8_t, kRequestBytes>;
using Reply = std::array<std::uint8_t, kReplyBytes>;

inline Request readRequest(std::uint16_t page) {
  Request r{};
  r[0] = kReadCommand;
  r[1] = static_cast<std::uint8_t>(page >> 8);
  r[2] = static_cast<std::uint8_t>(page & 0xff);
  return r;
}

inline std::uint16_t replyPage(const Reply& reply) { return static_cast<std::uint16_t>((reply[2] << 8) | reply[3]); }

inline bool replyEchoes(const Reply& reply, std::uint16_t page) {
  return reply[1] == kReadCommand && replyPage(reply) == page;
}

}  // namespace ht::devices::gen1
