// devices_command.cpp - see devices_command.h.
#include "cli/devices_command.h"

#include <array>
#include <nlohmann/json.hpp>

#include "cli/arguments.h"
#include "cli/cli_app.h"
#include "common/error.h"
#include "devices/device_discovery.h"

namespace ht::cli {
namespace {

const char* const kCommand = "holotrace devices";
constexpr std::uint32_t kMaxTimeoutMs = 60'000;

const std::array<OptionSpec, 8> kSpecs = {{
    {"--calibration", "", "FILE", "an explicit visual.json, trusted before drives and USB"},
    {"--no-drives", "", "", "do not look for LKG_calibration/visual.json on mounted drives"},
    {"--no-usb", "", "", "do not read Gen1 panels over USB HID"},
    {"--no-detach", "", "", "never detach the kernel HID driver (a bound driver then fails as 'busy')"},
    {"--usb-timeout-ms", "", "MS", "timeout of each USB transfer (default 500)"},
    {"--mountinfo", "", "FILE", "mount table to scan instead of /proc/self/mountinfo"},
    {"--by-label", "", "DIR", "volume label links to scan instead of /dev/disk/by-label"},
    {"--json", "", "", "one JSON object per panel and line instead of the table"},
}};

devices::DiscoveryOptions discoveryOptions(const ParsedArguments& parsed) {
  devices::DiscoveryOptions o;
  o.calibrationFile = parsed.textOr("--calibration", "");
  o.scanDrives = !parsed.has("--no-drives");
  o.scanUsb = !parsed.has("--no-usb");
  o.usb.detachKernelDriver = !parsed.has("--no-detach");
  if (auto ms = parsed.unsignedValue("--usb-timeout-ms", 1, kMaxTimeoutMs)) {
    o.usb.read.transferTimeout = std::chrono::milliseconds(*ms);
  }
  if (auto file = parsed.text("--mountinfo")) o.drives.mountinfo = *file;
  if (auto dir = parsed.text("--by-label")) o.drives.byLabelDir = *dir;
  return o;
}

std::string orDash(const std::string& text) { return text.empty() ? "-" : text; }

std::string column(const std::string& text, std::size_t width) {
  return text.size() >= width ? text + " " : text + std::string(width - text.size(), ' ');
}

void printTable(const devices::Discovery& found, std::ostream& out) {
  if (found.devices.empty())
    out << "no Looking Glass panels found\n";
  else
    out << column("SERIAL", 14) << column("TYPE", 22) << column("SOURCE", 18) << column("MONITOR", 10) << "LOCATION\n";
  for (const devices::FoundDevice& d : found.devices) {
    out << column(orDash(d.serial), 14) << column(orDash(d.deviceType), 22)
        << column(std::string(devices::calibrationSourceName(d.source)), 18) << column(orDash(d.matchedMonitor), 10)
        << d.location << "\n";
    if (!d.problem().empty()) out << "    problem: " << d.problem() << "\n";
  }
  for (const std::string& note : found.notes) out << "note: " << note << "\n";
}

void printJson(const devices::Discovery& found, std::ostream& out) {
  for (const devices::FoundDevice& d : found.devices) {
    nlohmann::json line = {
        {"serial", d.serial},     {"type", d.deviceType},        {"source", devices::calibrationSourceName(d.source)},
        {"location", d.location}, {"monitor", d.matchedMonitor}, {"loaded", d.loaded()},
        {"problem", d.problem()}};
    if (d.error) line["fault"] = devices::deviceFaultName(d.error->fault());
    if (d.calibration) {
      line["screenW"] = d.calibration->calibration.screenW;
      line["screenH"] = d.calibration->calibration.screenH;
    }
    out << line.dump() << "\n";
  }
}

}  // namespace

std::string devicesHelp() {
  return "Usage: holotrace devices [options]\n\n"
         "Lists the Looking Glass panels this host can see: serial, device type (from the serial), where the\n"
         "calibration came from (config-file, mounted-drive, usb-hid, drive-not-mounted), the matched monitor and\n"
         "the location. Sources in the order they are trusted: --calibration, LKG_calibration/visual.json on a\n"
         "mounted drive, the Gen1 EEPROM over USB HID (docs/DISPLAY.md). Exit status 1 when a panel's calibration\n"
         "could not be loaded (the problem is printed under it).\n\nOptions:\n" +
         formatOptions(kSpecs);
}

int runDevices(std::span<const std::string> args, std::ostream& out) {
  const ParsedArguments parsed = parseArguments(kCommand, kSpecs, args);
  const devices::Discovery found = devices::discoverDevices(discoveryOptions(parsed));
  if (parsed.has("--json"))
    printJson(found, out);
  else
    printTable(found, out);
  std::size_t failed = 0;
  for (const devices::FoundDevice& d : found.devices) failed += d.error ? 1 : 0;
  if (failed > 0) {
    throw Error(std::string(kCommand) + ": " + std::to_string(failed) +
                " panel(s) could not be loaded (the problems are listed above)");
  }
  return kExitOk;
}

}  // namespace ht::cli
