// Oblique (sheared orthographic) direction camera (docs/OPTICS.md §9 M6, Burnett "Oblique Slice and Dice"). The float
// shared header (run as C++) against the double reference over whole images and an 8K x 8K image; consistency checks
// written without the model code (parallel rays per view, each ray crosses its window point, starts on z = zFront,
// view angles evenly spaced in angle); placement defaults; bad sections are ConfigErrors.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <numbers>
#include <random>
#include <string>

#include <gtest/gtest.h>

#include "camera_models/oblique_model.h"
#include "camera_models/oblique_setup.h"
#include "camera_test_support.h"
#include "common/error.h"

namespace ht {
namespace {

#ifdef HT_SANITIZED_BUILD
constexpr std::uint32_t kObliqueStride = 7;
#else
constexpr std::uint32_t kObliqueStride = 1;
#endif

constexpr double kMaxAngleError = 2e-6;        // rad
constexpr double kMaxOriginErrorScale = 1e-6;  // of the scene scale (bounds diagonal)

DisplayConfig obliqueConfig(const std::string& section, const std::string& camera = R"({"target": "auto"})") {
  return parseDisplayConfig(
      R"({"name": "obl", "model": "oblique", "camera": )" + camera + R"(, "oblique": )" + section + "}", "obl.json",
      "");
}

double sceneScale(const Bounds3& b) { return glm::length(glm::dvec3(b.hi) - glm::dvec3(b.lo)); }

struct FloatRay {
  glm::dvec3 origin, dir;
};

FloatRay floatRay(const gpu_shared::ObliqueParams& p, std::uint32_t x, std::uint32_t y, std::uint32_t view,
                  glm::vec2 xi) {
  glm::vec3 o, d;
  gpu_shared::oblique_ray(p, x, y, view, xi, o, d);
  return {glm::dvec3(o), glm::dvec3(d)};
}

struct MaxErrors {
  double angle = 0.0, origin = 0.0;
  void add(const FloatRay& f, const ReferenceRay& r) {
    angle = std::max(angle, test::angleBetween(f.dir, r.dir));
    origin = std::max(origin, glm::length(f.origin - r.origin));
  }
};

TEST(ObliqueConfig, ShippedNineByNine) {
  const DisplayConfig config = builtinDisplay("oblique-9x9");
  ASSERT_EQ(config.model, DisplayModel::Oblique);
  ASSERT_TRUE(config.oblique);
  EXPECT_EQ(displayModelName(config.model), "oblique");
  EXPECT_EQ(config.oblique->columns, 9u);
  EXPECT_EQ(config.oblique->rows, 9u);
  EXPECT_EQ(config.oblique->horizontalConeDeg, 40.0);
  EXPECT_EQ(config.oblique->verticalConeDeg, 40.0);
  EXPECT_EQ(config.oblique->imageWidth, 512u);
  EXPECT_EQ(config.oblique->imageHeight, 512u);
  EXPECT_FALSE(config.oblique->windowWidth);
  EXPECT_FALSE(config.oblique->zFront);
  const gpu_shared::ObliqueParams p = makeObliqueParams(config, test::testBounds());
  EXPECT_EQ(p.grid, glm::ivec4(9, 9, 512, 512));
}

// Float (shared header as C++) vs double over whole images, every view of a 9x9 grid at the pixel centre, plus the
// image corners at the extreme footprints (xi = 0 and xi -> 1) and random footprints.
TEST(ObliqueModel, FloatMatchesDoubleOverWholeImages) {
  const Bounds3 bounds = test::testBounds();
  const DisplayConfig config = builtinDisplay("oblique-9x9");
  const gpu_shared::ObliqueParams p = makeObliqueParams(config, bounds);
  const ObliqueReference ref(config, bounds);
  const double scale = sceneScale(bounds);
  MaxErrors err;
  std::mt19937 rng(7);
  std::uniform_real_distribution<float> uniform(0.0f, 1.0f);
  const glm::vec2 xiMax(std::nextafter(1.0f, 0.0f));
  for (std::uint32_t view = 0; view < 81; ++view) {
    const bool whole = view == 0 || view == 40 || view == 80 || view == 8 || view == 72;
    for (std::uint32_t y = 0; y < 512; y += whole ? kObliqueStride : 37) {
      for (std::uint32_t x = 0; x < 512; x += whole ? kObliqueStride : 37) {
        const glm::vec2 xi(uniform(rng), uniform(rng));
        err.add(floatRay(p, x, y, view, xi), ref.ray(x, y, view, glm::dvec2(xi)));
        err.add(floatRay(p, x, y, view, glm::vec2(0.5f)), ref.ray(x, y, view, glm::dvec2(0.5)));
      }
    }
    for (auto [x, y] : {std::pair{0u, 0u}, {511u, 0u}, {0u, 511u}, {511u, 511u}}) {
      for (glm::vec2 xi : {glm::vec2(0.0f), xiMax, glm::vec2(0.0f, xiMax.y), glm::vec2(xiMax.x, 0.0f)})
        err.add(floatRay(p, x, y, view, xi), ref.ray(x, y, view, glm::dvec2(xi)));
    }
  }
  std::printf("oblique 9x9 512x512: max angle error %.3g rad, max origin error %.3g (scene scale %.3g)\n", err.angle,
              err.origin, scale);
  EXPECT_LE(err.angle, kMaxAngleError);
  EXPECT_LE(err.origin, kMaxOriginErrorScale * scale);
}

// 8K x 8K views: the pixel coordinate reaches 8192, where float spacing is 1e-3 pixel. Edges, corners, and rows and
// columns through the image, with random footprints, for a wide full-parallax grid.
TEST(ObliqueModel, FloatMatchesDoubleOnEightKImage) {
  const Bounds3 bounds = test::testBounds();
  const DisplayConfig config = obliqueConfig(
      R"({"columns": 16, "rows": 12, "horizontalConeDeg": 100, "verticalConeDeg": 70,
          "image": {"width": 8192, "height": 8192}})");
  const gpu_shared::ObliqueParams p = makeObliqueParams(config, bounds);
  const ObliqueReference ref(config, bounds);
  const double scale = sceneScale(bounds);
  MaxErrors err;
  std::mt19937 rng(11);
  std::uniform_real_distribution<float> uniform(0.0f, 1.0f);
  const glm::vec2 xiMax(std::nextafter(1.0f, 0.0f));
  for (std::uint32_t view : {0u, 15u, 100u, 176u, 191u}) {
    for (std::uint32_t k = 0; k < 8192; k += 3 * kObliqueStride) {
      for (auto [x, y] : {std::pair{k, 0u}, {k, 8191u}, {0u, k}, {8191u, k}, {k, k}, {8191u - k, k}, {k, 4097u}}) {
        const glm::vec2 xi(uniform(rng), uniform(rng));
        err.add(floatRay(p, x, y, view, xi), ref.ray(x, y, view, glm::dvec2(xi)));
      }
    }
    for (auto [x, y] : {std::pair{0u, 0u}, {8191u, 0u}, {0u, 8191u}, {8191u, 8191u}}) {
      for (glm::vec2 xi : {glm::vec2(0.0f), xiMax, glm::vec2(0.5f)})
        err.add(floatRay(p, x, y, view, xi), ref.ray(x, y, view, glm::dvec2(xi)));
    }
  }
  std::printf("oblique 16x12 8192x8192: max angle error %.3g rad, max origin error %.3g (scene scale %.3g)\n",
              err.angle, err.origin, scale);
  EXPECT_LE(err.angle, kMaxAngleError);
  EXPECT_LE(err.origin, kMaxOriginErrorScale * scale);
}

// Near-grazing directions (outermost view at 88.5 degrees, tan = 39): the direction stays within the angular budget;
// origins lie zFront*tan(theta) away, so their error is measured against that distance.
TEST(ObliqueModel, WideConesStayAccurate) {
  const Bounds3 bounds = test::testBounds();
  const DisplayConfig config = obliqueConfig(
      R"({"columns": 64, "rows": 2, "horizontalConeDeg": 179.9, "verticalConeDeg": 120,
          "image": {"width": 1024, "height": 768}})");
  const gpu_shared::ObliqueParams p = makeObliqueParams(config, bounds);
  const ObliqueReference ref(config, bounds);
  double maxAngle = 0.0, maxOriginRel = 0.0;
  for (std::uint32_t view = 0; view < 128; ++view) {
    for (auto [x, y] : {std::pair{0u, 0u}, {1023u, 767u}, {512u, 384u}, {1023u, 0u}}) {
      const FloatRay f = floatRay(p, x, y, view, glm::vec2(0.25f, 0.75f));
      const ReferenceRay r = ref.ray(x, y, view, glm::dvec2(0.25, 0.75));
      maxAngle = std::max(maxAngle, test::angleBetween(f.dir, r.dir));
      const double reach = std::max(sceneScale(bounds), glm::length(r.origin - ref.geometry().target));
      maxOriginRel = std::max(maxOriginRel, glm::length(f.origin - r.origin) / reach);
    }
  }
  std::printf("oblique 179.9/120 degree cones: max angle error %.3g rad, max relative origin error %.3g\n", maxAngle,
              maxOriginRel);
  EXPECT_LE(maxAngle, kMaxAngleError);
  EXPECT_LE(maxOriginRel, kMaxOriginErrorScale);
}

// Geometry checked from the definition, not the model code: per view all directions are identical (orthographic),
// the direction makes the view's angles (evenly spaced bin centres, measured with atan2), every ray crosses the
// plane z = 0 at its pixel's window point and starts on z = zFront in display-local coordinates.
TEST(ObliqueModel, ParallelRaysThroughWindowPointsFromFrontPlane) {
  const Bounds3 bounds = test::testBounds();
  const DisplayConfig config = obliqueConfig(
      R"({"columns": 5, "rows": 3, "horizontalConeDeg": 60, "verticalConeDeg": 24,
          "image": {"width": 320, "height": 200}, "window": {"width": 3.2, "height": 2.5}, "zFront": 1.75})",
      R"({"target": [0.25, -1.5, 2.0]})");
  const gpu_shared::ObliqueParams p = makeObliqueParams(config, bounds);
  const glm::dvec3 target(0.25, -1.5, 2.0);
  const double pi = std::numbers::pi;
  for (std::uint32_t j = 0; j < 3; ++j) {
    for (std::uint32_t i = 0; i < 5; ++i) {
      const std::uint32_t view = j * 5 + i;  // bottom-left first
      const double thx = (-24.0 + 12.0 * i) * pi / 180.0, thy = (-8.0 + 8.0 * j) * pi / 180.0;
      const FloatRay first = floatRay(p, 0, 0, view, glm::vec2(0.5f));
      // The ray travels along -e: e = (tan thx, tan thy, 1)/|.|, so atan2(-d.x, -d.z) = thx, atan2(-d.y, -d.z) = thy.
      EXPECT_NEAR(std::atan2(-first.dir.x, -first.dir.z), thx, 1e-6) << view;
      EXPECT_NEAR(std::atan2(-first.dir.y, -first.dir.z), thy, 1e-6) << view;
      EXPECT_NEAR(glm::length(first.dir), 1.0, 1e-6);
      for (std::uint32_t y = 0; y < 200; y += 13) {
        for (std::uint32_t x = 0; x < 320; x += 11) {
          const glm::vec2 xi(float(x % 7) / 7.0f, float(y % 5) / 5.0f);
          const FloatRay r = floatRay(p, x, y, view, xi);
          EXPECT_EQ(r.dir, first.dir) << "view " << view << " pixel " << x << "," << y;  // parallel: same bits
          EXPECT_NEAR(r.origin.z - target.z, 1.75, 1e-6);                                // starts on z = zFront
          const glm::dvec3 window =
              target + glm::dvec3((x + double(xi.x)) / 320.0 * 3.2 - 1.6, (y + double(xi.y)) / 200.0 * 2.5 - 1.25, 0.0);
          // Crosses z = 0 (display-local) at its window point.
          const double t = (target.z - r.origin.z) / r.dir.z;
          const glm::dvec3 hit = r.origin + t * r.dir;
          EXPECT_NEAR(hit.x, window.x, 2e-6) << view;
          EXPECT_NEAR(hit.y, window.y, 2e-6) << view;
        }
      }
    }
  }
}

TEST(ObliqueModel, HorizontalOnlyParallax) {
  for (const char* section : {R"({"columns": 7, "rows": 1, "horizontalConeDeg": 30, "image": {"width": 64,
                                  "height": 32}})",
                              R"({"columns": 7, "rows": 4, "horizontalConeDeg": 30, "verticalConeDeg": 0,
                                  "image": {"width": 64, "height": 32}})"}) {
    const DisplayConfig config = obliqueConfig(section);
    const gpu_shared::ObliqueParams p = makeObliqueParams(config, test::testBounds());
    double previous = -1.0;
    for (std::uint32_t i = 0; i < 7; ++i) {
      const FloatRay r = floatRay(p, 10, 20, i, glm::vec2(0.3f, 0.6f));
      EXPECT_EQ(r.dir.y, 0.0) << section;
      // Views run left to right: view 0 emits toward the left (e.x < 0), i.e. its ray travels to +x.
      const double emittedX = -r.dir.x;
      EXPECT_GT(emittedX, previous) << i;
      previous = emittedX;
    }
    EXPECT_LT(-floatRay(p, 0, 0, 0, glm::vec2(0.5f)).dir.x, 0.0);
  }
}

TEST(ObliqueSetup, AutoWindowAndFrontPlane) {
  const Bounds3 bounds = test::testBounds();  // (-0.8, 1, -3) .. (1.4, 2.6, -1.5)
  DisplayConfig config = obliqueConfig(R"({"columns": 3, "rows": 3, "horizontalConeDeg": 20, "verticalConeDeg": 20,
                                           "image": {"width": 400, "height": 200}})");
  ObliqueGeometry g = resolveObliqueGeometry(config, bounds);
  EXPECT_NEAR(g.target.x, 0.3, 1e-6);
  EXPECT_NEAR(g.target.y, 1.8, 1e-6);
  EXPECT_NEAR(g.target.z, -2.25, 1e-6);
  // Auto fit as the other models: height = 1.1 * max(extent.y, extent.x / aspect) = 1.1 * max(1.6, 2.2/2).
  EXPECT_NEAR(g.windowHeight, 1.76, 1e-6);
  EXPECT_NEAR(g.windowWidth, 3.52, 1e-6);
  // The start plane clears the scene: target.z + zFront > bounds.hi.z.
  EXPECT_GT(g.target.z + g.zFront, double(bounds.hi.z));
  EXPECT_NEAR(g.zFront, 0.75 + 0.05 * 3.52, 1e-6);
  // Every ray of every view starts in front of the scene box.
  const gpu_shared::ObliqueParams p = makeObliqueParams(config, bounds);
  for (std::uint32_t view = 0; view < 9; ++view)
    for (auto [x, y] : {std::pair{0u, 0u}, {399u, 199u}}) EXPECT_GT(floatRay(p, x, y, view, {}).origin.z, -1.5);

  config = obliqueConfig(R"({"columns": 3, "rows": 3, "horizontalConeDeg": 20, "verticalConeDeg": 20,
                             "image": {"width": 400, "height": 200}, "zFront": 4})",
                         R"({"target": [0, 0, 0], "size": 3})");
  g = resolveObliqueGeometry(config, bounds);
  EXPECT_EQ(g.target, glm::dvec3(0.0));
  EXPECT_NEAR(g.windowHeight, 3.0, 1e-12);
  EXPECT_NEAR(g.windowWidth, 6.0, 1e-12);
  EXPECT_EQ(g.zFront, 4.0);
  EXPECT_THROW(makeObliqueParams(builtinDisplay("capture-8x6"), bounds), ConfigError);
}

ConfigError obliqueError(const std::string& section, const std::string& camera = R"({"target": "auto"})") {
  try {
    obliqueConfig(section, camera);
  } catch (const ConfigError& e) { return e; }
  ADD_FAILURE() << "accepted: " << section;
  return ConfigError("", "", "", "");
}

TEST(ObliqueConfig, BadSectionsAreRejected) {
  const std::string image = R"("image": {"width": 64, "height": 64})";
  struct Case {
    std::string section, field;
  } cases[] = {
      {R"({"columns": 0, "rows": 3, "horizontalConeDeg": 20, "verticalConeDeg": 20, )" + image + "}",
       "oblique.columns"},
      {R"({"columns": -2, "rows": 3, "horizontalConeDeg": 20, "verticalConeDeg": 20, )" + image + "}",
       "oblique.columns"},
      {R"({"columns": 3, "rows": 0, "horizontalConeDeg": 20, "verticalConeDeg": 20, )" + image + "}", "oblique.rows"},
      {R"({"columns": 3, "rows": 2.5, "horizontalConeDeg": 20, "verticalConeDeg": 20, )" + image + "}", "oblique.rows"},
      {R"({"columns": 3, "rows": 3, "horizontalConeDeg": 180, "verticalConeDeg": 20, )" + image + "}",
       "oblique.horizontalConeDeg"},
      {R"({"columns": 3, "rows": 3, "horizontalConeDeg": 20, "verticalConeDeg": 200, )" + image + "}",
       "oblique.verticalConeDeg"},
      {R"({"columns": 3, "rows": 3, "horizontalConeDeg": -5, "verticalConeDeg": 20, )" + image + "}",
       "oblique.horizontalConeDeg"},
      {R"({"columns": 3, "rows": 3, "horizontalConeDeg": "NaN", "verticalConeDeg": 20, )" + image + "}",
       "oblique.horizontalConeDeg"},
      {R"({"columns": 3, "rows": 3, "horizontalConeDeg": 20, )" + image + "}", "oblique.verticalConeDeg"},
      {R"({"columns": 3, "rows": 3, "horizontalConeDeg": 20, "verticalConeDeg": 20})", "oblique.image"},
      {R"({"columns": 3, "rows": 3, "horizontalConeDeg": 20, "verticalConeDeg": 20, "image": {"width": 0,
          "height": 64}})",
       "oblique.image.width"},
      {R"({"columns": 3, "rows": 3, "horizontalConeDeg": 20, "verticalConeDeg": 20, "image": {"width": 64,
          "height": -64}})",
       "oblique.image.height"},
      {R"({"columns": 3, "rows": 3, "horizontalConeDeg": 20, "verticalConeDeg": 20, "image": {"width": 64,
          "height": 64, "depth": 1}})",
       "oblique.image.depth"},
      {R"({"columns": 3, "rows": 3, "horizontalConeDeg": 20, "verticalConeDeg": 20, )" + image +
           R"(, "window": {"width": 0, "height": 1}})",
       "oblique.window.width"},
      {R"({"columns": 3, "rows": 3, "horizontalConeDeg": 20, "verticalConeDeg": 20, )" + image +
           R"(, "window": {"width": 1, "height": -1}})",
       "oblique.window.height"},
      {R"({"columns": 3, "rows": 3, "horizontalConeDeg": 20, "verticalConeDeg": 20, )" + image +
           R"(, "window": {"width": 1, "height": "NaN"}})",
       "oblique.window.height"},
      {R"({"columns": 3, "rows": 3, "horizontalConeDeg": 20, "verticalConeDeg": 20, )" + image + R"(, "window": 2})",
       "oblique.window"},
      {R"({"columns": 3, "rows": 3, "horizontalConeDeg": 20, "verticalConeDeg": 20, )" + image + R"(, "zFront": 0})",
       "oblique.zFront"},
      {R"({"columns": 3, "rows": 3, "horizontalConeDeg": 20, "verticalConeDeg": 20, )" + image + R"(, "zFront": -1})",
       "oblique.zFront"},
      {R"({"columns": 3, "rows": 3, "horizontalConeDeg": 20, "verticalConeDeg": 20, )" + image +
           R"(, "zFront": "far"})",
       "oblique.zFront"},
      {R"({"columns": 3, "rows": 3, "horizontalConeDeg": 20, "verticalConeDeg": 20, )" + image + R"(, "zfront": 1})",
       "oblique.zfront"},
  };
  for (const Case& c : cases) {
    const ConfigError e = obliqueError(c.section);
    EXPECT_EQ(e.file(), "obl.json") << c.section;
    EXPECT_EQ(e.field(), c.field) << c.section << "\n" << e.what();
    EXPECT_FALSE(e.expected().empty());
  }
  // Both camera.size and an explicit window: ambiguous size.
  const ConfigError both = obliqueError(R"({"columns": 3, "rows": 3, "horizontalConeDeg": 20, "verticalConeDeg": 20,
      "image": {"width": 64, "height": 64}, "window": {"width": 1, "height": 1}})",
                                        R"({"size": 2})");
  EXPECT_EQ(both.field(), "camera.size");
  // NaN / infinity cannot be written as JSON numbers: the parser reports them.
  EXPECT_THROW(obliqueConfig(R"({"columns": 3, "rows": 3, "horizontalConeDeg": NaN, "verticalConeDeg": 20,
                                 "image": {"width": 64, "height": 64}})"),
               ConfigError);
  EXPECT_THROW(obliqueConfig(R"({"columns": 3, "rows": 3, "horizontalConeDeg": 1e999, "verticalConeDeg": 20,
                                 "image": {"width": 64, "height": 64}})"),
               ConfigError);
  // Section required for, and only for, model "oblique".
  EXPECT_THROW(parseDisplayConfig(R"({"model": "oblique"})", "x.json", ""), ConfigError);
  EXPECT_THROW(parseDisplayConfig(R"({"model": "pinhole", "oblique": {"columns": 3, "rows": 1,
                                      "horizontalConeDeg": 20, "image": {"width": 64, "height": 64}}})",
                                  "x.json", ""),
               ConfigError);
}

}  // namespace
}  // namespace ht
