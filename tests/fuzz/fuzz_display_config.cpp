// fuzz_display_config.cpp - libFuzzer target: holotrace display configs and raw Looking Glass visual.json.
//
// Every input goes through ht::parseDisplayConfig (our format, or a visual.json detected by "pitch"/"slope") and
// ht::parseLookingGlassCalibrationText. The only acceptable failure is an ht::ConfigError; any other exception
// (nlohmann type_error, std::out_of_range, ...), a crash, a sanitizer report or a leak is a finding.
// Relative calibration / ray-table paths resolve against an empty folder, so the fuzzer never reads real files.
#include <cstddef>
#include <cstdint>
#include <filesystem>
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

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string_view text(reinterpret_cast<const char*>(data), size);
  try {
    (void)ht::parseDisplayConfig(text, "fuzz.json", emptyBaseDir());
  } catch (const ht::ConfigError&) {}
  try {
    (void)ht::parseLookingGlassCalibrationText(text, "fuzz-visual.json");
  } catch (const ht::ConfigError&) {}
  return 0;
}
