// embedded_display_configs.h - the shipped configs/*.json, compiled into ht_camera_models by
// embed_display_configs.cmake (generated embedded_display_configs.cpp). Internal to camera_models.
#pragma once
#include <span>
#include <string_view>

namespace ht::detail {

struct EmbeddedDisplayConfig {
  std::string_view name;  // file stem: configs/portrait.json -> "portrait"
  std::string_view json;  // file contents, verbatim
};

// Sorted by name.
std::span<const EmbeddedDisplayConfig> embeddedDisplayConfigs();

}  // namespace ht::detail
