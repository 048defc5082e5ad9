// bench_main.h - the one main() shape of the benchmark programs: parse options (nullopt after printing --help),
// run, and map errors to exit codes (2 usage, 1 anything else, named after the program).
#pragma once
#include <exception>
#include <iostream>
#include <optional>
#include <string>
#include <vector>

#include "common/error.h"

namespace ht::bench {

// `parse(args, &help)` returns the options or nullopt (then `help` is printed); `run(options)` returns the exit code.
template <class Parse, class Run>
int benchMain(int argc, char** argv, const char* program, Parse parse, Run run) {
  const std::vector<std::string> args(argv + (argc > 0 ? 1 : 0), argv + argc);
  try {
    std::string help;
    const auto options = parse(args, &help);
    if (!options) {
      std::cout << help;
      return 0;
    }
    return run(*options);
  } catch (const UsageError& e) {
    std::cerr << e.what() << "\n";
    return 2;
  } catch (const std::exception& e) {
    std::cerr << program << ": error: " << e.what() << "\n";
    return 1;
  }
}

}  // namespace ht::bench
