// end_to_end_test.cpp - the `holotrace` binary as a user runs it (on lavapipe in CI): a real render of the
// Portrait panel, and bad inputs that must fail with exit 1, the file named on stderr, and no output file.
#include <OpenImageIO/imageio.h>
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <fstream>
#include <set>

#include "camera_models/display_config.h"
#include "camera_models/lenticular_params.h"
#include "process_runner.h"
#include "temp_directory.h"

#ifndef HOLOTRACE_EXE
#error "HOLOTRACE_EXE must be defined by tests/cli/CMakeLists.txt"
#endif

namespace ht::cli {
namespace {

namespace fs = std::filesystem;
using ::testing::ElementsAre;
using ::testing::HasSubstr;
using test::ProcessResult;
using test::runProcess;

ProcessResult holotrace(const std::vector<std::string>& args) { return runProcess(HOLOTRACE_EXE, args); }

struct ImageSize {
  int width = 0, height = 0, channels = 0;
  std::size_t distinctPixels = 0;  // of the 8-bit RGB values, to see that something was rendered
};

ImageSize inspect(const fs::path& path) {
  auto in = OIIO::ImageInput::open(path.string());
  if (!in) return {};
  const OIIO::ImageSpec spec = in->spec();
  std::vector<std::uint8_t> pixels(std::size_t(spec.width) * spec.height * spec.nchannels);
  in->read_image(0, 0, 0, spec.nchannels, OIIO::TypeDesc::UINT8, pixels.data());
  std::set<std::uint32_t> distinct;
  for (std::size_t i = 0; i + 2 < pixels.size(); i += spec.nchannels) {
    distinct.insert(std::uint32_t(pixels[i]) << 16 | std::uint32_t(pixels[i + 1]) << 8 | pixels[i + 2]);
  }
  return {spec.width, spec.height, spec.nchannels, distinct.size()};
}

TEST(CliEndToEnd, RendersThePortraitPanelToDefaultNamedPngAndExr) {
  test::TempDirectory dir;
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
  test::TempDirectory dir;
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
  test::TempDirectory dir;
  const fs::path missing = dir.path() / "no-such-display.json";
  const ProcessResult r = holotrace({"render", "--display", missing, "--spp", "1", "--out-dir", dir.path() / "out"});
  EXPECT_EQ(r.exitCode, 1) << r.out;
  EXPECT_THAT(r.err, HasSubstr("no-such-display.json"));
  EXPECT_TRUE(dir.entries().empty());
}

TEST(CliEndToEnd, InvalidDisplayFileExitsOneNamingFileAndField) {
  test::TempDirectory dir;
  const fs::path config = dir.path() / "broken.json";
  std::ofstream(config) << R"({"name": "broken", "model": "lenticular", "spp": 0})";
  const ProcessResult r = holotrace({"render", "--display", config, "-o", dir.path() / "x.png"});
  EXPECT_EQ(r.exitCode, 1) << r.out;
  EXPECT_THAT(r.err, HasSubstr("broken.json"));
  EXPECT_THAT(dir.entries(), ElementsAre("broken.json"));
}

TEST(CliEndToEnd, MissingSceneFileExitsOneNamingItAndWritesNothing) {
  test::TempDirectory dir;
  const ProcessResult r =
      holotrace({"render", "--scene", dir.path() / "no-such-scene.glb", "--spp", "1", "--out-dir", dir.path()});
  EXPECT_EQ(r.exitCode, 1) << r.out;
  EXPECT_THAT(r.err, HasSubstr("no-such-scene.glb"));
  EXPECT_TRUE(dir.entries().empty());
}

TEST(CliEndToEnd, UnwritableOutputFailsBeforeRendering) {
  test::TempDirectory dir;
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

}  // namespace
}  // namespace ht::cli
