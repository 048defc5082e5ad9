// `mpirun -np N holotrace render|capture` on this machine, over shared memory and loopback only, against a plain
// single-process run: the files are byte-identical for 1, 2 and 3 ranks; a killed rank ends the job on every rank
// within seconds and leaves no file; a rank started with another display config is refused before rendering.
// Sizes are tiny: mpirun's start (~0.4 s) and Vulkan's (~0.5 s per rank) dominate, and a shader cache shared by the
// runs of this program keeps lavapipe from compiling the kernels again in every rank.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <chrono>
#include <cstdlib>
#include <fstream>
#include <iterator>

#include "tests/cli/process_runner.h"
#include "tests/cluster/mpirun_launcher.h"
#include "tests/common/temp_directory.h"

namespace ht::test {
namespace {

namespace fs = std::filesystem;
using cli::test::ProcessResult;
using cli::test::runProcess;
using ::testing::HasSubstr;

class ClusterMpirun : public ::testing::Test {
 protected:
  static void SetUpTestSuite() { shaderCache_ = new fs::path(prepareMpirunEnvironment()); }
  static void TearDownTestSuite() {
    std::error_code ignored;
    fs::remove_all(*shaderCache_, ignored);
    delete shaderCache_;
    shaderCache_ = nullptr;
  }

  fs::path writeConfig(const std::string& name, const std::string& json) const {
    const fs::path path = dir_.path() / (name + ".json");
    std::ofstream(path) << json;
    return path;
  }
  static ProcessResult single(const std::vector<std::string>& args) { return runProcess(HOLOTRACE_EXE, args); }
  static ProcessResult mpirun(int ranks, const std::vector<std::string>& args,
                              const std::vector<std::string>& extraFlags = {}) {
    std::vector<std::string> all = kLauncherFlags;
    all.insert(all.end(), extraFlags.begin(), extraFlags.end());
    all.insert(all.end(), {"-np", std::to_string(ranks), HOLOTRACE_EXE});
    all.insert(all.end(), args.begin(), args.end());
    return launch(all);
  }
  static ProcessResult launch(const std::vector<std::string>& mpirunArgs) { return launchMpirun(mpirunArgs); }
  static std::string bytes(const fs::path& path) {
    std::ifstream in(path, std::ios::binary);
    return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
  }
  // Renders `args` + "-o <dir>/frame.png" once alone and with each rank count; every file must match.
  void expectSameFilesAtRankCounts(const std::vector<std::string>& args, const std::vector<std::string>& files,
                                   std::initializer_list<int> rankCounts) {
    const fs::path reference = dir_.path() / "single";
    std::vector<std::string> singleArgs = args;
    singleArgs.insert(singleArgs.end(), {"-o", (reference / "frame.png").string()});
    const ProcessResult r = single(singleArgs);
    ASSERT_EQ(r.exitCode, 0) << r.err << r.out;
    for (const int ranks : rankCounts) {
      const fs::path out = dir_.path() / ("np" + std::to_string(ranks));
      std::vector<std::string> mpiArgs = args;
      mpiArgs.insert(mpiArgs.end(), {"-o", (out / "frame.png").string()});
      const ProcessResult m = mpirun(ranks, mpiArgs);
      ASSERT_EQ(m.exitCode, 0) << "np " << ranks << ": " << m.err << m.out;
      EXPECT_THAT(m.out, HasSubstr("over " + std::to_string(ranks) + " rank"));
      for (const std::string& file : files) {
        const std::string expected = bytes(reference / file);
        ASSERT_FALSE(expected.empty()) << file;
        EXPECT_TRUE(bytes(out / file) == expected) << file << " differs at np " << ranks;
      }
    }
  }

  TempDirectory dir_;
  static fs::path* shaderCache_;
};
fs::path* ClusterMpirun::shaderCache_ = nullptr;

const char* const kTinyLenticular = R"({"name": "tinylent", "model": "lenticular", "spp": 2,
  "calibration": {"configVersion": "3.0", "serial": "T", "pitch": 52.594383239746094, "slope": -7.21152925491333,
    "center": 0.40277382731437683, "viewCone": 40, "invView": 1, "verticalAngle": 0, "DPI": 324, "screenW": 36,
    "screenH": 30, "flipImageX": 0, "flipImageY": 0, "flipSubp": 0, "CellPatternMode": 0, "subpixelCells": []},
  "camera": {"target": "auto", "size": "auto", "fovyDeg": 14, "depthiness": 1.0}})";

// Every mpirun costs seconds on 2 shared cores, so the view-cut frames run at 3 and 2 ranks only: 1 rank goes through
// the same unit path as more (rank 0's render thread), which the panel covers at 1, 2 and 3.
TEST_F(ClusterMpirun, ALenticularPanelCutIntoBandsIsByteIdenticalAtOneTwoAndThreeRanks) {
  // The showcase scene has glass: its random Fresnel choice must not depend on the band either.
  expectSameFilesAtRankCounts({"render", "--display", writeConfig("tinylent", kTinyLenticular).string(), "--scene",
                               "builtin:showcase", "--depth", "2"},
                              {"frame.png"}, {1, 2, 3});
}

TEST_F(ClusterMpirun, AProjectorArrayCutIntoViewsIsByteIdenticalAtThreeRanks) {
  const fs::path config = writeConfig("wall", R"({"name": "wall", "model": "projector-array", "spp": 2,
      "projectorArray": {"screen": {"width": 160, "height": 90}, "observerDistance": 300, "observerHeight": 0,
      "angularScattering": "auto", "image": {"width": 20, "height": 10},
      "projectors": [{"position": [-15, 0, -180]}, {"position": [-5, 0, -180]}, {"position": [5, 0, -180]},
                     {"position": [15, 0, -180]}]}})");
  expectSameFilesAtRankCounts({"render", "--display", config.string(), "--scene", "builtin:showcase", "--depth", "1"},
                              {"frame_v00.png", "frame_v01.png", "frame_v02.png", "frame_v03.png"}, {3});
}

TEST_F(ClusterMpirun, AQuiltOfCaptureViewsIsByteIdenticalAtTwoRanks) {
  const fs::path config = writeConfig("rig", R"({"name": "rig", "model": "capture-grid", "spp": 1,
      "captureGrid": {"columns": 3, "rows": 2, "spacing": [0.1, 0.1], "distance": 3, "window": {"width": 2.4,
      "height": 1.8}, "image": {"width": 16, "height": 12}}})");
  expectSameFilesAtRankCounts({"render", "--display", config.string(), "--scene", "builtin:showcase", "--depth", "1"},
                              {"frame_qs3x2a1.3333333333333333.png", "frame_qs3x2a1.3333333333333333.json"}, {2});
}

TEST_F(ClusterMpirun, ASixFrameCaptureIsByteIdenticalSpreadOverRanksAndWrittenByThem) {
  const std::vector<std::string> args = {"capture", "--display",      writeConfig("tinylent", kTinyLenticular).string(),
                                         "--scene", "builtin:sphere", "--frames",
                                         "6",       "--name",         "spin"};
  const auto run = [&](int ranks, const std::string& dir, bool rankWrites) {
    std::vector<std::string> all = args;
    all.insert(all.end(), {"--out-dir", (dir_.path() / dir).string()});
    if (rankWrites) all.push_back("--rank-writes");
    const ProcessResult r = ranks == 0 ? single(all) : mpirun(ranks, all);
    EXPECT_EQ(r.exitCode, 0) << dir << ": " << r.err << r.out;
  };
  run(0, "single", false);
  run(3, "np3", false);
  run(2, "np2-rank-writes", true);
  for (std::uint32_t f = 0; f < 6; ++f) {
    const std::string name = "spin_f000" + std::to_string(f) + ".png";
    const std::string expected = bytes(dir_.path() / "single" / name);
    ASSERT_FALSE(expected.empty()) << name;
    EXPECT_TRUE(bytes(dir_.path() / "np3" / name) == expected) << name;
    EXPECT_TRUE(bytes(dir_.path() / "np2-rank-writes" / name) == expected) << name;
  }
  EXPECT_EQ(std::distance(fs::directory_iterator(dir_.path() / "np3"), fs::directory_iterator()), 6);
}

TEST_F(ClusterMpirun, AKilledRankEndsTheJobOnEveryRankWithoutAnOutputFile) {
  const fs::path out = dir_.path() / "out";
  const auto start = std::chrono::steady_clock::now();
  // Rank 1 raises SIGKILL after rendering its first band, before sending it (cluster/work_dispatch.h).
  const ProcessResult m = mpirun(3,
                                 {"render", "--display", writeConfig("tinylent", kTinyLenticular).string(), "--scene",
                                  "builtin:sphere", "-o", (out / "frame.png").string()},
                                 {"-x", "HOLOTRACE_TEST_KILL_RANK=1"});
  const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  EXPECT_NE(m.exitCode, 0) << m.out;
  EXPECT_LT(seconds, 60.0);
  EXPECT_FALSE(fs::exists(out / "frame.png"));
  if (fs::exists(out)) { EXPECT_TRUE(fs::is_empty(out)) << "temporary files left in " << out; }
}

TEST_F(ClusterMpirun, ARankWithAnotherDisplayConfigIsRefusedAtStart) {
  const fs::path out = dir_.path() / "out";
  const std::string same = writeConfig("tinylent", kTinyLenticular).string();
  std::string changed = kTinyLenticular;
  changed.replace(changed.find("0.40277382731437683"), 19, "0.50277382731437683");  // another unit's center
  const std::string other = writeConfig("other", changed).string();
  const std::vector<std::string> common = {"render", "--scene", "builtin:sphere", "-o", (out / "frame.png").string()};
  // Two programs in one job (MPMD): rank 0 with one config, rank 1 with the other.
  std::vector<std::string> args = kLauncherFlags;
  for (const std::string& config : {same, other}) {
    if (config == other) args.push_back(":");
    args.insert(args.end(), {"-np", "1", HOLOTRACE_EXE});
    args.insert(args.end(), common.begin(), common.end());
    args.insert(args.end(), {"--display", config});
  }
  const ProcessResult m = launch(args);
  EXPECT_NE(m.exitCode, 0);
  EXPECT_THAT(m.err, HasSubstr("rank 1 has another display config than rank 0"));
  EXPECT_THAT(m.err, HasSubstr("rank 0 of 2"));
  EXPECT_THAT(m.err, HasSubstr("rank 1 of 2"));
  EXPECT_FALSE(fs::exists(out / "frame.png"));
}

}  // namespace
}  // namespace ht::test
