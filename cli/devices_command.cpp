// devices_command.cpp - see devices_command.h.
#include "cli/devices_command.h"

#include <array>
#include <nlohmann/json.hpp>

#include "cli/arguments.h"
#include "cli/cli_app.h"
#include "common/error.h"
#include "devices/device_discovery.h"
#include "present/monitor_lookup.h"

namespace ht::cli {
namespace {

const char* const kCommand = "holotrace devices";
constexpr std::uint32_t kMaxTimeoutMs = 60'000;

const std::array<OptionSpec, 10> kSpecs = {{
    {"--calibration", "", "FILE", "an explicit visual.json, trusted before drives and USB"},
    {"--no-drives", "", "", "do not look for LKG_calibration/visual.json on mounted drives"},
    {"--no-usb", "", "", "do not read Gen1 panels over USB HID"},
    {"--no-detach", "", "", "never detach the kernel HID driver (a bound driver then fails as 'busy')"},
    {"--usb-timeout-ms", "", "MS", "timeout of each USB transfer (default 500)"},
    {"--mountinfo", "", "FILE", "mount table to scan instead of /proc/self/mountinfo"},
    {"--by-label", "", "DIR", "volume label links to scan instead of /dev/disk/by-label"},
    {"--x-display", "", "DISPLAY", "X display whose RandR monitors are matched to the panels (default $DISPLAY)"},
    {"--no-monitors", "", "", "do not look for the panels' monitors (MONITOR stays '-')"},
    {"--json", "", "", "one JSON object per panel and line instead of the table"},
}};

// The MONITOR column: the display sink's picker over one RandR snapshot, asked with the panel's screen size.
devices::MonitorMatch matchMonitor(present::MonitorLookup& lookup, const devices::FoundDevice& device) {
  const LookingGlassCalibration& c = device.calibration->calibration;
  present::PanelRequest request{static_cast<std::uint32_t>(c.screenW), static_cast<std::uint32_t>(c.screenH),
                                std::nullopt, std::nullopt};
  present::MonitorLookupResult found = lookup.find(request);
  if (!found.monitor) return {"", found.problem};
  return {found.monitor->monitor, ""};
}

devices::DiscoveryOptions discoveryOptions(const ParsedArguments& parsed,
                                           const std::shared_ptr<present::MonitorLookup>& lookup) {
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
  if (lookup) o.matchMonitor = [lookup](const devices::FoundDevice& d) { return matchMonitor(*lookup, d); };
  return o;
}

std::string orDash(const std::string& text) { return text.empty() ? "-" : text; }

// The MONITOR column: the monitor, "none" with the reason on a line below, or "-" when not asked.
std::string monitorColumn(const devices::FoundDevice& d) {
  if (!d.matchedMonitor.empty()) return d.matchedMonitor;
  return d.monitorProblem.empty() ? "-" : "none";
}

// A multi-line reason (the picker lists every monitor) indented under the device.
std::string indented(const std::string& text) {
  std::string out;
  for (char c : text) out += c == '\n' ? std::string("\n      ") : std::string(1, c);
  return out;
}

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
        << column(std::string(devices::calibrationSourceName(d.source)), 18) << column(monitorColumn(d), 10)
        << d.location << "\n";
    if (!d.problem().empty()) out << "    problem: " << d.problem() << "\n";
    if (!d.monitorProblem.empty()) out << "    monitor: " << indented(d.monitorProblem) << "\n";
  }
  for (const std::string& note : found.notes) out << "note: " << note << "\n";
}

void printJson(const devices::Discovery& found, std::ostream& out) {
  for (const devices::FoundDevice& d : found.devices) {
    nlohmann::json line = {
        {"serial", d.serial},     {"type", d.deviceType},        {"source", devices::calibrationSourceName(d.source)},
        {"location", d.location}, {"monitor", d.matchedMonitor}, {"monitor_problem", d.monitorProblem},
        {"loaded", d.loaded()},   {"problem", d.problem()}};
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
         "the location. The monitor is the RandR monitor of $DISPLAY (or --x-display) the display sink would choose\n"
         "for the panel's screen size (EDID name starting with LKG, else the only monitor of that size); without an X\n"
         "server, or when no monitor fits, MONITOR says 'none' and the reason is printed under the panel. Sources in\n"
         "the order they are trusted: --calibration, LKG_calibration/visual.json on a mounted drive, the Gen1 EEPROM\n"
         "over USB HID (docs/DISPLAY.md). Exit status 1 when a panel's calibration\n"
         "could not be loaded (the problem is printed under it).\n\nOptions:\n" +
         formatOptions(kSpecs);
}

int runDevices(std::span<const std::string> args, std::ostream& out) {
  const ParsedArguments parsed = parseArguments(kCommand, kSpecs, args);
  std::shared_ptr<present::MonitorLookup> lookup;
  if (!parsed.has("--no-monitors")) lookup = std::make_shared<present::MonitorLookup>(parsed.textOr("--x-display", ""));
  const devices::Discovery found = devices::discoverDevices(discoveryOptions(parsed, lookup));
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
