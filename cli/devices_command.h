// devices_command.h - `holotrace devices`: the Looking Glass panels this host can see and where each one's
// calibration came from (config file, mounted drive, USB HID; docs/DISPLAY.md "Calibration from the device").
#pragma once
#include <ostream>
#include <span>
#include <string>

namespace ht::cli {

int runDevices(std::span<const std::string> args, std::ostream& out);
std::string devicesHelp();

}  // namespace ht::cli
