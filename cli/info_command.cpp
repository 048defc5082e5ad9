// info_command.cpp - see info_command.h.
#include "cli/info_command.h"

#include <array>
#include <exception>
#include <iomanip>
#include <optional>
#include <sstream>

#include "camera_models/display_config.h"
#include "cli/arguments.h"
#include "cli/cli_app.h"
#include "common/error.h"
#include "gpu/vulkan_context.h"
#include "scene/scene.h"

namespace ht::cli {
namespace {

const char* const kCommand = "holotrace info";
constexpr std::uint32_t kMaxDevice = 255;

const std::array<OptionSpec, 2> kSpecs = {{
    {"--device", "", "N", "mark device N as the one to use instead of the automatic choice"},
    {"--validation", "", "", "create the device with the Vulkan validation layer enabled"},
}};

std::string mib(std::uint64_t bytes) {
  std::ostringstream s;
  s << bytes << " B (" << std::fixed << std::setprecision(0) << double(bytes) / (1024.0 * 1024.0) << " MiB)";
  return s.str();
}

const char* yesNo(bool value) { return value ? "yes" : "no"; }

void printDeviceInfo(std::ostream& out, const gpu::DeviceInfo& d, bool chosen) {
  out << (chosen ? "* " : "  ") << "[" << d.index << "] " << d.name << (chosen ? "   <- chosen" : "") << "\n"
      << "      type                      " << d.type << "\n"
      << "      Vulkan API                " << d.apiVersion << "\n"
      << "      driver                    " << d.driver << "\n"
      << "      maxStorageBufferRange     " << mib(d.maxStorageBufferRange) << "\n"
      << "      maxMemoryAllocationSize   " << mib(d.maxMemoryAllocationSize) << "\n"
      << "      maxComputeWorkGroupInv.   " << d.maxComputeWorkGroupInvocations << "\n"
      << "      subgroup size             " << d.subgroupSize << "\n"
      << "      timestamp period          " << d.timestampPeriodNs << " ns\n"
      << "      shaderFloat64             " << yesNo(d.shaderFloat64) << "\n"
      << "      bufferDeviceAddress       " << yesNo(d.bufferDeviceAddress) << "\n"
      << "      denormals kept (fp32)     " << yesNo(d.denormPreserveFloat32) << "\n"
      << "      usable                    " << (d.usable ? "yes" : "no: " + d.unusableReason) << "\n";
}

void printNames(std::ostream& out, const char* title, const std::vector<std::string>& names) {
  out << title << ":";
  for (const auto& name : names) out << (name.rfind("builtin:", 0) == 0 ? " " : " builtin:") << name;
  out << "\n";
}

struct DeviceChoice {
  std::optional<std::uint32_t> index;  // unset if no device could be chosen
  std::uint32_t validationMessages = 0;
  std::exception_ptr failure;  // the GpuError that prevented the choice
};

// Creates a context exactly as `render` does, so the mark shows the device `render` would use.
DeviceChoice chooseDevice(const gpu::VulkanContext::Options& options) {
  DeviceChoice choice;
  try {
    const gpu::VulkanContext context(options);
    choice.index = context.device().index;
    choice.validationMessages = context.validationMessageCount();
  } catch (const GpuError&) { choice.failure = std::current_exception(); }
  return choice;
}

}  // namespace

std::string infoHelp() {
  return "Usage: holotrace info [options]\n\n"
         "Lists every Vulkan device with the limits holotrace depends on, marks the one `holotrace render`\n"
         "would use (*), and lists the builtin displays and scenes.\n\nOptions:\n" +
         formatOptions(kSpecs);
}

int runInfo(std::span<const std::string> args, std::ostream& out) {
  const ParsedArguments parsed = parseArguments(kCommand, kSpecs, args);
  gpu::VulkanContext::Options options;
  if (auto device = parsed.unsignedValue("--device", 0, kMaxDevice)) options.deviceIndex = int(*device);
  options.validation = parsed.has("--validation");

  const std::vector<gpu::DeviceInfo> devices = gpu::VulkanContext::listDevices();
  printNames(out, "builtin displays", builtinDisplayNames());
  printNames(out, "builtin scenes", builtinSceneNames());
  out << "Vulkan devices (" << devices.size() << "):\n";
  const DeviceChoice choice = chooseDevice(options);
  for (const auto& device : devices) printDeviceInfo(out, device, choice.index == device.index);
  if (choice.failure) std::rethrow_exception(choice.failure);  // e.g. no usable device: exit 1 with the reason
  if (options.validation) out << "validation messages: " << choice.validationMessages << "\n";
  return kExitOk;
}

}  // namespace ht::cli
