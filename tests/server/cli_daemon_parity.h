// cli_daemon_parity.h - runs the same render request through `holotrace render` (in-process) and the daemon's Capture
// and compares the files byte for byte (tests/server/cli_daemon_parity_test.cpp, cli_daemon_quilt_parity_test.cpp).
#pragma once
#include <filesystem>
#include <string>
#include <vector>

#include "tests/server/server_fixture.h"

namespace ht::server::test {

inline constexpr std::uint32_t kParitySeed = 5;

// The models DaemonFiles lacks (it has tiny = lenticular, rig = capture-grid, wall = projector-array), all small:
// pin (pinhole), lens (integral), obl (oblique), table (ray-table, with its table file).
void writeMoreDisplays(const std::filesystem::path& displays);

// Names of the files in `dir` that start with `stem`, sorted.
std::vector<std::string> filesWithStem(const std::filesystem::path& dir, const std::string& stem);
std::vector<std::uint8_t> fileBytes(const std::filesystem::path& file);

// One display of the test daemon, rendered by both.
struct ParityCase {
  std::string display;    // daemon id: its config is displays/<id>.json, or builtin:NAME
  std::string sceneId;    // the daemon's session of `sceneSpec`
  std::string sceneSpec;  // what the CLI loads
  // 2 samples: their pattern depends on the seed, so a seed the daemon and the CLI disagree on changes the bytes (one
  // sample per pixel of an unlit scene does not).
  std::uint32_t spp = 2;
  bool quiltPath = false;   // RenderRequest.quilt / --quilt
  bool singleView = false;  // the layout changes nothing: one CLI run serves every layout's captures
  std::vector<std::string> layouts = {"auto", "quilt", "views"};
  std::vector<v1::CaptureFormat> formats = {v1::CAPTURE_FORMAT_PNG, v1::CAPTURE_FORMAT_EXR};
};

class ParityRunner {
 public:
  ParityRunner(const DaemonFiles& files, v1::Holotrace::Stub& stub) : files_(files), stub_(stub) {}

  // For each layout: one CLI run writing every format of the case to <cli>/<display>_<layout>_f0000.png/.exr, and one
  // Capture per format named <display>_<layout>; every file the daemon reports must exist from the CLI with the same
  // bytes, and the CLI must write no other file of that stem. A layout the CLI refuses (exit 2) the daemon must refuse
  // (INVALID_ARGUMENT), and neither may write a file. A single-view case runs the CLI for its first layout only.
  void check(const ParityCase& c);

  std::filesystem::path cliDir() const { return files_.dir.path / "cli"; }
  std::size_t compared() const { return compared_; }  // files compared so far

 private:
  int runCli(const ParityCase& c, const std::string& layout, const std::string& stem);
  const DaemonFiles& files_;
  v1::Holotrace::Stub& stub_;
  std::size_t compared_ = 0;
};

}  // namespace ht::server::test
