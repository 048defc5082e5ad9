// fuzz_display_config.cpp - libFuzzer target: holotrace display configs and raw Looking Glass visual.json.
//
// Every input goes through ht::parseDisplayConfig (our format, or a visual.json detected by "pitch"/"slope") and
// ht::parseLookingGlassCalibrationText. The only acceptable failure is an ht::ConfigError; any other exception
// (nlohmann type_error, std::out_of_range, ...), a crash, a sanitizer report or a leak is a finding.
// Relative calibration / ray-table paths resolve against an empty folder, so the fuzzer never reads real files.
//
// Nesting and long inputs (issue 14 item 2): a display config nested 100,000 levels deep crashed every reader, but
// such a file is 200 KB, beyond fuzz.sh's -max_len, and the byte mutator would need ages to grow one. So each input
// also runs amplified: wrapped in N levels of '[' and of '{"k":' (N from the input's first two bytes, up to 2^18)
// and, when short, repeated to about 1 MiB. The amplified forms meet the same rule: ConfigError or success.
#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <string>
#include <string_view>

#include "camera_models/display_config.h"
#include "camera_models/looking_glass_calibration.h"
#include "common/error.h"

namespace {

const std::filesystem::path& emptyBaseDir() {
  static const std::filesystem::path dir = [] {
    auto d = std::filesystem::temp_directory_path() / "holotrace-fuzz-display-config-base";
    std::filesystem::create_directories(d);
    return d;
  }();
  return dir;
}

void parseBoth(std::string_view text) {
  try {
    (void)ht::parseDisplayConfig(text, "fuzz.json", emptyBaseDir());
  } catch (const ht::ConfigError&) {}
  try {
    (void)ht::parseLookingGlassCalibrationText(text, "fuzz-visual.json");
  } catch (const ht::ConfigError&) {}
}

// The input inside `levels` arrays [ ... ] or objects {"k": ... }.
std::string nested(std::string_view text, std::size_t levels, bool objects) {
  std::string out;
  out.reserve(text.size() + levels * (objects ? 6 : 2));
  for (std::size_t i = 0; i < levels; ++i) out += objects ? "{\"k\":" : "[";
  out += text;
  for (std::size_t i = 0; i < levels; ++i) out += objects ? '}' : ']';
  return out;
}

std::string repeated(std::string_view text, std::size_t targetBytes) {
  std::string out;
  out.reserve(targetBytes + text.size());
  while (out.size() < targetBytes) out += text;
  return out;
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string_view text(reinterpret_cast<const char*>(data), size);
  parseBoth(text);
  if (size >= 2) {
    const std::size_t levels = std::size_t{data[0]} << 10 | std::size_t{data[1]} << 2;  // 0 .. 262140
    parseBoth(nested(text.substr(2), levels, false));
    parseBoth(nested(text.substr(2), levels, true));
  }
  if (size > 0 && size < 4096) parseBoth(repeated(text, std::size_t{1} << 20));
  return 0;
}
