// quilt_commands_test.cpp - `holotrace interleave` end to end: a quilt written by `holotrace render --quilt --layout
// quilt` and interleaved for its panel matches the direct per-subpixel render of the same scene (PSNR bounds measured
// on lavapipe), the better filter is better, and bad quilts fail with exit 1, the value named and no output file.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include "frame_io/atomic_output_file.h"
#include "frame_io/image_encoding.h"
#include "frame_io/image_reading.h"
#include "frame_io/pixel_encoding.h"
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
using ::testing::HasSubstr;

ProcessResult holotrace(const std::vector<std::string>& args) { return runProcess(HOLOTRACE_EXE, args); }

// PSNR (dB, peak 1) over R, G, B of two 8-bit sRGB images as the panel shows them.
double psnr8(const fs::path& a, const fs::path& b) {
  const frame_io::ImageFile x = frame_io::readImageFile(a), y = frame_io::readImageFile(b);
  EXPECT_EQ(x.width, y.width);
  EXPECT_EQ(x.height, y.height);
  if (x.rgba.size() != y.rgba.size()) return 0.0;
  double sum = 0.0;
  std::size_t n = 0;
  for (std::size_t i = 0; i < x.rgba.size(); ++i) {
    if (i % 4 == 3) continue;
    const double d = (double(frame_io::srgbEncode8(x.rgba[i])) - frame_io::srgbEncode8(y.rgba[i])) / 255.0;
    sum += d * d;
    ++n;
  }
  return 10.0 * std::log10(double(n) / sum);
}

// A 192x128 panel with the Portrait's phase rates (0.16 phase per pixel across) and a quilt of 8x6 views of 96x64:
// small enough for a fast test, with the Portrait's view count.
fs::path writeSmallPanel(const fs::path& dir) {
  const fs::path path = dir / "small.json";
  std::ofstream(path) << R"({"name": "small", "calibration": {"pitch": 52.59, "slope": -7.21, "center": 0.40,
      "viewCone": 40, "invView": 1, "DPI": 324, "screenW": 192, "screenH": 128, "flipImageX": 0, "flipImageY": 0,
      "flipSubp": 0}, "camera": {"quilt": {"columns": 8, "rows": 6, "width": 768, "height": 384}}})";
  return path;
}

// The panel's quilt of a plain scene at 1 spp, interleaved, against the direct render at 1 spp: each subpixel's ray at
// its footprint centre vs the vendor path's two nearest views sampled at the pixel's uv (view quantisation and tile
// resampling: docs/OPTICS.md §8). Measured (lavapipe, 2026-12-02): vendor lerp 40.43 dB, centred lerp 40.53 dB,
// nearest 40.28 dB. The Portrait itself (1536x2048, 8x6 of 420x560, same command): 46.1 / 48.5 / 47.8 dB, where the
// centred lerp's gain is clearer.
TEST(CliInterleave, InterleavedRenderedQuiltMatchesTheDirectRender) {
  ht::test::TempDirectory dir;
  const fs::path display = writeSmallPanel(dir.path());
  const std::vector<std::string> common = {"--display", display, "--scene", "builtin:plain", "--spp", "1"};
  auto withCommon = [&](std::vector<std::string> args) {
    args.insert(args.begin() + 1, common.begin(), common.end());
    return args;
  };
  ProcessResult r = holotrace(withCommon({"render", "--quilt", "--layout", "quilt", "-o", dir.path() / "take.png"}));
  ASSERT_EQ(r.exitCode, 0) << r.err << r.out;
  r = holotrace(withCommon({"render", "-o", dir.path() / "direct.png"}));
  ASSERT_EQ(r.exitCode, 0) << r.err << r.out;
  const fs::path quilt = dir.path() / "take_qs8x6a1.5.png";
  ASSERT_TRUE(fs::exists(quilt));

  double db[3] = {};
  const char* filters[3] = {"vendor", "centred", "nearest"};
  for (int f = 0; f < 3; ++f) {
    const fs::path panel = dir.path() / (std::string("panel_") + filters[f] + ".png");
    r = holotrace({"interleave", "--display", display, "--quilt", quilt, "-o", panel, "--filter", filters[f]});
    ASSERT_EQ(r.exitCode, 0) << r.err << r.out;
    EXPECT_THAT(r.out, HasSubstr("8x6 views of 96x64 (layout from the file name"));
    db[f] = psnr8(panel, dir.path() / "direct.png");
    std::printf("interleaved quilt vs direct render, %s: %.2f dB\n", filters[f], db[f]);
  }
  EXPECT_GT(db[0], 40.0);
  EXPECT_GT(db[1], db[0]);  // the centred lerp is the better filter
  EXPECT_GT(db[2], 39.8);

  // Renamed, the quilt's embedded metadata still gives its layout, and the panel is the same.
  fs::copy_file(quilt, dir.path() / "renamed.png");
  r = holotrace(
      {"interleave", "--display", display, "--quilt", dir.path() / "renamed.png", "-o", dir.path() / "panel_meta.png"});
  ASSERT_EQ(r.exitCode, 0) << r.err << r.out;
  EXPECT_THAT(r.out, HasSubstr("layout from the metadata"));
  EXPECT_EQ(frame_io::readImageFile(dir.path() / "panel_meta.png").rgba,
            frame_io::readImageFile(dir.path() / "panel_vendor.png").rgba);
}

void writeQuilt(const fs::path& path, std::uint32_t w, std::uint32_t h,
                const frame_io::ImageAttributes& attributes = {}) {
  const std::vector<float> rgba(std::size_t(w) * h * 4, 0.5f);
  const frame_io::OutputFile file{path,
                                  frame_io::encodeImage({w, h, rgba}, frame_io::ImageFormat::Png8Srgb, attributes)};
  frame_io::writeFilesAtomically({&file, 1});
}

TEST(CliInterleave, QuiltsThatCannotFitFailNamingTheValue) {
  ht::test::TempDirectory dir;
  struct Case {
    std::string file;
    std::vector<std::string> extra;
    std::string display;
    std::string message;
  };
  writeQuilt(dir.path() / "wide_qs8x6a1.777.png", 64, 48);
  writeQuilt(dir.path() / "holiday.png", 64, 48);
  writeQuilt(dir.path() / "tiny_qs64x48a0.75.png", 64, 48);
  const std::vector<Case> cases = {
      {"wide_qs8x6a1.777.png", {}, "builtin:portrait", "field 'quilt aspect' = 1.777"},
      {"holiday.png", {}, "builtin:portrait", "field 'quilt name'"},
      {"tiny_qs64x48a0.75.png", {}, "builtin:portrait", "field 'quilt size'"},
      {"holiday.png", {"--columns", "80", "--rows", "60"}, "builtin:portrait", "field 'quiltWidth' = 64"},
      {"wide_qs8x6a1.777.png", {}, "builtin:holovizio-wall-70", "field 'model' = projector-array"},
      {"missing_qs8x6a0.75.png", {}, "builtin:portrait", "missing_qs8x6a0.75.png"},
  };
  for (const Case& c : cases) {
    std::vector<std::string> args = {
        "interleave", "--display", c.display, "--quilt", dir.path() / c.file, "-o", dir.path() / "out" / "panel.png"};
    args.insert(args.end(), c.extra.begin(), c.extra.end());
    const ProcessResult r = holotrace(args);
    EXPECT_EQ(r.exitCode, 1) << c.file << ": " << r.err;
    EXPECT_THAT(r.err, HasSubstr(c.message)) << c.file;
    EXPECT_FALSE(fs::exists(dir.path() / "out" / "panel.png")) << c.file;
  }
  const ProcessResult usage = holotrace({"interleave", "--display", "builtin:portrait", "--quilt",
                                         dir.path() / "holiday.png", "-o", dir.path() / "panel.jpg"});
  EXPECT_EQ(usage.exitCode, 2);
  EXPECT_THAT(usage.err, HasSubstr("'-o' = "));
}

// ---- holotrace simulate ---------------------------------------------------------------------------------------------

std::vector<float> rowSlice(const frame_io::ImageFile& image, std::uint32_t x0, std::uint32_t w) {
  std::vector<float> out;
  for (std::uint32_t row = 0; row < image.height; ++row) {
    const auto begin = image.rgba.begin() + std::ptrdiff_t((std::size_t(row) * image.width + x0) * 4);
    out.insert(out.end(), begin, begin + std::ptrdiff_t(w) * 4);
  }
  return out;
}

// One eye gives a panel-sized view; a sweep of 3 puts 3 views side by side, the middle one the default eye's (the
// middle of the cone); the same panel seen from two different eyes differs.
TEST(CliSimulate, OneEyeAndASweepOfALenticularPanel) {
  ht::test::TempDirectory dir;
  const fs::path display = writeSmallPanel(dir.path());
  ProcessResult r = holotrace(
      {"render", "--display", display, "--scene", "builtin:plain", "--spp", "1", "-o", dir.path() / "panel.png"});
  ASSERT_EQ(r.exitCode, 0) << r.err << r.out;
  r = holotrace({"simulate", "--display", display, "--panel", dir.path() / "panel.png", "-o", dir.path() / "mid.png"});
  ASSERT_EQ(r.exitCode, 0) << r.err << r.out;
  r = holotrace({"simulate", "--display", display, "--panel", dir.path() / "panel.png", "--sweep", "3", "-o",
                 dir.path() / "strip.png"});
  ASSERT_EQ(r.exitCode, 0) << r.err << r.out;
  EXPECT_THAT(r.out, HasSubstr("3 views side by side of 192x128"));
  const frame_io::ImageFile mid = frame_io::readImageFile(dir.path() / "mid.png");
  const frame_io::ImageFile strip = frame_io::readImageFile(dir.path() / "strip.png");
  ASSERT_EQ(mid.width, 192u);
  ASSERT_EQ(mid.height, 128u);
  ASSERT_EQ(strip.width, 3u * 192u);
  ASSERT_EQ(strip.height, 128u);
  EXPECT_EQ(rowSlice(strip, 192, 192), mid.rgba);
  EXPECT_NE(rowSlice(strip, 0, 192), rowSlice(strip, 384, 192));
}

// The `--debug views` phase image seen from the middle of the cone: every screen point sends the eye the middle
// view's phase 0.5, within half a subpixel's phase width (0.16/6 = 0.027) plus 8-bit rounding where the line of sight
// crosses a subpixel of that colour; the rest is crosstalk from the neighbouring subpixels (OPTICS.md §12).
TEST(CliSimulate, PhasePatternSeenFromTheConeCentreIsTheMiddleView) {
  ht::test::TempDirectory dir;
  const fs::path display = writeSmallPanel(dir.path());
  ProcessResult r = holotrace({"render", "--display", display, "--debug", "views", "--exr", dir.path() / "phase.exr"});
  ASSERT_EQ(r.exitCode, 0) << r.err << r.out;
  r = holotrace({"simulate", "--display", display, "--panel", dir.path() / "phase.exr", "-o", dir.path() / "seen.exr"});
  ASSERT_EQ(r.exitCode, 0) << r.err << r.out;
  const frame_io::ImageFile seen = frame_io::readImageFile(dir.path() / "seen.exr");
  std::size_t near = 0, total = 0;
  for (std::size_t i = 0; i < seen.rgba.size(); ++i) {
    if (i % 4 == 3) continue;
    near += std::fabs(seen.rgba[i] - 0.5f) <= 0.03f;
    ++total;
  }
  std::printf("phase within 0.03 of the middle view: %.4f of the subpixels\n", double(near) / double(total));
  EXPECT_GT(double(near) / double(total), 0.99);  // measured 0.9987
}

// Projector images as `render` writes them (x_v00.png ..., or a multiView EXR) are read as one frame.
TEST(CliSimulate, ProjectorImagesFromPerViewPngsOrAMultiViewExr) {
  ht::test::TempDirectory dir;
  const fs::path display = fs::path(HT_TEST_DATA_DIR) / "configs" / "display_projector_small.json";
  // display_projector_small has projectors of two image sizes: the simulator refuses it, naming the projector.
  ProcessResult r =
      holotrace({"simulate", "--display", display, "--panel", dir.path() / "none.png", "-o", dir.path() / "v.png"});
  EXPECT_EQ(r.exitCode, 1);
  EXPECT_THAT(r.err, HasSubstr("projectors[1].image"));

  const fs::path wall = dir.path() / "wall.json";
  std::ofstream(wall) << R"({"name": "wall", "model": "projector-array", "projectorArray": {"screen": {"width": 160,
      "height": 90}, "observerDistance": 300, "angularScattering": "auto", "image": {"width": 32, "height": 18},
      "projectors": [{"position": [-20, 0, -180]}, {"position": [0, 0, -180]}, {"position": [20, 0, -180]}]}})";
  r = holotrace({"render", "--display", wall, "--scene", "builtin:plain", "--spp", "1", "-o", dir.path() / "w.png",
                 "--exr", dir.path() / "w.exr"});
  ASSERT_EQ(r.exitCode, 0) << r.err << r.out;
  for (const char* panel : {"w_v00.png", "w.exr"}) {
    r = holotrace({"simulate", "--display", wall, "--panel", dir.path() / panel, "--sweep", "2", "-o",
                   dir.path() / (std::string(panel) + ".view.png")});
    ASSERT_EQ(r.exitCode, 0) << r.err << r.out;
    const frame_io::ImageFile view = frame_io::readImageFile(dir.path() / (std::string(panel) + ".view.png"));
    EXPECT_EQ(view.width, 2u * 32u) << panel;
    EXPECT_EQ(view.height, 18u) << panel;
  }
  // One projector image alone is not the frame.
  r = holotrace({"simulate", "--display", wall, "--panel", dir.path() / "w_v01.png", "-o", dir.path() / "x.png"});
  EXPECT_EQ(r.exitCode, 1);
  EXPECT_THAT(r.err, HasSubstr("the display shows 3 image(s) of 32x18"));
}

TEST(CliSimulate, BadInputsFailWithoutOutput) {
  ht::test::TempDirectory dir;
  const fs::path display = writeSmallPanel(dir.path());
  writeQuilt(dir.path() / "wrong_size.png", 64, 48);
  const fs::path out = dir.path() / "out" / "view.png";
  struct Case {
    std::vector<std::string> args;
    int exitCode;
    std::string message;
  };
  const std::vector<Case> cases = {
      {{"--display", display, "--panel", dir.path() / "wrong_size.png"}, 1, "the display shows 1 image(s) of 192x128"},
      {{"--display", display, "--panel", dir.path() / "wrong_size.png", "--eye", "0,0,-1"}, 2, "'--eye' = '0,0,-1'"},
      {{"--display", display, "--panel", dir.path() / "wrong_size.png", "--eye", "0,0,5", "--sweep", "3"},
       2,
       "not both"},
      {{"--display", display, "--panel", dir.path() / "wrong_size.png", "--sweep", "1"}, 2, "'--sweep'"},
      {{"--display", fs::path(HT_TEST_DATA_DIR) / "configs" / "display_pinhole.json", "--panel",
        dir.path() / "wrong_size.png"},
       1,
       "field 'model' = pinhole"},
  };
  for (const Case& c : cases) {
    std::vector<std::string> args = {"simulate", "-o", out};
    args.insert(args.end(), c.args.begin(), c.args.end());
    const ProcessResult r = holotrace(args);
    EXPECT_EQ(r.exitCode, c.exitCode) << c.message << ": " << r.err;
    EXPECT_THAT(r.err, HasSubstr(c.message));
    EXPECT_FALSE(fs::exists(out)) << c.message;
  }
}

}  // namespace
}  // namespace ht::cli
