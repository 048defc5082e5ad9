// arguments.h - a small hand-written command-line parser for the holotrace commands and benchmarks.
//
// A command declares its options as a table of OptionSpec; parseArguments() checks argv against it and
// throws ht::UsageError for anything it does not understand, e.g.
//   "holotrace render: unknown option '--spq' (see holotrace render --help)".
// Both "--spp 4" and "--spp=4" are accepted. Values are converted on access, with range checks.
#pragma once
#include <cstdint>
#include <map>
#include <optional>
#include <span>
#include <string>
#include <vector>

namespace ht::cli {

struct OptionSpec {
  std::string name;       // long form, e.g. "--spp"
  std::string alias;      // optional short form, e.g. "-o" ("" = none)
  std::string valueName;  // e.g. "N", "PATH"; empty = a flag that takes no value
  std::string help;       // one line for --help

  bool takesValue() const { return !valueName.empty(); }
};

class ParsedArguments {
 public:
  ParsedArguments(std::string command, std::map<std::string, std::string> values);

  // True if the option (by long name) was given at all.
  bool has(const std::string& name) const;
  // The option's value, if given.
  std::optional<std::string> text(const std::string& name) const;
  // The option's value or the fallback.
  std::string textOr(const std::string& name, const std::string& fallback) const;
  // The value of a required option; throws UsageError "<command>: missing option '<name>'" if it was not given.
  std::string required(const std::string& name) const;
  // An unsigned integer within [lo, hi]; throws UsageError naming option, value and range otherwise.
  std::optional<std::uint32_t> unsignedValue(const std::string& name, std::uint32_t lo, std::uint32_t hi) const;
  // A finite decimal number within [lo, hi]; throws UsageError naming option, value and range otherwise.
  std::optional<double> numberValue(const std::string& name, double lo, double hi) const;

  const std::string& command() const { return command_; }

 private:
  std::string command_;                        // "holotrace render": prefix of every error message
  std::map<std::string, std::string> values_;  // long name -> value ("" for flags)
};

// Parses `args` (without the program and command names). `command` is how errors name the command
// ("holotrace render"). Throws UsageError for unknown options, missing values, repeated options and
// positional arguments. "--help"/"-h" must be handled by the caller before (see wantsHelp()).
ParsedArguments parseArguments(const std::string& command, std::span<const OptionSpec> specs,
                               std::span<const std::string> args);

// True if any argument is --help or -h.
bool wantsHelp(std::span<const std::string> args);

// The option table plus "-h, --help" as aligned help lines ("  --spp N        samples per subpixel ...").
std::string formatOptions(std::span<const OptionSpec> specs);

// Builds the UsageError text with the pointer to the command's --help.
std::string usageMessage(const std::string& command, const std::string& problem);

}  // namespace ht::cli
