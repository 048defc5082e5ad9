// cli_app.cpp - top-level dispatch of `holotrace`: help, version, commands, error -> exit code mapping.
#include "cli/cli_app.h"

#include <algorithm>
#include <array>
#include <exception>
#include <new>

#include "cli/arguments.h"
#include "cli/capture_command.h"
#ifdef HT_WITH_CLIENT
#include "cli/client_command.h"
#endif
#include "cli/command.h"
#include "cli/devices_command.h"
#include "cli/info_command.h"
#include "cli/interleave_command.h"
#include "cli/raycast_command.h"
#include "cli/rays_command.h"
#include "cli/render_command.h"
#include "cli/show_command.h"
#include "cli/simulate_command.h"
#include "cli/wall_command.h"
#include "common/error.h"

#ifndef HT_VERSION
#error "HT_VERSION must be defined by cli/CMakeLists.txt"
#endif

namespace ht::cli {
namespace {

constexpr std::array kCommands = {
    Command{"render", "render a display frame (native interleaved panel image) to PNG/EXR", renderHelp, runRender},
    Command{"show", "render a display frame and keep it on the panel's monitor until Ctrl-C (X11 + Vulkan)", showHelp,
            runShow},
    Command{"wall", "live wall under mpirun: each rank shows its projectors, all flip together (swap barrier)",
            wallHelp, runWall},
    Command{"capture", "render a sequence of frames to NAME_fNNNN files (spread over MPI ranks under mpirun)",
            captureHelp, runCapture},
    Command{"info", "list Vulkan devices, the one holotrace picks, builtin displays and scenes", infoHelp, runInfo},
    Command{"raycast", "trace a ray batch file against a scene, write the hits (binary or CSV)", raycastHelp,
            runRaycast},
    Command{"devices", "list the Looking Glass panels found and where their calibration came from", devicesHelp,
            runDevices},
    Command{"interleave", "interleave a quilt image (_qs{c}x{r}a{aspect}) into a lenticular panel image",
            interleaveHelp, runInterleave},
    Command{"simulate", "what an eye sees of a rendered frame through the display's optics (one eye or a sweep)",
            simulateHelp, runSimulate},
    Command{"rays", "write a display's per-(sub)pixel primary rays (+ view phase) as an EXR ray table", raysHelp,
            runRays},
#ifdef HT_WITH_CLIENT
    Command{"client", "talk to a running holotraced: displays|load|render|stream|capture", clientHelp, runClient},
#endif
};

const Command* findCommand(const std::string& name) {
  auto it = std::find_if(kCommands.begin(), kCommands.end(), [&](const Command& c) { return name == c.name; });
  return it == kCommands.end() ? nullptr : &*it;
}

std::string padRight(const std::string& text, std::size_t width) {
  return text.size() >= width ? text + " " : text + std::string(width - text.size(), ' ');
}

std::string mainHelp() {
  std::string text = "holotrace " HT_VERSION
                     " - light-field display renderer (Vulkan compute ray tracing)\n\n"
                     "Usage: holotrace <command> [options]\n\nCommands:\n";
  for (const Command& c : kCommands) text += "  " + padRight(c.name, 12) + c.summary + "\n";
  text +=
      "  help        show this text, or `holotrace help <command>`\n\n"
      "Options:\n  -h, --help     show this text\n  --version      print the version\n\n"
      "Run `holotrace <command> --help` for the options of a command.\n";
  return text;
}

int runHelp(std::span<const std::string> args, std::ostream& out) {
  if (args.empty()) {
    out << mainHelp();
    return kExitOk;
  }
  const Command* command = findCommand(args[0]);
  if (command == nullptr || args.size() > 1) {
    throw UsageError(usageMessage("holotrace", "help: unknown command '" + args[0] + "'"));
  }
  out << command->help();
  return kExitOk;
}

int dispatch(std::span<const std::string> args, std::ostream& out) {
  if (args.empty()) throw UsageError(usageMessage("holotrace", "missing command, e.g. `holotrace render`"));
  const std::string& first = args[0];
  if (first == "--help" || first == "-h" || first == "help") return runHelp(args.subspan(1), out);
  if (first == "--version") {
    out << versionText() << "\n";
    return kExitOk;
  }
  const Command* command = findCommand(first);
  if (command == nullptr) {
    const std::string what = first.starts_with("-") ? "unknown option '" : "unknown command '";
    throw UsageError(usageMessage("holotrace", what + first + "'"));
  }
  const auto rest = args.subspan(1);
  if (wantsHelp(rest)) {
    out << command->help();
    return kExitOk;
  }
  return command->run(rest, out);
}

}  // namespace

std::string versionText() { return "holotrace " HT_VERSION; }

int runCli(std::span<const std::string> args, std::ostream& out, std::ostream& err) {
  try {
    return dispatch(args, out);
  } catch (const UsageError& e) {
    err << e.what() << "\n";
    return kExitUsage;
  } catch (const Error& e) {
    err << "holotrace: error: " << e.what() << "\n";
    return kExitError;
  } catch (const std::bad_alloc&) {
    err << "holotrace: error: out of memory (try a smaller display, scene or --spp)\n";
    return kExitError;
  } catch (const std::exception& e) {
    err << "holotrace: internal error: " << e.what() << " (please report this with the command line)\n";
    return kExitError;
  } catch (...) {
    err << "holotrace: internal error: unknown exception (please report this with the command line)\n";
    return kExitError;
  }
}

}  // namespace ht::cli
