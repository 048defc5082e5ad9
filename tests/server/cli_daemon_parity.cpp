// cli_daemon_parity.cpp - see cli_daemon_parity.h.
#include "tests/server/cli_daemon_parity.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <algorithm>
#include <fstream>
#include <iterator>
#include <sstream>

#include "cli/cli_app.h"
#include "frame_io/ray_table_exr.h"

namespace ht::server::test {
namespace {

namespace fs = std::filesystem;

// A ray table for the "table" display: 24x16 rays converging on the scene (as tests/gpu/frame_pin_test.cpp).
RayTable smallRayTable() {
  RayTable table;
  table.width = 24;
  table.height = 16;
  for (std::uint32_t y = 0; y < table.height; ++y) {
    for (std::uint32_t x = 0; x < table.width; ++x) {
      const float u = (x + 0.5f) / table.width - 0.5f, v = (y + 0.5f) / table.height - 0.5f;
      table.origins.push_back(glm::vec3(u * 0.8f, v * 0.6f, 2.0f));
      table.directions.push_back(glm::normalize(glm::vec3(u * 0.3f, v * 0.2f, -1.0f)));
    }
  }
  table.normalizeDirections();
  return table;
}

v1::CaptureLayout captureLayout(const std::string& layout) {
  if (layout == "quilt") return v1::CAPTURE_LAYOUT_QUILT;
  return layout == "views" ? v1::CAPTURE_LAYOUT_VIEWS : v1::CAPTURE_LAYOUT_AUTO;
}

}  // namespace

void writeMoreDisplays(const fs::path& displays) {
  writeText(displays / "pin.json", R"({"name": "pin", "model": "pinhole", "spp": 1,
    "pinhole": {"width": 48, "height": 32, "fovyDeg": 50}})");
  writeText(displays / "lens.json", R"({"name": "lens", "model": "integral", "spp": 1,
    "integral": {"panelWidth": 48, "panelHeight": 32, "pixelPitch": 0.1, "lensPitch": 1.0, "gap": 3.0,
    "focalLength": 3.0, "viewerDistance": 600, "frontPlane": 600}})");
  writeText(displays / "obl.json", R"({"name": "obl", "model": "oblique", "spp": 1,
    "oblique": {"columns": 3, "rows": 3, "horizontalConeDeg": 40, "verticalConeDeg": 30,
    "image": {"width": 16, "height": 12}}})");
  frame_io::writeRayTableExr(displays / "table_rays.exr", smallRayTable());
  writeText(displays / "table.json", R"({"name": "table", "model": "ray-table", "spp": 1,
    "camera": {"target": [0, 0, 0]}, "rayTable": {"file": "table_rays.exr", "units": 1}})");
}

std::vector<std::string> filesWithStem(const fs::path& dir, const std::string& stem) {
  std::vector<std::string> names;
  if (!fs::is_directory(dir)) return names;
  for (const auto& entry : fs::directory_iterator(dir)) {
    const std::string name = entry.path().filename().string();
    if (name.rfind(stem, 0) == 0) names.push_back(name);
  }
  std::sort(names.begin(), names.end());
  return names;
}

std::vector<std::uint8_t> fileBytes(const fs::path& file) {
  std::ifstream in(file, std::ios::binary);
  return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

int ParityRunner::runCli(const ParityCase& c, const std::string& layout, const std::string& stem) {
  const bool builtin = c.display.rfind("builtin:", 0) == 0;
  std::vector<std::string> args = {
      "render",
      "--display",
      builtin ? c.display : (files_.dir.path / "displays" / (c.display + ".json")).string(),
      "--scene",
      c.sceneSpec,
      "--spp",
      std::to_string(c.spp),
      "--seed",
      std::to_string(kParitySeed),
      "--layout",
      layout};
  for (v1::CaptureFormat format : c.formats) {
    const bool exr = format == v1::CAPTURE_FORMAT_EXR;
    args.push_back(exr ? "--exr" : "-o");
    args.push_back((cliDir() / (stem + "_f0000" + (exr ? ".exr" : ".png"))).string());
  }
  if (c.quiltPath) args.push_back("--quilt");
  std::ostringstream out, err;
  const int code = cli::runCli(args, out, err);
  EXPECT_TRUE(code == cli::kExitOk || code == cli::kExitUsage) << err.str() << out.str();
  return code;
}

void ParityRunner::check(const ParityCase& c) {
  const std::string display = c.display.substr(c.display.find(':') + 1);
  int cliCode = cli::kExitOk;
  for (const std::string& layout : c.layouts) {
    const std::string stem = display + "_" + layout;
    // One view ignores the layout: the CLI runs once, with the first layout, and every capture is compared with that.
    const std::string cliStem = c.singleView ? display + "_" + c.layouts.front() : stem;
    if (!c.singleView || layout == c.layouts.front()) {
      for (const std::string& old : filesWithStem(cliDir(), cliStem + "_"))
        fs::remove(cliDir() / old);  // earlier cases'
      cliCode = runCli(c, layout, cliStem);
    }
    // Each format's Capture replaces the previous one's files of this name (CaptureRequest.overwrite), so the set
    // the daemon wrote is collected from its reports.
    std::vector<std::string> written;
    for (v1::CaptureFormat format : c.formats) {
      v1::RenderRequest render = tinyRequest(c.sceneId);
      render.set_display_id(c.display);
      render.set_seed(kParitySeed);
      render.set_spp(c.spp);
      render.set_quilt(c.quiltPath);
      std::vector<std::string> daemonFiles;
      const grpc::Status status = captureFrame(stub_, stem, render, format, captureLayout(layout), daemonFiles);
      const std::string what = c.display + " layout " + layout + (format == v1::CAPTURE_FORMAT_EXR ? " EXR" : " PNG");
      if (cliCode == cli::kExitUsage) {
        EXPECT_EQ(status.error_code(), grpc::StatusCode::INVALID_ARGUMENT) << what;
        EXPECT_THAT(daemonFiles, ::testing::IsEmpty()) << what;
        continue;
      }
      ASSERT_TRUE(status.ok()) << what << ": " << status.error_message();
      ASSERT_FALSE(daemonFiles.empty()) << what;
      for (const std::string& name : daemonFiles) {
        ASSERT_EQ(name.rfind(stem, 0), 0u) << what << ": " << name;
        const fs::path cliFile = cliDir() / (cliStem + name.substr(stem.size()));
        ASSERT_TRUE(fs::is_regular_file(cliFile)) << what << ": the CLI wrote no " << cliFile.filename();
        EXPECT_TRUE(fileBytes(cliFile) == fileBytes(files_.outputRoot() / name)) << what << ": " << name << " differs";
        ++compared_;
        written.push_back(name);
      }
    }
    if (!c.singleView) {  // the CLI wrote nothing the daemon did not
      std::sort(written.begin(), written.end());
      EXPECT_EQ(filesWithStem(cliDir(), stem + "_"), written) << c.display;
    }
  }
}

}  // namespace ht::server::test
