// arguments.cpp - see arguments.h.
#include "cli/arguments.h"

#include <algorithm>
#include <charconv>
#include <utility>
#include <vector>

#include "common/error.h"

namespace ht::cli {
namespace {

const OptionSpec* findSpec(std::span<const OptionSpec> specs, const std::string& flag) {
  auto matches = [&](const OptionSpec& s) { return s.name == flag || (!s.alias.empty() && s.alias == flag); };
  auto it = std::find_if(specs.begin(), specs.end(), matches);
  return it == specs.end() ? nullptr : &*it;
}

bool looksLikeOption(const std::string& arg) { return arg.size() > 1 && arg[0] == '-'; }

std::string valueHint(const OptionSpec& spec) {
  return spec.name + (spec.alias.empty() ? "" : " (" + spec.alias + ")") + " <" + spec.valueName + ">";
}

// Shortest decimal text of a bound ("0.25", "16").
std::string formatNumber(double v) {
  char buffer[32];
  auto [end, ec] = std::to_chars(buffer, buffer + sizeof(buffer), v);
  return ec == std::errc() ? std::string(buffer, end) : std::to_string(v);
}

}  // namespace

std::string usageMessage(const std::string& command, const std::string& problem) {
  return command + ": " + problem + " (see " + command + " --help)";
}

ParsedArguments::ParsedArguments(std::string command, std::map<std::string, std::string> values)
    : command_(std::move(command)), values_(std::move(values)) {}

bool ParsedArguments::has(const std::string& name) const { return values_.count(name) != 0; }

std::optional<std::string> ParsedArguments::text(const std::string& name) const {
  auto it = values_.find(name);
  if (it == values_.end()) return std::nullopt;
  return it->second;
}

std::string ParsedArguments::required(const std::string& name) const {
  auto value = text(name);
  if (!value) throw UsageError(usageMessage(command_, "missing option '" + name + "'"));
  return *value;
}

std::string ParsedArguments::textOr(const std::string& name, const std::string& fallback) const {
  return text(name).value_or(fallback);
}

std::optional<std::uint32_t> ParsedArguments::unsignedValue(const std::string& name, std::uint32_t lo,
                                                            std::uint32_t hi) const {
  auto value = text(name);
  if (!value) return std::nullopt;
  std::uint64_t parsed = 0;
  const char* first = value->data();
  const char* last = first + value->size();
  auto [end, ec] = std::from_chars(first, last, parsed);
  if (value->empty() || ec != std::errc() || end != last || parsed < lo || parsed > hi) {
    throw UsageError(usageMessage(command_, "option '" + name + "' = '" + *value + "': expected an integer in [" +
                                                std::to_string(lo) + ", " + std::to_string(hi) + "]"));
  }
  return static_cast<std::uint32_t>(parsed);
}

std::optional<double> ParsedArguments::numberValue(const std::string& name, double lo, double hi) const {
  auto value = text(name);
  if (!value) return std::nullopt;
  double parsed = 0.0;
  const char* first = value->data();
  const char* last = first + value->size();
  auto [end, ec] = std::from_chars(first, last, parsed);
  if (value->empty() || ec != std::errc() || end != last || !(parsed >= lo && parsed <= hi)) {
    throw UsageError(usageMessage(command_, "option '" + name + "' = '" + *value + "': expected a number in [" +
                                                formatNumber(lo) + ", " + formatNumber(hi) + "]"));
  }
  return parsed;
}

ParsedArguments parseArguments(const std::string& command, std::span<const OptionSpec> specs,
                               std::span<const std::string> args) {
  std::map<std::string, std::string> values;
  for (std::size_t i = 0; i < args.size(); ++i) {
    const std::string& arg = args[i];
    if (!looksLikeOption(arg)) { throw UsageError(usageMessage(command, "unexpected argument '" + arg + "'")); }
    const std::size_t eq = arg.rfind("--", 0) == 0 ? arg.find('=') : std::string::npos;
    const std::string flag = arg.substr(0, eq);
    const OptionSpec* spec = findSpec(specs, flag);
    if (spec == nullptr) throw UsageError(usageMessage(command, "unknown option '" + flag + "'"));
    if (values.count(spec->name)) throw UsageError(usageMessage(command, "option '" + spec->name + "' given twice"));
    std::string value;
    if (!spec->takesValue()) {
      if (eq != std::string::npos) {
        throw UsageError(usageMessage(command, "option '" + spec->name + "' takes no value"));
      }
    } else if (eq != std::string::npos) {
      value = arg.substr(eq + 1);
    } else if (i + 1 < args.size() && !looksLikeOption(args[i + 1])) {
      value = args[++i];
    } else {
      throw UsageError(usageMessage(command, "option '" + spec->name + "' needs a value: " + valueHint(*spec)));
    }
    if (spec->takesValue() && value.empty()) {
      throw UsageError(usageMessage(command, "option '" + spec->name + "' has an empty value: " + valueHint(*spec)));
    }
    values.emplace(spec->name, std::move(value));
  }
  return ParsedArguments(command, std::move(values));
}

bool wantsHelp(std::span<const std::string> args) {
  return std::any_of(args.begin(), args.end(), [](const std::string& a) { return a == "--help" || a == "-h"; });
}

std::string formatOptions(std::span<const OptionSpec> specs) {
  std::vector<OptionSpec> all(specs.begin(), specs.end());
  all.push_back({"--help", "-h", "", "show this text"});
  auto left = [](const OptionSpec& s) {
    std::string text = s.alias.empty() ? s.name : s.alias + ", " + s.name;
    return s.takesValue() ? text + " " + s.valueName : text;
  };
  std::size_t width = 0;
  for (const auto& s : all) width = std::max(width, left(s).size());
  std::string out;
  for (const auto& s : all) {
    const std::string l = left(s);
    out += "  " + l + std::string(width - l.size() + 2, ' ') + s.help + "\n";
  }
  return out;
}

}  // namespace ht::cli
