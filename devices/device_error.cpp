// device_error.cpp - see device_error.h.
#include "devices/device_error.h"

namespace ht::devices {

std::string_view deviceFaultName(DeviceFault fault) {
  switch (fault) {
    case DeviceFault::NoAccess: return "no-access";
    case DeviceFault::Busy: return "busy";
    case DeviceFault::Transport: return "transport";
    case DeviceFault::Timeout: return "timeout";
    case DeviceFault::Stall: return "stall";
    case DeviceFault::Disconnected: return "disconnected";
    case DeviceFault::TruncatedReport: return "truncated-report";
    case DeviceFault::EchoMismatch: return "echo-mismatch";
    case DeviceFault::LengthOverCap: return "length-over-cap";
    case DeviceFault::EmptyCalibration: return "empty-calibration";
    case DeviceFault::InvalidJson: return "invalid-json";
    case DeviceFault::InvalidCalibration: return "invalid-calibration";
    case DeviceFault::FileTooLarge: return "file-too-large";
    case DeviceFault::Unreadable: return "unreadable";
  }
  return "unknown";
}

}  // namespace ht::devices
