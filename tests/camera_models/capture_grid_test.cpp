// Two-plane capture grid (docs/OPTICS.md §9 M5, Levoy & Hanrahan 1996). Checks written without the model code: each ray
// starts at its camera (s, t) on the camera plane and crosses the focal window at its pixel's (u, v); one row of the
// grid with ds = D tan(theta) spacing reproduces the M1 quilt cameras; float vs double over whole images; bad
// sections are ConfigErrors.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <functional>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "camera_models/capture_grid_model.h"
#include "camera_models/capture_grid_setup.h"
#include "camera_test_support.h"
#include "common/error.h"

namespace ht {
namespace {

#ifdef HT_SANITIZED_BUILD
constexpr std::uint32_t kGridStride = 29;
#else
constexpr std::uint32_t kGridStride = 2;
#endif

using nlohmann::json;

TEST(CaptureGrid, RaysJoinCameraAndWindowPoint) {
  DisplayConfig config = builtinDisplay("capture-8x6");
  config.camera.target = glm::dvec3(0.5, 1.0, -2.0);
  const CaptureGridConfig& c = *config.captureGrid;
  const gpu_shared::CaptureGridParams p = makeCaptureGridParams(config, test::testBounds());
  const glm::dvec3 target(0.5, 1.0, -2.0);
  for (std::uint32_t j = 0; j < c.rows; ++j) {
    for (std::uint32_t i = 0; i < c.columns; ++i) {
      const std::uint32_t view = j * c.columns + i;  // bottom-left first, left to right, then up
      const glm::dvec3 camera = target + glm::dvec3((i - 3.5) * 0.08, (j - 2.5) * 0.08, 2.5);
      for (auto [x, y] : {std::pair{0u, 0u}, {639u, 479u}, {320u, 17u}}) {
        glm::vec3 origin, dir;
        gpu_shared::capture_grid_ray(p, x, y, view, glm::vec2(0.5f), origin, dir);
        EXPECT_LT(glm::length(glm::dvec3(origin) - camera), 1e-6);
        const glm::dvec3 d(dir);
        const glm::dvec3 hit = glm::dvec3(origin) + ((target.z - origin.z) / d.z) * d;
        EXPECT_NEAR(hit.x - target.x, ((x + 0.5) / 640.0 - 0.5) * 1.6, 1e-6);
        EXPECT_NEAR(hit.y - target.y, ((y + 0.5) / 480.0 - 0.5) * 1.2, 1e-6);
      }
    }
  }
}

// One row, spacing chosen per camera as D tan(theta_i): M5 reduces to M1 (quilt cameras of looking-glass-webxr).
// With equal spacing only the centre camera pair is exact, so compare camera 0 of a 1x1 grid placed at theta = 0 and
// the 2-camera row at +-ds/2 against o = (D tan(theta), 0, D), theta = atan(ds/(2D)).
TEST(CaptureGrid, RowIsTheQuiltCameraArray) {
  const json config = {{"model", "capture-grid"},
                       {"camera", {{"target", {0, 0, 0}}}},
                       {"captureGrid",
                        {{"columns", 2},
                         {"rows", 1},
                         {"spacing", {0.4, 1.0}},
                         {"distance", 5.0},
                         {"window", {{"width", 2.0}, {"height", 1.5}}},
                         {"image", {{"width", 400}, {"height", 300}}}}}};
  const DisplayConfig parsed = parseDisplayConfig(config.dump(), "row.json", "");
  const gpu_shared::CaptureGridParams p = makeCaptureGridParams(parsed, Bounds3{});
  const double theta = std::atan(0.2 / 5.0);
  for (std::uint32_t view : {0u, 1u}) {
    const double sign = view == 0 ? -1.0 : 1.0;
    const glm::dvec3 o(5.0 * std::tan(sign * theta), 0.0, 5.0);
    const glm::dvec3 target((150.5 / 400.0 - 0.5) * 2.0, (20.5 / 300.0 - 0.5) * 1.5, 0.0);
    glm::vec3 origin, dir;
    gpu_shared::capture_grid_ray(p, 150, 20, view, glm::vec2(0.5f), origin, dir);
    EXPECT_LT(glm::length(glm::dvec3(origin) - o), 1e-6);
    EXPECT_LT(test::angleBetween(glm::dvec3(dir), glm::normalize(target - o)), 1e-6);
  }
}

TEST(CaptureGrid, FloatMatchesDoubleReference) {
  for (const char* name : {"capture-8x6", "capture-16x16"}) {
    const DisplayConfig config = builtinDisplay(name);
    const Bounds3 bounds = test::testBounds();
    const gpu_shared::CaptureGridParams p = makeCaptureGridParams(config, bounds);
    const CaptureGridReference reference(config, bounds);
    const CaptureGridConfig& c = *config.captureGrid;
    const double sceneScale = glm::length(glm::dvec3(bounds.hi) - glm::dvec3(bounds.lo));
    double maxAngle = 0.0, maxOrigin = 0.0;
    auto check = [&](std::uint32_t x, std::uint32_t y, std::uint32_t view, glm::vec2 xi) {
      glm::vec3 o, d;
      gpu_shared::capture_grid_ray(p, x, y, view, xi, o, d);
      const ReferenceRay r = reference.ray(x, y, view, glm::dvec2(xi));
      maxAngle = std::max(maxAngle, test::angleBetween(glm::dvec3(d), r.dir));
      maxOrigin = std::max(maxOrigin, glm::length(glm::dvec3(o) - r.origin));
    };
    const std::uint32_t views = c.columns * c.rows;
    for (std::uint32_t view : {0u, c.columns - 1, views / 2, views - 1}) {
      for (std::uint32_t y = 0; y < c.imageHeight; y += kGridStride)
        for (std::uint32_t x = 0; x < c.imageWidth; x += kGridStride) check(x, y, view, glm::vec2(0.5f));
      for (std::uint32_t x : {0u, c.imageWidth - 1})
        for (std::uint32_t y : {0u, c.imageHeight - 1})
          for (glm::vec2 xi : {glm::vec2(0.0f), glm::vec2(0.9999999f)}) check(x, y, view, xi);
    }
    std::printf("capture %s float vs double: max angle %.3g rad, max origin %.3g (scene scale %.3g)\n", name, maxAngle,
                maxOrigin, sceneScale);
    EXPECT_LE(maxAngle, 2e-6);
    EXPECT_LE(maxOrigin, 1e-6 * sceneScale);
  }
}

ConfigError gridSectionError(const std::function<void(json&)>& edit) {
  json config = {{"model", "capture-grid"},
                 {"captureGrid",
                  {{"columns", 8},
                   {"rows", 6},
                   {"spacing", {0.1, 0.1}},
                   {"distance", 2.0},
                   {"window", {{"width", 1.6}, {"height", 1.2}}},
                   {"image", {{"width", 64}, {"height", 48}}}}}};
  edit(config["captureGrid"]);
  try {
    parseDisplayConfig(config.dump(), "cg.json", "");
  } catch (const ConfigError& e) { return e; }
  ADD_FAILURE() << "expected a ConfigError for " << config.dump();
  return ConfigError("", "", "", "");
}

TEST(CaptureGrid, BadSectionsRejected) {
  EXPECT_EQ(gridSectionError([](json& s) { s["columns"] = 0; }).field(), "captureGrid.columns");
  EXPECT_EQ(gridSectionError([](json& s) { s["spacing"] = {0.1, 0}; }).field(), "captureGrid.spacing");
  EXPECT_EQ(gridSectionError([](json& s) { s["spacing"] = {0.1, "NaN"}; }).field(), "captureGrid.spacing");
  EXPECT_EQ(gridSectionError([](json& s) { s["distance"] = -2; }).field(), "captureGrid.distance");
  EXPECT_EQ(gridSectionError([](json& s) { s["window"]["width"] = 0; }).field(), "captureGrid.window.width");
  EXPECT_EQ(gridSectionError([](json& s) { s["image"]["height"] = 0; }).field(), "captureGrid.image.height");
  EXPECT_EQ(gridSectionError([](json& s) { s["fov"] = 1; }).field(), "captureGrid.fov");
  EXPECT_THROW(makeCaptureGridParams(builtinDisplay("portrait"), test::testBounds()), ConfigError);
}

}  // namespace
}  // namespace ht
