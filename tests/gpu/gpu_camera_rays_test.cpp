// GPU ray generation of every camera model against its double-precision reference (written independently of the
// float model code, camera_models/*_setup.cpp / lenticular_reference.cpp): the rays the raygen kernel writes (read
// back with Renderer::generateRays) over whole rows of every view, including the corners of an 8K panel.
// Bounds (issue 3): angular error <= 2e-6 rad, origin error <= 1e-6 of the scene scale. The footprint positions of
// multi-sample rays are regenerated on the CPU with the shared camera_models/footprint_sampling.h.
#include <cmath>
#include <cstdio>
#include <functional>
#include <optional>
#include <vector>

#include <gtest/gtest.h>

#include "camera_models/capture_grid_setup.h"
#include "camera_models/footprint_sampling.h"
#include "camera_models/integral_setup.h"
#include "camera_models/lens_distortion.h"
#include "camera_models/lenticular_params.h"
#include "camera_models/lenticular_reference.h"
#include "camera_models/oblique_setup.h"
#include "camera_models/pinhole_params.h"
#include "camera_models/projector_setup.h"
#include "camera_models/quilt_setup.h"
#include "camera_models/ray_table.h"
#include "gpu/display_camera.h"
#include "gpu_test_util.h"
#include "tests/camera_models/camera_test_support.h"

namespace ht {
namespace {

constexpr double kAngleBound = 2e-6;          // rad
constexpr double kOriginBoundOfScale = 1e-6;  // of the scene scale

struct TargetIndex {
  std::uint32_t x, y, view, c;
};

TargetIndex decode(const gpu::FrameShape& shape, std::uint64_t target) {
  const std::uint64_t pixel = target / shape.targetsPerPixel;
  const auto c = static_cast<std::uint32_t>(target % shape.targetsPerPixel);
  const std::uint64_t viewPixels = std::uint64_t(shape.width) * shape.height;
  return {static_cast<std::uint32_t>(pixel % shape.width),
          static_cast<std::uint32_t>((pixel / shape.width) % shape.height),
          static_cast<std::uint32_t>(pixel / viewPixels), c};
}

// nullopt: no comparison for this sample (lenticular phase at the wrap, where either side is right).
using ReferenceFn = std::function<std::optional<ReferenceRay>(const TargetIndex&, glm::dvec2 xi)>;

// The reference of the models whose targets are (x, y, view) pixels.
template <class Reference>
ReferenceFn viewReference(const Reference& reference) {
  return [&reference](const TargetIndex& t, glm::dvec2 xi) -> std::optional<ReferenceRay> {
    return reference.ray(t.x, t.y, t.view, xi);
  };
}

struct RayErrors {
  double angle = 0.0, origin = 0.0;
  std::uint64_t rays = 0, skipped = 0;
};

// Whole rows: the first two, the middle and the last two of each listed view, plus every `stride`-th row (stride 1:
// the whole view).
std::vector<std::uint32_t> rowsToCheck(std::uint32_t height, std::uint32_t stride) {
  std::vector<std::uint32_t> rows = {0, 1, height / 2, height - 2, height - 1};
  for (std::uint32_t y = 2; y < height - 2; ++y) {
    if (y % stride == 0 && y != height / 2) rows.push_back(y);
  }
  return rows;
}

RayErrors measure(gpu::Renderer& renderer, const gpu::FrameCamera& camera, const gpu::RenderSettings& settings,
                  const std::vector<std::uint32_t>& views, std::uint32_t rowStride, const ReferenceFn& reference) {
  const gpu::FrameShape shape = gpu::frameShape(camera);
  const std::uint32_t rowTargets = shape.width * shape.targetsPerPixel;
  RayErrors errors;
  for (std::uint32_t view : views) {
    for (std::uint32_t y : rowsToCheck(shape.height, rowStride)) {
      const std::uint64_t first = (std::uint64_t(view) * shape.height + y) * rowTargets;
      const auto rays = renderer.generateRays(camera, settings, first, rowTargets);
      for (std::uint32_t i = 0; i < rowTargets; ++i) {
        const std::uint64_t target = first + i;
        const TargetIndex index = decode(shape, target);
        for (std::uint32_t s = 0; s < settings.spp; ++s) {
          const glm::vec2 xi = gpu_shared::footprint_sample(static_cast<std::uint32_t>(target), s, settings.spp,
                                                            settings.seed, static_cast<std::uint32_t>(settings.filter));
          const auto ref = reference(index, glm::dvec2(xi));
          if (!ref) {
            ++errors.skipped;
            continue;
          }
          const gpu_shared::HtRay& ray = rays[std::size_t(i) * settings.spp + s];
          errors.angle = std::max(errors.angle, test::angleBetween(glm::dvec3(ray.dir), ref->dir));
          const double scale = std::max(1.0, glm::length(ref->origin));
          errors.origin = std::max(errors.origin, glm::length(glm::dvec3(ray.origin) - ref->origin) / scale);
          ++errors.rays;
        }
      }
    }
  }
  return errors;
}

// Origin errors are relative to max(1, |o_ref|), the ray's distance from the world origin: the scale its float
// coordinates are rounded at.
void expectWithinBounds(const char* what, const RayErrors& e) {
  std::printf("[ %s ] %llu GPU rays vs double: max angle %.3g rad, max origin error %.3g of scale (%llu skipped)\n",
              what, static_cast<unsigned long long>(e.rays), e.angle, e.origin,
              static_cast<unsigned long long>(e.skipped));
  EXPECT_GT(e.rays, 1000u) << what;
  EXPECT_LT(e.angle, kAngleBound) << what;
  EXPECT_LT(e.origin, kOriginBoundOfScale) << what;
  EXPECT_LT(e.skipped, e.rays / 1000 + 50) << what;
}

std::vector<std::uint32_t> allViews(std::uint32_t n) {
  std::vector<std::uint32_t> v(n);
  for (std::uint32_t i = 0; i < n; ++i) v[i] = i;
  return v;
}

class GpuCameraRays : public ::testing::Test {
 protected:
  void SetUp() override {
    Scene scene;
    const std::uint32_t m = test::addMaterial(scene, Material{});
    test::addQuad(scene, glm::vec3(-1, -1, -5), glm::vec3(2, 0, 0), glm::vec3(0, 2, 0), m);
    renderer_ = std::make_unique<gpu::Renderer>(test::sharedContext(), scene);
    settings_.spp = 2;
    settings_.seed = 7;
  }
  std::unique_ptr<gpu::Renderer> renderer_;
  gpu::RenderSettings settings_;
  const Bounds3 bounds_ = test::testBounds();
};

void checkLenticular(gpu::Renderer& renderer, const gpu::RenderSettings& settings, const char* what,
                     const DisplayConfig& config, const Bounds3& bounds, std::uint32_t rowStride) {
  const LenticularReference reference(config, bounds);
  const RayErrors e = measure(renderer, makeLenticularParams(config, bounds), settings, {0}, rowStride,
                              [&](const TargetIndex& t, glm::dvec2 xi) -> std::optional<ReferenceRay> {
                                const double phase = reference.viewPhase(t.x, t.y, t.c, xi);
                                if (phase < 1e-5 || phase > 1.0 - 1e-5) return std::nullopt;
                                return reference.rayForPhase(phase, reference.sampleUV(t.x, t.y, t.c, xi));
                              });
  expectWithinBounds(what, e);
}

TEST_F(GpuCameraRays, LenticularPortraitRows) {
  checkLenticular(*renderer_, settings_, "portrait", builtinDisplay("portrait"), bounds_, test::kSanitized ? 16 : 1);
}

TEST_F(GpuCameraRays, LenticularEightKGen3CornersAndRows) {
  checkLenticular(*renderer_, settings_, "8k gen3", test::eightKDisplay(2), bounds_, test::kSanitized ? 97 : 13);
}

// Raygen folds the panel's cell pattern mode and count into its code (specialisation constants, lenticular_model.h
// HT_LENTICULAR_CELL_MODE): every mode, with 2 cells (mode 3 counts 4 cells, so its cell index wraps), against the
// double reference.
TEST_F(GpuCameraRays, LenticularEveryGen3CellPatternMode) {
  for (int mode = 1; mode <= 4; ++mode) {
    const std::string what = "8k gen3 cell mode " + std::to_string(mode);
    checkLenticular(*renderer_, settings_, what.c_str(), test::eightKDisplay(mode), bounds_,
                    test::kSanitized ? 1031 : 211);
  }
}

TEST_F(GpuCameraRays, LenticularEightKClassicBgrFlipped) {
  checkLenticular(*renderer_, settings_, "8k classic bgr flipX", test::eightKDisplay(0, true, true), bounds_,
                  test::kSanitized ? 211 : 29);
}

TEST_F(GpuCameraRays, QuiltEveryView) {
  const DisplayConfig config = builtinDisplay("portrait");
  const QuiltLayout layout = defaultQuiltLayout(config);
  const QuiltReference reference(config, bounds_, layout);
  const RayErrors e = measure(*renderer_, makeQuiltParams(config, bounds_, layout), settings_, allViews(layout.views()),
                              test::kSanitized ? 23 : 3, viewReference(reference));
  expectWithinBounds("quilt 8x6", e);
}

TEST_F(GpuCameraRays, ProjectorWallEveryProjector) {
  const DisplayConfig config = builtinDisplay("holovizio-wall-70");
  const ProjectorArrayReference reference(config, bounds_);
  gpu::RenderSettings centre = settings_;
  centre.spp = 1;  // with spp > 1 the screen scattering rotates the ray (ProjectorScatteredRaysPassThroughTheScreen)
  const RayErrors e = measure(*renderer_, makeProjectorArrayParams(config, bounds_), centre, allViews(70),
                              test::kSanitized ? 71 : 9, viewReference(reference));
  expectWithinBounds("projector wall 70", e);
}

// The same wall behind distorting projector lenses (barrel and pincushion with tangential terms, principal point off
// centre): the kernel's float Newton inverse vs the reference's double one (lens_distortion_params.cpp).
TEST_F(GpuCameraRays, ProjectorWallThroughDistortingLenses) {
  for (const LensDistortionSettings lens : {LensDistortionSettings{-0.22, 0.05, 0.0, 0.0008, -0.0004},
                                            LensDistortionSettings{0.15, 0.02, 0.001, -0.001, 0.0015}}) {
    DisplayConfig config = builtinDisplay("holovizio-wall-70");
    const ProjectorConfig& first = config.projectorArray->projectors[0];
    config.projectorArray->lens = ProjectorArrayConfig::Lens{1.1 * first.width, glm::dvec2(12.0, -7.5), lens};
    const ProjectorArrayReference reference(config, bounds_);
    const gpu_shared::ProjectorArrayParams params = makeProjectorArrayParams(config, bounds_);
    ASSERT_TRUE(gpu_shared::lens_has_distortion(params.distortion));
    gpu::RenderSettings centre = settings_;
    centre.spp = 1;
    const RayErrors e =
        measure(*renderer_, params, centre, {0, 17, 35, 69}, test::kSanitized ? 71 : 9, viewReference(reference));
    expectWithinBounds(lens.k1 < 0 ? "projector wall, barrel lenses" : "projector wall, pincushion lenses", e);
  }
}

// Independent of the model code: a scattered ray still passes through its projector's screen point S (the rotation
// axis is vertical through S) and keeps its vertical slope (the scattering is horizontal only, docs/OPTICS.md §6).
TEST_F(GpuCameraRays, ProjectorScatteredRaysPassThroughTheScreen) {
  const DisplayConfig config = builtinDisplay("holovizio-wall-70");
  const ProjectorArrayReference reference(config, bounds_);
  const ProjectorPlacement& place = reference.placement();
  const gpu_shared::ProjectorArrayParams params = makeProjectorArrayParams(config, bounds_);
  gpu::RenderSettings scattered = settings_;
  scattered.spp = 16;
  const gpu::FrameShape shape = gpu::frameShape(params);
  const std::uint32_t view = 35, y = 300;
  const std::uint64_t first = (std::uint64_t(view) * shape.height + y) * shape.width;
  const auto rays = renderer_->generateRays(params, scattered, first, shape.width);
  double maxMiss = 0.0, maxSlope = 0.0, maxAngle = 0.0;
  for (std::uint32_t x = 0; x < shape.width; ++x) {
    for (std::uint32_t s = 0; s < scattered.spp; ++s) {
      const glm::vec2 xi =
          gpu_shared::footprint_sample(static_cast<std::uint32_t>(first + x), s, scattered.spp, scattered.seed, 0u);
      const ReferenceRay straight = reference.ray(x, y, view, glm::dvec2(xi));
      const glm::dvec3 screen =
          place.target + reference.screenPoint(view, glm::dvec2(x, y) + glm::dvec2(xi)) * place.scale;
      const gpu_shared::HtRay& r = rays[std::size_t(x) * scattered.spp + s];
      const glm::dvec3 o(r.origin), d(r.dir);
      const double t = (screen.z - o.z) / d.z;
      maxMiss = std::max(maxMiss, glm::length(o + t * d - screen) / glm::length(screen - o));
      const double slope = d.y / glm::length(glm::dvec2(d.x, d.z));
      const double slopeRef = straight.dir.y / glm::length(glm::dvec2(straight.dir.x, straight.dir.z));
      maxSlope = std::max(maxSlope, std::fabs(slope - slopeRef));
      maxAngle = std::max(maxAngle, test::angleBetween(d, straight.dir));
    }
  }
  std::printf("[ scattered ] miss %.3g of distance, slope error %.3g, max scatter angle %.3g rad\n", maxMiss, maxSlope,
              maxAngle);
  EXPECT_LT(maxMiss, 2e-6);
  EXPECT_LT(maxSlope, 2e-6);
  EXPECT_GT(maxAngle, 1e-3);  // the samples really are scattered
}

TEST_F(GpuCameraRays, IntegralPanelRows) {
  const DisplayConfig config = builtinDisplay("integral-15-4k");
  const IntegralReference reference(config, bounds_);
  const RayErrors e =
      measure(*renderer_, makeIntegralParams(config, bounds_), settings_, {0}, test::kSanitized ? 41 : 5,
              [&](const TargetIndex& t, glm::dvec2 xi) -> std::optional<ReferenceRay> {
                // On a lens border either lens is right (like the lenticular phase wrap).
                if (reference.lensBorderDistance(reference.samplePosition(t.x, t.y, t.c, xi)) < 1e-5) {
                  return std::nullopt;
                }
                return reference.ray(t.x, t.y, t.c, xi);
              });
  expectWithinBounds("integral 4k", e);
}

TEST_F(GpuCameraRays, CaptureGridEveryView) {
  const DisplayConfig config = builtinDisplay("capture-8x6");
  const CaptureGridReference reference(config, bounds_);
  const gpu_shared::CaptureGridParams params = makeCaptureGridParams(config, bounds_);
  const RayErrors e = measure(*renderer_, params, settings_, allViews(gpu::frameShape(params).views),
                              test::kSanitized ? 53 : 7, viewReference(reference));
  expectWithinBounds("capture 8x6", e);
}

// Wider filters move samples outside the footprint (tent: [-0.5, 1.5), Gaussian: unbounded); the models are affine in
// xi, so the rays must still match the reference at the warped position.
TEST_F(GpuCameraRays, FiltersWarpTheFootprintAndStayExact) {
  const DisplayConfig config = builtinDisplay("capture-8x6");
  const CaptureGridReference reference(config, bounds_);
  const gpu_shared::CaptureGridParams params = makeCaptureGridParams(config, bounds_);
  for (gpu::SampleFilter filter : {gpu::SampleFilter::Tent, gpu::SampleFilter::Gaussian}) {
    gpu::RenderSettings s = settings_;
    s.spp = 8;
    s.filter = filter;
    double minXi = 1.0, maxXi = 0.0;
    const RayErrors e = measure(*renderer_, params, s, {0, 47}, 239, [&](const TargetIndex& t, glm::dvec2 xi) {
      minXi = std::min({minXi, xi.x, xi.y});
      maxXi = std::max({maxXi, xi.x, xi.y});
      return viewReference(reference)(t, xi);
    });
    expectWithinBounds(filter == gpu::SampleFilter::Tent ? "capture, tent" : "capture, gaussian", e);
    EXPECT_LT(minXi, -0.2);  // the filter reaches into the neighbours
    EXPECT_GT(maxXi, 1.2);
    if (filter == gpu::SampleFilter::Tent) {
      EXPECT_GE(minXi, -0.5);
      EXPECT_LE(maxXi, 1.5);
    }
  }
}

TEST_F(GpuCameraRays, ObliqueEveryDirection) {
  const DisplayConfig config = builtinDisplay("oblique-9x9");
  const ObliqueReference reference(config, bounds_);
  const gpu_shared::ObliqueParams params = makeObliqueParams(config, bounds_);
  const RayErrors e = measure(*renderer_, params, settings_, allViews(gpu::frameShape(params).views),
                              test::kSanitized ? 101 : 13, viewReference(reference));
  expectWithinBounds("oblique 9x9", e);
}

// Pinhole through a Brown-Conrady lens (lens_distortion.h, OpenCV form), every 3rd row and the corners. The double
// reference does not reuse the kernel's solver: it inverts the written-out distortion with Newton steps on a
// central-difference Jacobian, to 1e-15; the camera frame comes from resolvePinholeCamera's eye / lookAt / up.
struct DistortedPinholeReference {
  PinholeCamera camera;
  LensDistortionSettings lens;
  glm::dvec3 right, up, forward;
  double tanHalf, aspect;

  DistortedPinholeReference(const DisplayConfig& config, const Bounds3& bounds)
      : camera(resolvePinholeCamera(config, bounds)), lens(config.pinhole.distortion) {
    forward = glm::normalize(camera.lookAt - camera.eye);
    right = glm::normalize(glm::cross(forward, camera.up));
    up = glm::cross(right, forward);
    tanHalf = std::tan(0.5 * camera.fovyDeg * 3.14159265358979323846 / 180.0);
    aspect = double(camera.width) / camera.height;
  }
  glm::dvec2 distort(glm::dvec2 u) const {
    const double r2 = u.x * u.x + u.y * u.y;
    const double radial = 1.0 + lens.k1 * r2 + lens.k2 * r2 * r2 + lens.k3 * r2 * r2 * r2;
    return {u.x * radial + 2.0 * lens.p1 * u.x * u.y + lens.p2 * (r2 + 2.0 * u.x * u.x),
            u.y * radial + lens.p1 * (r2 + 2.0 * u.y * u.y) + 2.0 * lens.p2 * u.x * u.y};
  }
  glm::dvec2 undistort(glm::dvec2 xd) const {
    glm::dvec2 u = xd;
    const double h = 1e-6;
    for (int i = 0; i < 50; ++i) {
      const glm::dvec2 f = distort(u) - xd;
      if (glm::length(f) < 1e-15) break;
      const glm::dvec2 cx = (distort(u + glm::dvec2(h, 0)) - distort(u - glm::dvec2(h, 0))) / (2 * h);
      const glm::dvec2 cy = (distort(u + glm::dvec2(0, h)) - distort(u - glm::dvec2(0, h))) / (2 * h);
      const double det = cx.x * cy.y - cy.x * cx.y;
      u -= glm::dvec2(cy.y * f.x - cy.x * f.y, -cx.y * f.x + cx.x * f.y) / det;
    }
    return u;
  }
  std::optional<ReferenceRay> ray(std::uint32_t x, std::uint32_t y, std::uint32_t, glm::dvec2 xi) const {
    const glm::dvec2 xd((2.0 * (x + xi.x) / camera.width - 1.0) * aspect * tanHalf,
                        (2.0 * (y + xi.y) / camera.height - 1.0) * tanHalf);
    const glm::dvec2 u = undistort(xd);
    return ReferenceRay{camera.eye, glm::normalize(right * u.x + up * u.y + forward)};
  }
};

TEST_F(GpuCameraRays, PinholeThroughADistortingLens) {
  for (const char* lens : {"{}", R"({"k1": -0.28, "k2": 0.07, "p1": 0.0005, "p2": -0.0003})",
                           R"({"k1": 0.12, "k2": 0.03, "k3": 0.001, "p1": -0.001, "p2": 0.002})"}) {
    const DisplayConfig config =
        parseDisplayConfig(std::string(R"({"model": "pinhole", "pinhole": {"width": 640, "height": 360, "fovyDeg": 60,
            "eye": [0.3, 0.2, 4], "lookAt": [0, 0, -5], "distortion": )") +
                               lens + "}}",
                           "lens", "");
    const DistortedPinholeReference reference(config, bounds_);
    const RayErrors e = measure(*renderer_, makePinholeParams(config, bounds_), settings_, {0},
                                test::kSanitized ? 37 : 3, viewReference(reference));
    expectWithinBounds(lens, e);
  }
}

// A per-pixel table (a curved, off-centre fan of rays, the kind a measured calibration gives) interpolated over the
// footprint: GPU vs the double reference of the interpolation.
TEST_F(GpuCameraRays, RayTableInterpolatesLikeTheReference) {
  auto table = std::make_shared<RayTable>();
  table->width = 160;
  table->height = 90;
  for (std::uint32_t y = 0; y < table->height; ++y) {
    for (std::uint32_t x = 0; x < table->width; ++x) {
      const double u = (x + 0.5) / table->width - 0.5, v = (y + 0.5) / table->height - 0.5;
      table->origins.push_back(glm::vec3(float(0.02 * u * u), float(0.01 * v), 2.0f));
      table->directions.push_back(glm::vec3(glm::normalize(glm::dvec3(0.8 * u + 0.1 * v * v, 0.45 * v, -1.0))));
    }
  }
  table->normalizeDirections();
  table->validate("synthetic");
  const DisplayConfig config = parseDisplayConfig(
      R"({"name": "table", "model": "ray-table", "rayTable": {"file": "t.exr", "units": 2.5}})", "synthetic", "");
  const RayTableReference reference(config, *table, bounds_);
  const gpu::RayTableCamera camera{makeRayTableParams(config, *table, bounds_), table};
  gpu::RenderSettings s = settings_;
  s.spp = 8;
  s.filter = gpu::SampleFilter::Tent;  // reaches into the neighbours and past the border (clamped)
  const RayErrors e = measure(
      *renderer_, camera, s, {0}, 1,
      [&](const TargetIndex& t, glm::dvec2 xi) -> std::optional<ReferenceRay> { return reference.ray(t.x, t.y, xi); });
  expectWithinBounds("ray table 160x90", e);
  // spp 1: the table's own rays, bit for bit after the placement.
  gpu::RenderSettings one = settings_;
  one.spp = 1;
  const auto rays = renderer_->generateRays(camera, one, 0, 160 * 90);
  for (std::size_t i = 0; i < rays.size(); i += 97) EXPECT_EQ(rays[i].dir, table->directions[i]) << i;
}

}  // namespace
}  // namespace ht
