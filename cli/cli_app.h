// cli_app.h - the `holotrace` program as a function, so tests can run it in-process.
//
// Exit codes: 0 success; 1 a runtime error (ht::Error: bad config/scene file, GPU, I/O); 2 a usage error
// (unknown command or option, missing/invalid value). Every exception ends in a message on `err`.
#pragma once
#include <ostream>
#include <span>
#include <string>

namespace ht::cli {

inline constexpr int kExitOk = 0;
inline constexpr int kExitError = 1;
inline constexpr int kExitUsage = 2;

// `args` are the arguments after the program name.
int runCli(std::span<const std::string> args, std::ostream& out, std::ostream& err);

// "holotrace 0.1.0".
std::string versionText();

}  // namespace ht::cli
