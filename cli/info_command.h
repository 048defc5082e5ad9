// info_command.h - `holotrace info`: Vulkan devices (with the one holotrace picks), builtin displays, scenes.
#pragma once
#include <ostream>
#include <span>
#include <string>

namespace ht::cli {

int runInfo(std::span<const std::string> args, std::ostream& out);
std::string infoHelp();

}  // namespace ht::cli
