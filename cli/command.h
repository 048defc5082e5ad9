// command.h - one `holotrace <command>`: its name, one-line summary, help text and entry point.
#pragma once
#include <ostream>
#include <span>
#include <string>

namespace ht::cli {

struct Command {
  const char* name;
  const char* summary;
  std::string (*help)();
  // Runs the command on its arguments (after the command name). Returns the exit code; throws ht::Error
  // (UsageError for bad arguments) on failure.
  int (*run)(std::span<const std::string> args, std::ostream& out);
};

}  // namespace ht::cli
