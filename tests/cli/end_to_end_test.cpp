// end_to_end_test.cpp - the `holotrace` binary as a user runs it (on lavapipe in CI): a real render of the
// Portrait panel, and bad inputs that must fail with exit 1, the file named on stderr, and no output file.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <fstream>
#include <set>

#include "camera_models/capture_grid_setup.h"
#include "camera_models/display_config.h"
#include "camera_models/lenticular_params.h"
#include "frame_io/image_reading.h"
#include "frame_io/pixel_encoding.h"
#include "frame_io/ray_table_exr.h"
#include "process_runner.h"
#include "tests/common/temp_directory.h"

#ifndef HOLOTRACE_EXE
#error "HOLOTRACE_EXE must be defined by tests/cli/CMakeLists.txt"
#endif

namespace ht::cli {
namespace {

namespace fs = std::filesystem;
using test::ProcessResult;
using test::runProcess;
using ::testing::ElementsAre;
using ::testing::HasSubstr;
using ::testing::Not;

ProcessResult holotrace(const std::vector<std::string>& args) { return runProcess(HOLOTRACE_EXE, args); }

struct ImageSize {
  int width = 0, height = 0, channels = 0;
  std::size_t distinctPixels = 0;  // of the 8-bit RGB values, to see that something was rendered
};

ImageSize inspect(const fs::path& path) {
  const frame_io::ImageFile image = frame_io::readImageFile(path);
  std::set<std::uint32_t> distinct;
  for (std::size_t i = 0; i + 2 < image.rgba.size(); i += 4) {
    const std::uint32_t r = frame_io::srgbEncode8(image.rgba[i]), g = frame_io::srgbEncode8(image.rgba[i + 1]);
    distinct.insert(r << 16 | g << 8 | frame_io::srgbEncode8(image.rgba[i + 2]));
  }
  return {int(image.width), int(image.height), int(image.channelNames.size()), distinct.size()};
}

TEST(CliEndToEnd, RendersThePortraitPanelToDefaultNamedPngAndExr) {
  ht::test::TempDirectory dir;
  const ProcessResult r = holotrace({"render", "--scene", "builtin:plain", "--spp", "1", "--out-dir", dir.path()});
  ASSERT_EQ(r.exitCode, 0) << r.err << r.out;
  EXPECT_THAT(r.out, HasSubstr("device:"));
  EXPECT_THAT(r.out, HasSubstr("SAH cost"));
  EXPECT_THAT(r.out, HasSubstr("Mrays/s"));
  EXPECT_THAT(dir.entries(), ElementsAre("portrait_plain.exr", "portrait_plain.png"));

  const PanelLayout panel = panelLayout(builtinDisplay("portrait"));
  const ImageSize png = inspect(dir.path() / "portrait_plain.png");
  EXPECT_EQ(png.width, int(panel.width));
  EXPECT_EQ(png.height, int(panel.height));
  EXPECT_EQ(png.channels, 4);
  EXPECT_GT(png.distinctPixels, 16u) << "the panel image looks empty or flat";
  const ImageSize exr = inspect(dir.path() / "portrait_plain.exr");
  EXPECT_EQ(exr.width, int(panel.width));
  EXPECT_EQ(exr.height, int(panel.height));
}

TEST(CliEndToEnd, PinholeDisplayRendersAnOrdinaryImageOfItsSize) {
  ht::test::TempDirectory dir;
  const fs::path config = dir.path() / "preview.json";
  std::ofstream(config) << R"({"name": "preview", "model": "pinhole", "spp": 1,
                               "pinhole": {"width": 96, "height": 64, "fovyDeg": 50}})";
  const ProcessResult r = holotrace({"render", "--display", config, "--scene", "builtin:plain", "-o",
                                     dir.path() / "frames" / "preview.png", "--seed", "3"});
  ASSERT_EQ(r.exitCode, 0) << r.err << r.out;
  EXPECT_THAT(r.out, HasSubstr("pinhole"));
  const ImageSize png = inspect(dir.path() / "frames" / "preview.png");
  EXPECT_EQ(png.width, 96);
  EXPECT_EQ(png.height, 64);
  EXPECT_GE(png.distinctPixels, 5u) << "expected background, walls, floor and objects";  // plain: ambient only
  EXPECT_THAT(dir.entries(), ElementsAre("frames", "preview.json"));  // only -o: no EXR, no default names
}

TEST(CliEndToEnd, MissingDisplayFileExitsOneNamingItAndWritesNothing) {
  ht::test::TempDirectory dir;
  const fs::path missing = dir.path() / "no-such-display.json";
  const ProcessResult r = holotrace({"render", "--display", missing, "--spp", "1", "--out-dir", dir.path() / "out"});
  EXPECT_EQ(r.exitCode, 1) << r.out;
  EXPECT_THAT(r.err, HasSubstr("no-such-display.json"));
  EXPECT_TRUE(dir.entries().empty());
}

TEST(CliEndToEnd, InvalidDisplayFileExitsOneNamingFileAndField) {
  ht::test::TempDirectory dir;
  const fs::path config = dir.path() / "broken.json";
  std::ofstream(config) << R"({"name": "broken", "model": "lenticular", "spp": 0})";
  const ProcessResult r = holotrace({"render", "--display", config, "-o", dir.path() / "x.png"});
  EXPECT_EQ(r.exitCode, 1) << r.out;
  EXPECT_THAT(r.err, HasSubstr("broken.json"));
  EXPECT_THAT(dir.entries(), ElementsAre("broken.json"));
}

TEST(CliEndToEnd, MissingSceneFileExitsOneNamingItAndWritesNothing) {
  ht::test::TempDirectory dir;
  const ProcessResult r =
      holotrace({"render", "--scene", dir.path() / "no-such-scene.glb", "--spp", "1", "--out-dir", dir.path()});
  EXPECT_EQ(r.exitCode, 1) << r.out;
  EXPECT_THAT(r.err, HasSubstr("no-such-scene.glb"));
  EXPECT_TRUE(dir.entries().empty());
}

TEST(CliEndToEnd, UnwritableOutputFailsBeforeRendering) {
  ht::test::TempDirectory dir;
  std::ofstream(dir.path() / "blocker") << "a file where the output directory should be";
  const fs::path output = dir.path() / "blocker" / "frame.png";
  const ProcessResult r = holotrace({"render", "--scene", "builtin:plain", "--spp", "1", "-o", output});
  EXPECT_EQ(r.exitCode, 1);
  EXPECT_THAT(r.err, HasSubstr(output.string()));
  EXPECT_THAT(r.out, ::testing::Not(HasSubstr("frame:"))) << "the error must come before the render";
  EXPECT_THAT(dir.entries(), ElementsAre("blocker"));
}

TEST(CliEndToEnd, UsageErrorsExitTwo) {
  const ProcessResult r = holotrace({"render", "--spq", "1"});
  EXPECT_EQ(r.exitCode, 2);
  EXPECT_EQ(r.err, "holotrace render: unknown option '--spq' (see holotrace render --help)\n");
}

TEST(CliEndToEnd, InfoListsDevicesMarksTheChosenOneAndBuiltins) {
  const ProcessResult r = holotrace({"info"});
  ASSERT_EQ(r.exitCode, 0) << r.err;
  EXPECT_THAT(r.out, HasSubstr("<- chosen"));
  EXPECT_THAT(r.out, HasSubstr("maxStorageBufferRange"));
  EXPECT_THAT(r.out, HasSubstr("builtin:portrait"));
  EXPECT_THAT(r.out, HasSubstr("builtin:plain"));
}

TEST(CliEndToEnd, BadDeviceIndexExitsOne) {
  const ProcessResult r = holotrace({"info", "--device", "99"});
  EXPECT_EQ(r.exitCode, 1) << r.out;
  EXPECT_THAT(r.err, HasSubstr("99"));
}

// Writes a display config into `dir` and returns its path.
fs::path writeConfig(const ht::test::TempDirectory& dir, const std::string& name, const std::string& json) {
  const fs::path path = dir.path() / (name + ".json");
  std::ofstream(path) << json;
  return path;
}

TEST(CliEndToEnd, CaptureGridWritesATaggedQuiltWithMetadataAndAMultiViewExr) {
  ht::test::TempDirectory dir;
  const fs::path config = writeConfig(dir, "rig", R"({"name": "rig", "model": "capture-grid", "spp": 1,
      "captureGrid": {"columns": 4, "rows": 2, "spacing": [0.1, 0.1], "distance": 3, "window": {"width": 2.4,
      "height": 1.8}, "image": {"width": 32, "height": 24}}})");
  const ProcessResult r = holotrace({"render", "--display", config.string(), "--scene", "builtin:sphere", "-o",
                                     (dir.path() / "cap.png").string(), "--exr", (dir.path() / "cap.exr").string()});
  ASSERT_EQ(r.exitCode, 0) << r.err << r.out;
  EXPECT_THAT(r.out, HasSubstr("8 views of 32x24"));
  EXPECT_THAT(dir.entries(), ElementsAre("cap.exr", "cap_qs4x2a1.3333333333333333.json",
                                         "cap_qs4x2a1.3333333333333333.png", "rig.json"));
  const ImageSize quilt = inspect(dir.path() / "cap_qs4x2a1.3333333333333333.png");
  EXPECT_EQ(quilt.width, 128);
  EXPECT_EQ(quilt.height, 48);
  EXPECT_GE(quilt.distinctPixels, 2u);  // the unlit sphere (ambient only) and the background
  const frame_io::ImageHeader exr = frame_io::readImageHeader(dir.path() / "cap.exr");
  EXPECT_EQ(exr.channelNames.size(), 32u);
  EXPECT_EQ(exr.views, 8u);
}

TEST(CliEndToEnd, ProjectorArrayWritesOneImagePerProjector) {
  ht::test::TempDirectory dir;
  const fs::path config = writeConfig(dir, "wall", R"({"name": "wall", "model": "projector-array", "spp": 2,
      "projectorArray": {"screen": {"width": 160, "height": 90}, "observerDistance": 300, "observerHeight": 0,
      "angularScattering": "auto", "image": {"width": 40, "height": 20},
      "projectors": [{"position": [-10, 0, -180]}, {"position": [0, 0, -180]}, {"position": [10, 0, -180]}]}})");
  const ProcessResult r = holotrace(
      {"render", "--display", config.string(), "--scene", "builtin:sphere", "-o", (dir.path() / "p.png").string()});
  ASSERT_EQ(r.exitCode, 0) << r.err << r.out;
  EXPECT_THAT(r.out, HasSubstr("3 views of 40x20"));
  EXPECT_THAT(dir.entries(), ElementsAre("p_v00.png", "p_v01.png", "p_v02.png", "wall.json"));
  EXPECT_EQ(inspect(dir.path() / "p_v01.png").width, 40);
}

TEST(CliEndToEnd, IntegralPanelRendersItsLcdImage) {
  ht::test::TempDirectory dir;
  const fs::path config = writeConfig(dir, "lenslets", R"({"name": "lenslets", "model": "integral", "spp": 1,
      "integral": {"panelWidth": 96, "panelHeight": 64, "pixelPitch": 0.1, "lensPitch": 1.0, "gap": 3.0,
      "focalLength": 3.0, "viewerDistance": 600, "frontPlane": 600}})");
  const ProcessResult r = holotrace(
      {"render", "--display", config.string(), "--scene", "builtin:sphere", "-o", (dir.path() / "lcd.png").string()});
  ASSERT_EQ(r.exitCode, 0) << r.err << r.out;
  EXPECT_THAT(r.out, HasSubstr("1 view of 96x64, 18432 targets"));  // 3 subpixel targets per pixel
  const ImageSize lcd = inspect(dir.path() / "lcd.png");
  EXPECT_EQ(lcd.width, 96);
  EXPECT_EQ(lcd.height, 64);
}

TEST(CliEndToEnd, QuiltPathRendersThePortraitQuiltAtItsDefaultSize) {
  ht::test::TempDirectory dir;
  const ProcessResult r = holotrace({"render", "--quilt", "--scene", "builtin:sphere", "--spp", "1", "--depth", "0",
                                     "-o", (dir.path() / "q.png").string()});
  ASSERT_EQ(r.exitCode, 0) << r.err << r.out;
  EXPECT_THAT(r.out, HasSubstr("48 views of 420x560"));
  const ImageSize quilt = inspect(dir.path() / "q_qs8x6a0.75.png");
  EXPECT_EQ(quilt.width, 3360);
  EXPECT_EQ(quilt.height, 3360);
}

TEST(CliEndToEnd, QuiltPathOfANonLenticularDisplayIsAConfigError) {
  ht::test::TempDirectory dir;
  const ProcessResult r =
      holotrace({"render", "--quilt", "--display", "builtin:capture-8x6", "--out-dir", dir.path().string()});
  EXPECT_EQ(r.exitCode, 1);
  EXPECT_THAT(r.err, HasSubstr("capture-grid"));
  EXPECT_THAT(r.err, HasSubstr("--quilt"));
  EXPECT_TRUE(dir.entries().empty());
}

// --debug views: channel c of pixel (x, y) = the view phase of subpixel (x, y, c), from the shared model code.
TEST(CliEndToEnd, DebugViewsWritesTheSubpixelViewPhasesWithoutTracing) {
  ht::test::TempDirectory dir;
  const fs::path exr = dir.path() / "phase.exr";
  const ProcessResult r = holotrace({"render", "--debug", "views", "--exr", exr.string()});
  ASSERT_EQ(r.exitCode, 0) << r.err << r.out;
  EXPECT_THAT(r.out, Not(HasSubstr("device:")));
  const frame_io::ImageFile image = frame_io::readImageFile(exr);
  ASSERT_EQ(image.width, 1536u);
  const std::vector<float>& pixels = image.rgba;
  // Independent check of the classic phase formula (docs/OPTICS.md §3.1) at a few subpixels, half-float precision.
  const DisplayConfig display = builtinDisplay("portrait");
  const LenticularShaderValues v = lenticularShaderValues(*display.calibration);
  for (std::uint32_t x : {0u, 700u, 1535u}) {
    for (std::uint32_t y : {0u, 1000u, 2047u}) {
      for (int c = 0; c < 3; ++c) {
        const double u = (x + 0.5) / 1536.0, vv = (y + 0.5) / 2048.0;
        const double phi = (u + c * v.subp + vv * v.tilt) * v.pitch - v.center;
        double t = phi - std::floor(phi);
        if (display.calibration->invView) t = 1.0 - t;
        const float got = pixels[((2047 - y) * std::size_t(1536) + x) * 4 + c];
        const double d = std::fabs(got - t);
        EXPECT_LT(std::min(d, 1.0 - d), 2e-3) << x << "," << y << "," << c;
      }
    }
  }
}

// `holotrace rays` writes the GPU rays of every pixel of every view; they match the double reference of the model
// (written independently of the float code), and the file reads back as a "ray-table" display that renders and
// reproduces the same table bit for bit.
TEST(CliEndToEnd, RaysDumpsTheTableAndItReadsBackAsARayTableDisplay) {
  ht::test::TempDirectory dir;
  const fs::path config = writeConfig(dir, "rig", R"({"name": "rig", "model": "capture-grid", "spp": 1,
      "camera": {"target": [0, 0, 0]},
      "captureGrid": {"columns": 3, "rows": 2, "spacing": [0.1, 0.1], "distance": 3, "window": {"width": 2.4,
      "height": 1.8}, "image": {"width": 32, "height": 24}}})");
  const fs::path table = dir.path() / "rig_rays.exr";
  ProcessResult r =
      holotrace({"rays", "--display", config.string(), "--scene", "builtin:sphere", "-o", table.string()});
  ASSERT_EQ(r.exitCode, 0) << r.err << r.out;
  const RayTable rays = frame_io::readRayTableExr(table);
  ASSERT_EQ(rays.width, 192u);  // the 6 views side by side (they fit the 16384-entry limit)
  ASSERT_EQ(rays.height, 24u);
  const DisplayConfig display = loadDisplayConfig(config);
  const CaptureGridReference reference(display, Bounds3{});
  double maxAngle = 0.0, maxOrigin = 0.0;
  for (std::uint32_t view = 0; view < 6; ++view)
    for (std::uint32_t y = 0; y < 24; ++y)
      for (std::uint32_t x = 0; x < 32; ++x) {
        const std::size_t i = rays.index(view * 32 + x, y);
        const ReferenceRay ref = reference.ray(x, y, view, glm::dvec2(0.5));
        const glm::dvec3 d(rays.directions[i]);
        maxAngle = std::max(maxAngle, std::atan2(glm::length(glm::cross(d, ref.dir)), glm::dot(d, ref.dir)));
        maxOrigin = std::max(maxOrigin, glm::length(glm::dvec3(rays.origins[i]) - ref.origin));
      }
  EXPECT_LT(maxAngle, 2e-6);
  EXPECT_LT(maxOrigin, 1e-6 * 3.0);

  const fs::path tableDisplay = writeConfig(dir, "table", R"({"name": "table", "model": "ray-table",
      "camera": {"target": [0, 0, 0]}, "spp": 2, "rayTable": {"file": "rig_rays.exr", "units": 1}})");
  r = holotrace({"render", "--display", tableDisplay.string(), "--scene", "builtin:sphere", "-o",
                 (dir.path() / "t.png").string()});
  ASSERT_EQ(r.exitCode, 0) << r.err << r.out;
  EXPECT_EQ(inspect(dir.path() / "t.png").width, 192);
  r = holotrace({"rays", "--display", tableDisplay.string(), "--scene", "builtin:sphere", "-o",
                 (dir.path() / "again.exr").string()});
  ASSERT_EQ(r.exitCode, 0) << r.err << r.out;
  const RayTable again = frame_io::readRayTableExr(dir.path() / "again.exr");
  EXPECT_EQ(again.origins, rays.origins);
  EXPECT_EQ(again.directions, rays.directions);
}

TEST(CliEndToEnd, RayTableDisplayWithAMissingFileNamesTheField) {
  ht::test::TempDirectory dir;
  const fs::path config = writeConfig(dir, "table", R"({"name": "table", "model": "ray-table",
      "rayTable": {"file": "nowhere.exr"}})");
  const ProcessResult r = holotrace({"render", "--display", config.string(), "--out-dir", dir.path().string()});
  EXPECT_EQ(r.exitCode, 1);
  EXPECT_THAT(r.err, HasSubstr("rayTable.file"));
  EXPECT_THAT(dir.entries(), ElementsAre("table.json"));
}

}  // namespace
}  // namespace ht::cli
