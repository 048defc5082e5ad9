// main.cpp - entry point of the `holotrace` command; everything else lives in the ht_cli library.
#include <iostream>
#include <string>
#include <vector>

#include "cli/cli_app.h"

int main(int argc, char** argv) {
  const std::vector<std::string> args(argv + (argc > 0 ? 1 : 0), argv + argc);
  const int code = ht::cli::runCli(args, std::cout, std::cerr);
  std::cout.flush();
  return code;
}
