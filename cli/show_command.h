// show_command.h - `holotrace show`: render a display's frame once and keep it on the panel (the display sink,
// docs/DISPLAY.md) until Ctrl-C / SIGTERM, re-attaching if the panel or the X server goes away meanwhile.
#pragma once
#include <ostream>
#include <span>
#include <string>

namespace ht::cli {

int runShow(std::span<const std::string> args, std::ostream& out);
std::string showHelp();

}  // namespace ht::cli
