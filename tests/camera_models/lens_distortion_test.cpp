// Brown-Conrady distortion (Brown 1966; OpenCV camera model): the float Newton inverse undoes a distortion computed
// here in double from the written-out formula (round trip), the Jacobian is checked against finite differences through
// the round trip's convergence, and the distorted pinhole ray leaves along the undistorted direction.
#include <cmath>

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "camera_models/lens_distortion.h"
#include "camera_models/pinhole_model.h"
#include "camera_models/pinhole_params.h"
#include "camera_models/projector_setup.h"
#include "camera_test_support.h"
#include "common/error.h"

namespace ht {
namespace {

struct Coefficients {
  double k1, k2, k3, p1, p2;
};

// x_d = x(1 + k1 r^2 + k2 r^4 + k3 r^6) + 2 p1 x y + p2 (r^2 + 2x^2); y_d = y(...) + p1 (r^2 + 2y^2) + 2 p2 x y.
glm::dvec2 distortDouble(const Coefficients& c, glm::dvec2 u) {
  const double r2 = u.x * u.x + u.y * u.y;
  const double radial = 1.0 + c.k1 * r2 + c.k2 * r2 * r2 + c.k3 * r2 * r2 * r2;
  return {u.x * radial + 2.0 * c.p1 * u.x * u.y + c.p2 * (r2 + 2.0 * u.x * u.x),
          u.y * radial + c.p1 * (r2 + 2.0 * u.y * u.y) + 2.0 * c.p2 * u.x * u.y};
}

gpu_shared::LensDistortion block(const Coefficients& c) {
  gpu_shared::LensDistortion d{};
  d.radial = glm::vec4(glm::dvec4(c.k1, c.k2, c.k3, 1.0));
  d.tangential = glm::vec4(glm::dvec4(c.p1, c.p2, 0.0, 0.0));
  return d;
}

TEST(LensDistortion, UndistortInvertsDistortRoundTrip) {
  // Barrel, pincushion and a strong wide-angle set with tangential terms (OpenCV-typical magnitudes).
  for (const Coefficients& c :
       {Coefficients{-0.28, 0.07, 0.0, 0.0005, -0.0003}, Coefficients{0.12, 0.03, 0.001, -0.001, 0.002},
        Coefficients{-0.35, 0.15, -0.03, 0.001, 0.001}}) {
    const gpu_shared::LensDistortion d = block(c);
    double maxError = 0.0, maxForward = 0.0;
    for (double x = -0.6; x <= 0.6; x += 0.05) {
      for (double y = -0.45; y <= 0.45; y += 0.05) {
        const glm::dvec2 u(x, y);
        const glm::dvec2 xd = distortDouble(c, u);
        maxForward =
            std::max(maxForward, glm::length(glm::dvec2(gpu_shared::brown_conrady_distort(d, glm::vec2(u))) - xd));
        const glm::dvec2 back(gpu_shared::brown_conrady_undistort(d, glm::vec2(xd)));
        maxError = std::max(maxError, glm::length(back - u));
      }
    }
    EXPECT_LT(maxForward, 1e-6);
    EXPECT_LT(maxError, 2e-6);  // float: a few ulp of coordinates below 1
  }
}

TEST(LensDistortion, ZeroCoefficientsAreIdentity) {
  const gpu_shared::LensDistortion none{};
  const glm::vec2 p(0.3f, -0.2f);
  EXPECT_EQ(gpu_shared::brown_conrady_distort(none, p), p);
  EXPECT_EQ(gpu_shared::brown_conrady_undistort(none, p), p);
}

TEST(LensDistortion, DistortedPinholeRayLeavesAlongUndistortedPoint) {
  DisplayConfig config = test::loadFixture("display_pinhole.json");
  const Coefficients c{-0.28, 0.07, 0.0, 0.0005, -0.0003};
  config.pinhole.distortion = LensDistortionSettings{c.k1, c.k2, c.k3, c.p1, c.p2};
  const gpu_shared::PinholeParams p = makePinholeParams(config, test::testBounds());
  ASSERT_TRUE(gpu_shared::lens_has_distortion(p.distortion));
  const PinholeCamera camera = resolvePinholeCamera(config, test::testBounds());
  // Camera frame rebuilt here from eye / lookAt / up (camera looks down -z).
  const glm::dvec3 forward = glm::normalize(camera.lookAt - camera.eye);
  const glm::dvec3 right = glm::normalize(glm::cross(forward, camera.up));
  const glm::dvec3 up = glm::cross(right, forward);
  const double tanHalf = std::tan(0.5 * camera.fovyDeg * 3.14159265358979323846 / 180.0);
  const double aspect = double(camera.width) / camera.height;
  for (auto [x, y] :
       {std::pair{0u, 0u}, {camera.width - 1, camera.height - 1}, {camera.width / 3, camera.height / 2}}) {
    glm::vec3 origin, dir;
    gpu_shared::pinhole_ray(p, x, y, glm::vec2(0.5f), origin, dir);
    // Project the ray back to normalized image coordinates and distort in double: must land on the pixel centre.
    const glm::dvec3 v(dir);
    const double depth = glm::dot(v, forward);
    const glm::dvec2 u(glm::dot(v, right) / depth, glm::dot(v, up) / depth);
    const glm::dvec2 xd = distortDouble(c, u);
    EXPECT_NEAR(xd.x, (2.0 * (x + 0.5) / camera.width - 1.0) * aspect * tanHalf, 2e-6);
    EXPECT_NEAR(xd.y, (2.0 * (y + 0.5) / camera.height - 1.0) * tanHalf, 2e-6);
    EXPECT_LT(glm::length(glm::dvec3(origin) - camera.eye), 1e-5 * (1.0 + glm::length(camera.eye)));
  }
}

// Config: "pinhole.distortion" reaches the GPU block; unknown keys, non-numbers and folding lenses are refused with
// the field named.
TEST(LensDistortion, ConfigFieldsReachTheBlock) {
  const DisplayConfig config = parseDisplayConfig(R"({"model": "pinhole", "pinhole": {"width": 64, "height": 48,
      "distortion": {"k1": -0.2, "k2": 0.05, "p2": 0.001}}})",
                                                  "lens.json", "");
  EXPECT_EQ(config.pinhole.distortion.k1, -0.2);
  EXPECT_EQ(config.pinhole.distortion.k3, 0.0);
  const gpu_shared::PinholeParams p = makePinholeParams(config, test::testBounds());
  EXPECT_EQ(p.distortion.radial, glm::vec4(-0.2f, 0.05f, 0.0f, 1.0f));
  EXPECT_EQ(p.distortion.tangential, glm::vec4(0.0f, 0.001f, 0.0f, 0.0f));
  const DisplayConfig ideal =
      parseDisplayConfig(R"({"model": "pinhole", "pinhole": {"width": 64, "height": 48}})", "i.json", "");
  EXPECT_FALSE(gpu_shared::lens_has_distortion(makePinholeParams(ideal, test::testBounds()).distortion));
}

TEST(LensDistortion, BadCoefficientsNameTheField) {
  auto message = [](const std::string& distortion, double fovyDeg) {
    try {
      const DisplayConfig c =
          parseDisplayConfig(R"({"model": "pinhole", "pinhole": {"width": 64, "height": 48, "fovyDeg": )" +
                                 std::to_string(fovyDeg) + R"(, "distortion": )" + distortion + "}}",
                             "lens.json", "");
      makePinholeParams(c, test::testBounds());
    } catch (const ConfigError& e) { return std::string(e.what()); }
    return std::string("(no error)");
  };
  EXPECT_THAT(message(R"({"k4": 0.1})", 45), ::testing::HasSubstr("k4"));
  EXPECT_THAT(message(R"({"k1": "big"})", 45), ::testing::HasSubstr("pinhole.distortion.k1"));
  EXPECT_THAT(message(R"([0.1])", 45), ::testing::HasSubstr("pinhole.distortion"));
  // Strong barrel on a 90-degree lens: f'(r) = 1 - 1.5 r^2 vanishes at r = 0.82, inside the corner radius 1.67.
  const std::string fold = message(R"({"k1": -0.5})", 90);
  EXPECT_THAT(fold, ::testing::HasSubstr("pinhole.distortion"));
  EXPECT_THAT(fold, ::testing::HasSubstr("fold"));
  // The same lens is fine on a narrow field of view (corner radius 0.29).
  EXPECT_EQ(message(R"({"k1": -0.5})", 20), "(no error)");
}

// "projectorArray.lens": parsed into the block, and refused with the field named when it cannot be a lens.
TEST(LensDistortion, ProjectorLensConfig) {
  auto config = [](const std::string& lens) {
    return parseDisplayConfig(
        R"({"model": "projector-array", "projectorArray": {"screen": {"width": 400, "height": 300},
        "observerDistance": 1000, "image": {"width": 320, "height": 240},
        "projectors": [{"position": [-20, 0, -800]}, {"position": [20, 0, -800]}], "lens": )" +
            lens + "}}",
        "wall.json", "");
  };
  auto message = [&](const std::string& lens) {
    try {
      makeProjectorArrayParams(config(lens), test::testBounds());
    } catch (const ConfigError& e) { return std::string(e.what()); }
    return std::string("(no error)");
  };
  const gpu_shared::ProjectorArrayParams p = makeProjectorArrayParams(
      config(R"({"focalLength": 400, "principalOffset": [3, -2], "distortion": {"k1": -0.1}})"), test::testBounds());
  EXPECT_EQ(p.lens, glm::vec4(400.0f, 0.0f, 3.0f, -2.0f));
  EXPECT_EQ(p.distortion.radial, glm::vec4(-0.1f, 0.0f, 0.0f, 1.0f));
  EXPECT_FALSE(gpu_shared::lens_has_distortion(
      makeProjectorArrayParams(config(R"({"focalLength": 400})"), test::testBounds()).distortion));
  EXPECT_THAT(message(R"({"focalLength": 0})"), ::testing::HasSubstr("projectorArray.lens.focalLength"));
  EXPECT_THAT(message(R"({"focalLength": 400, "principalOffset": [1]})"), ::testing::HasSubstr("principalOffset"));
  EXPECT_THAT(message(R"({"focalLength": 400, "zoom": 2})"), ::testing::HasSubstr("zoom"));
  // A 60-pixel focal length puts the image corner at normalized radius 3.3, past k1 = -0.1's fold at r = 1.83.
  EXPECT_THAT(message(R"({"focalLength": 60, "distortion": {"k1": -0.1}})"), ::testing::HasSubstr("fold"));
}

}  // namespace
}  // namespace ht
