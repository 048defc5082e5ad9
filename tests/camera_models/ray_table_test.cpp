// Generic per-pixel ray table (model "ray-table"): clamped bilinear interpolation of origin and direction
// (ray_table_model.h, run as C++). Checked without the model code: the pixel's own ray at xi = 0.5 bit-exactly,
// linear interpolation between two neighbours, clamping at the borders; float vs the double reference; the table's
// validation (sizes before allocation, non-finite values, zero and opposite directions) and the "rayTable" section.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <random>
#include <string>

#include <gtest/gtest.h>

#include "camera_models/ray_table.h"
#include "camera_models/ray_table_model.h"
#include "camera_test_support.h"
#include "common/error.h"

namespace ht {
namespace {

// A smooth synthetic calibration: origins on a slightly curved sheet, directions fanning out (a display whose rays
// converge toward a viewer at about z = 4), with a small per-pixel wobble so neighbours differ irregularly.
RayTable makeTable(std::uint32_t width, std::uint32_t height) {
  RayTable t;
  t.width = width;
  t.height = height;
  t.origins.resize(std::size_t(width) * height);
  t.directions.resize(t.origins.size());
  for (std::uint32_t y = 0; y < height; ++y) {
    for (std::uint32_t x = 0; x < width; ++x) {
      const double u = (x + 0.5) / width - 0.5, v = (y + 0.5) / height - 0.5;
      const double wobble = 0.01 * std::sin(1.7 * x + 2.3 * y);
      t.origins[t.index(x, y)] = glm::vec3(glm::dvec3(16.0 * u + wobble, 9.0 * v - wobble, 0.3 * u * u + 0.1 * v));
      t.directions[t.index(x, y)] = glm::vec3(glm::dvec3(-0.25 * u + wobble, -0.2 * v, -1.0));
    }
  }
  t.normalizeDirections();
  return t;
}

DisplayConfig rayTableConfig(const std::string& section = R"({"file": "table.exr"})",
                             const std::string& camera = R"({"target": [0, 0, 0]})") {
  return parseDisplayConfig(
      R"({"name": "rt", "model": "ray-table", "camera": )" + camera + R"(, "rayTable": )" + section + "}", "rt.json",
      "/calib");
}

struct Ray {
  glm::vec3 origin, dir;
};

Ray localRay(const RayTable& t, std::uint32_t x, std::uint32_t y, glm::vec2 xi) {
  gpu_shared::RayTableParams p{};
  p.size = glm::ivec4(int(t.width), int(t.height), 0, 0);
  Ray r;
  gpu_shared::ray_table_local_ray(gpu_shared::RayTableView{t.origins.data(), t.directions.data()}, p, x, y, xi,
                                  r.origin, r.dir);
  return r;
}

Ray worldRay(const gpu_shared::RayTableParams& p, const RayTable& t, std::uint32_t x, std::uint32_t y, glm::vec2 xi) {
  Ray r;
  gpu_shared::ray_table_ray(gpu_shared::RayTableView{t.origins.data(), t.directions.data()}, p, x, y, xi, r.origin,
                            r.dir);
  return r;
}

TEST(RayTableModel, PixelCentreReturnsTheEntryExactly) {
  const RayTable t = makeTable(37, 23);
  t.validate("synthetic");
  const DisplayConfig config = rayTableConfig();
  const gpu_shared::RayTableParams p = makeRayTableParams(config, t, test::testBounds());
  for (std::uint32_t y = 0; y < t.height; ++y) {
    for (std::uint32_t x = 0; x < t.width; ++x) {
      const Ray local = localRay(t, x, y, glm::vec2(0.5f));
      EXPECT_EQ(local.origin, t.origins[t.index(x, y)]) << x << "," << y;
      EXPECT_EQ(local.dir, t.directions[t.index(x, y)]) << x << "," << y;
      const Ray world = worldRay(p, t, x, y, glm::vec2(0.5f));  // identity placement: still exact
      EXPECT_EQ(world.origin, t.origins[t.index(x, y)]);
      EXPECT_EQ(world.dir, t.directions[t.index(x, y)]);
    }
  }
}

TEST(RayTableModel, LinearBetweenTwoNeighbours) {
  const RayTable t = makeTable(12, 9);
  for (std::uint32_t y : {0u, 4u, 8u}) {
    for (std::uint32_t x = 0; x + 1 < t.width; ++x) {
      const glm::dvec3 o0(t.origins[t.index(x, y)]), o1(t.origins[t.index(x + 1, y)]);
      const glm::dvec3 d0(t.directions[t.index(x, y)]), d1(t.directions[t.index(x + 1, y)]);
      for (float s : {0.0f, 0.125f, 0.25f, 0.4f, 0.49f}) {
        // Horizontally between entries x and x+1: pixel x at xi.x = 0.5 + s, or pixel x+1 at xi.x = s.
        for (auto [px, xi] : {std::pair{x, 0.5f + s}, {x + 1, s}}) {
          const double w = px == x ? s : s + 0.5;  // weight of entry x+1
          const Ray r = localRay(t, px, y, glm::vec2(xi, 0.5f));
          const glm::dvec3 expectedOrigin = (1.0 - w) * o0 + w * o1;
          EXPECT_LE(glm::length(glm::dvec3(r.origin) - expectedOrigin), 4e-6) << x << " s=" << s;
          // Direction: the linear blend, renormalised (parallel to it, unit length).
          const glm::dvec3 blend = (1.0 - w) * d0 + w * d1;
          EXPECT_LE(test::angleBetween(glm::dvec3(r.dir), blend), 1e-6) << x << " s=" << s;
          EXPECT_NEAR(glm::length(glm::dvec3(r.dir)), 1.0, 1e-6);
        }
      }
    }
  }
  // Vertically: the same along y.
  for (std::uint32_t y = 0; y + 1 < t.height; ++y) {
    const glm::dvec3 o0(t.origins[t.index(5, y)]), o1(t.origins[t.index(5, y + 1)]);
    const Ray r = localRay(t, 5, y, glm::vec2(0.5f, 0.75f));
    EXPECT_LE(glm::length(glm::dvec3(r.origin) - (0.75 * o0 + 0.25 * o1)), 4e-6);
  }
}

TEST(RayTableModel, ClampsAtTheBorders) {
  const RayTable t = makeTable(10, 6);
  const glm::vec2 lo(0.0f), hi(std::nextafter(1.0f, 0.0f));
  auto sameAsEntry = [&](std::uint32_t x, std::uint32_t y, glm::vec2 xi, std::uint32_t ex, std::uint32_t ey) {
    const Ray r = localRay(t, x, y, xi);
    EXPECT_EQ(r.origin, t.origins[t.index(ex, ey)]) << x << "," << y << " xi " << xi.x << "," << xi.y;
    EXPECT_EQ(r.dir, t.directions[t.index(ex, ey)]) << x << "," << y;
  };
  // Corners, footprint toward the outside: the corner entry itself.
  sameAsEntry(0, 0, lo, 0, 0);
  sameAsEntry(9, 0, glm::vec2(hi.x, lo.y), 9, 0);
  sameAsEntry(0, 5, glm::vec2(lo.x, hi.y), 0, 5);
  sameAsEntry(9, 5, hi, 9, 5);
  // Left / right edge, outward along x only: interpolation along y remains, x is clamped.
  for (std::uint32_t y = 1; y < 5; ++y) {
    EXPECT_EQ(localRay(t, 0, y, glm::vec2(0.1f, 0.7f)).origin, localRay(t, 0, y, glm::vec2(0.5f, 0.7f)).origin);
    EXPECT_EQ(localRay(t, 9, y, glm::vec2(0.9f, 0.3f)).origin, localRay(t, 9, y, glm::vec2(0.5f, 0.3f)).origin);
  }
  for (std::uint32_t x = 1; x < 9; ++x) {
    EXPECT_EQ(localRay(t, x, 0, glm::vec2(0.2f, 0.0f)).dir, localRay(t, x, 0, glm::vec2(0.2f, 0.5f)).dir);
    EXPECT_EQ(localRay(t, x, 5, glm::vec2(0.8f, hi.y)).dir, localRay(t, x, 5, glm::vec2(0.8f, 0.5f)).dir);
  }
  // A single-entry and a single-row table.
  const RayTable one = makeTable(1, 1), row = makeTable(8, 1);
  for (glm::vec2 xi : {lo, hi, glm::vec2(0.3f, 0.9f)}) {
    EXPECT_EQ(localRay(one, 0, 0, xi).origin, one.origins[0]);
    EXPECT_EQ(localRay(one, 0, 0, xi).dir, one.directions[0]);
    EXPECT_EQ(localRay(row, 3, 0, glm::vec2(0.5f, xi.y)).origin, row.origins[3]);
  }
}

TEST(RayTableModel, FloatMatchesDoubleReference) {
  const RayTable t = makeTable(1920, 1080);
  t.validate("synthetic");
  const Bounds3 bounds = test::testBounds();
  const DisplayConfig config = rayTableConfig(R"({"file": "t.exr", "units": 0.01})", R"({"target": "auto"})");
  const gpu_shared::RayTableParams p = makeRayTableParams(config, t, bounds);
  EXPECT_EQ(p.size, glm::ivec4(1920, 1080, 0, 0));
  EXPECT_EQ(p.scale.x, 0.01f);
  const RayTableReference ref(config, t, bounds);
  std::mt19937 rng(3);
  std::uniform_real_distribution<float> uniform(0.0f, 1.0f);
  double maxAngle = 0.0, maxOrigin = 0.0;
  for (std::uint32_t y = 0; y < 1080; y += 7) {
    for (std::uint32_t x = 0; x < 1920; x += 5) {
      const glm::vec2 xi(uniform(rng), uniform(rng));
      const Ray f = worldRay(p, t, x, y, xi);
      const ReferenceRay r = ref.ray(x, y, glm::dvec2(xi));
      maxAngle = std::max(maxAngle, test::angleBetween(glm::dvec3(f.dir), r.dir));
      maxOrigin = std::max(maxOrigin, glm::length(glm::dvec3(f.origin) - r.origin));
    }
  }
  // Same bounds as the oblique camera: origin error against the scene scale (bounds diagonal; the float error is
  // dominated by adding the off-origin target).
  const double scale = glm::length(glm::dvec3(bounds.hi) - glm::dvec3(bounds.lo));
  std::printf("ray table 1920x1080: max angle error %.3g rad, max origin error %.3g (scene scale %.3g)\n", maxAngle,
              maxOrigin, scale);
  EXPECT_LE(maxAngle, 2e-6);
  EXPECT_LE(maxOrigin, 1e-6 * scale);
}

TEST(RayTable, ValidationRejectsBadTables) {
  auto expectError = [](const RayTable& t, const std::string& field) {
    try {
      t.validate("table.exr");
      ADD_FAILURE() << "accepted, expected an error on " << field;
    } catch (const ConfigError& e) {
      EXPECT_EQ(e.file(), "table.exr");
      EXPECT_EQ(e.field(), field) << e.what();
    }
  };
  RayTable t = makeTable(6, 4);
  t.origins[t.index(2, 1)].y = std::numeric_limits<float>::quiet_NaN();
  expectError(t, "origin[x=2, y=1]");
  t = makeTable(6, 4);
  t.directions[t.index(5, 3)].z = std::numeric_limits<float>::infinity();
  expectError(t, "direction[x=5, y=3]");
  t = makeTable(6, 4);
  t.directions[t.index(0, 2)] = glm::vec3(0.0f);
  expectError(t, "direction[x=0, y=2]");
  t = makeTable(6, 4);
  t.directions[t.index(3, 2)] = -t.directions[t.index(3, 2)];  // opposite to its neighbours
  EXPECT_THROW(t.validate("table.exr"), ConfigError);
  t = makeTable(6, 4);
  t.origins.pop_back();
  expectError(t, "entries");
  t = makeTable(6, 4);
  t.width = 0;
  expectError(t, "size");
  // Size limits are checked without a table (readers call this before allocating).
  EXPECT_NO_THROW(checkRayTableSize(16384, 16384, "big.exr"));
  EXPECT_THROW(checkRayTableSize(16385, 1, "big.exr"), ConfigError);
  EXPECT_THROW(checkRayTableSize(1, 1ull << 40, "big.exr"), ConfigError);
  EXPECT_THROW(checkRayTableSize(0, 5, "big.exr"), ConfigError);
}

TEST(RayTable, NormalizeDirectionsIsIdempotent) {
  RayTable t = makeTable(5, 5);
  t.directions[7] = glm::vec3(3.0f, 0.0f, -4.0f);
  t.normalizeDirections();
  EXPECT_EQ(t.directions[7], glm::vec3(0.6f, 0.0f, -0.8f));
  const std::vector<glm::vec3> once = t.directions;
  t.normalizeDirections();
  EXPECT_EQ(t.directions, once);
  for (const glm::vec3& d : t.directions) EXPECT_NEAR(glm::length(glm::dvec3(d)), 1.0, 4e-7);
}

TEST(RayTableConfig, SectionParsing) {
  DisplayConfig config = rayTableConfig(R"({"file": "tables/panel.exr", "units": 0.001})");
  ASSERT_EQ(config.model, DisplayModel::RayTable);
  EXPECT_EQ(displayModelName(config.model), "ray-table");
  ASSERT_TRUE(config.rayTable);
  EXPECT_EQ(config.rayTable->file, std::filesystem::path("/calib/tables/panel.exr"));
  EXPECT_EQ(config.rayTable->units, 0.001);
  EXPECT_EQ(rayTableConfig(R"({"file": "/abs/t.exr"})").rayTable->file, std::filesystem::path("/abs/t.exr"));
  EXPECT_EQ(rayTableConfig().rayTable->units, 1.0);

  auto fieldOf = [](const std::string& section, const std::string& camera = R"({"target": "auto"})") {
    try {
      rayTableConfig(section, camera);
    } catch (const ConfigError& e) {
      EXPECT_EQ(e.file(), "rt.json");
      return e.field();
    }
    return std::string("(accepted)");
  };
  EXPECT_EQ(fieldOf(R"({"units": 1})"), "rayTable.file");
  EXPECT_EQ(fieldOf(R"({"file": ""})"), "rayTable.file");
  EXPECT_EQ(fieldOf(R"({"file": 3})"), "rayTable.file");
  EXPECT_EQ(fieldOf(R"({"file": "t.exr", "units": 0})"), "rayTable.units");
  EXPECT_EQ(fieldOf(R"({"file": "t.exr", "units": -2})"), "rayTable.units");
  EXPECT_EQ(fieldOf(R"({"file": "t.exr", "units": "NaN"})"), "rayTable.units");
  EXPECT_EQ(fieldOf(R"({"file": "t.exr", "unit": 1})"), "rayTable.unit");
  EXPECT_EQ(fieldOf(R"({"file": "t.exr"})", R"({"size": 2})"), "camera.size");
  EXPECT_THROW(parseDisplayConfig(R"({"model": "ray-table"})", "x.json", ""), ConfigError);
  EXPECT_THROW(parseDisplayConfig(R"({"model": "pinhole", "rayTable": {"file": "t.exr"}})", "x.json", ""), ConfigError);
  EXPECT_THROW(makeRayTableParams(builtinDisplay("capture-8x6"), makeTable(2, 2), test::testBounds()), ConfigError);
}

}  // namespace
}  // namespace ht
