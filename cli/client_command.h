// client_command.h - `holotrace client displays|load|render|stream|capture`: talks to a running holotraced over
// its gRPC protocol (protocol/holotrace/v1/holotrace.proto, docs/SERVICE.md).
#pragma once
#include <ostream>
#include <span>
#include <string>

namespace ht::cli {

int runClient(std::span<const std::string> args, std::ostream& out);
std::string clientHelp();

}  // namespace ht::cli
