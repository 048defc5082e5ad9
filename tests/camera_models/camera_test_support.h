// camera_test_support.h - fixtures and independent helpers shared by the camera_models tests.
#pragma once
#include <cmath>
#include <cstdint>
#include <string>

#include <glm/glm.hpp>
#include <gtest/gtest.h>

#include "camera_models/display_config.h"
#include "scene/scene.h"

namespace ht::test {

inline std::string fixturePath(const std::string& name) { return std::string(HT_TEST_DATA_DIR) + "/configs/" + name; }

inline DisplayConfig loadFixture(const std::string& name) { return loadDisplayConfig(fixturePath(name)); }

// A scene box off the origin, so placement errors (target, world transform) show up.
inline Bounds3 testBounds() {
  Bounds3 b;
  b.extend(glm::vec3(-0.8f, 1.0f, -3.0f));
  b.extend(glm::vec3(1.4f, 2.6f, -1.5f));
  return b;
}

// Synthetic 8K (7680x4320) lenticular panel in the style of the 32" Gen3 units: Gen3 lens parameters (docs/OPTICS.md
// §1.1, LKG-J pitch and slope) scaled to an 8K panel; pitch_s is about 1190 lenses, so phi reaches ~1200. cellMode 0 =
// classic; 2 = the LKG-J template cells.
inline DisplayConfig eightKDisplay(int cellMode, bool flipX = false, bool flipSubp = false, bool invView = true) {
  const std::string cells =
      cellMode == 0 ? "[]" : R"([{"ROffsetX":-0.31,"ROffsetY":0.25,"GOffsetX":0.28,"GOffsetY":0.25,"BOffsetX":0,
                           "BOffsetY":-0.25},
                          {"ROffsetX":-0.31,"ROffsetY":-0.25,"GOffsetX":0.28,"GOffsetY":-0.25,"BOffsetX":0,
                           "BOffsetY":0.25}])";
  std::string json = std::string(R"({"name": "8k", "calibration": {"pitch": 44.72, "slope": -6.9, "center": 0.37,
      "viewCone": 50, "invView": )") +
                     (invView ? "1" : "0") + R"(, "DPI": 280, "screenW": 7680, "screenH": 4320,
      "flipImageX": )" +
                     (flipX ? "1" : "0") + R"(, "flipImageY": 0, "flipSubp": )" + (flipSubp ? "1" : "0") +
                     R"(, "CellPatternMode": )" + std::to_string(cellMode) + R"(, "subpixelCells": )" + cells + "}}";
  return parseDisplayConfig(json, "synthetic-8k", "");
}

// Signed distance between two phases on the unit circle, in (-0.5, 0.5].
inline double phaseDifference(double a, double b) {
  double d = a - b;
  return d - std::round(d);
}

// Angle between two (near-)unit directions, robust for tiny angles.
inline double angleBetween(const glm::dvec3& a, const glm::dvec3& b) {
  return std::atan2(glm::length(glm::cross(a, b)), glm::dot(a, b));
}

}  // namespace ht::test
