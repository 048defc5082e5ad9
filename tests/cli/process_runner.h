// process_runner.h - run a program with arguments and capture its exit code, stdout and stderr.
#pragma once
#include <string>
#include <vector>

namespace ht::cli::test {

struct ProcessResult {
  int exitCode = -1;  // the exit status, or 128 + signal number if it was killed by a signal
  std::string out, err;
};

// Runs `program` with `args` (no shell involved), waits for it and returns what it printed.
ProcessResult runProcess(const std::string& program, const std::vector<std::string>& args);

}  // namespace ht::cli::test
