// `mpirun -np 2 holotraced` on this machine (shared memory and loopback only) against a single-process holotraced
// with the same displays and scenes: RenderFrame of a lenticular panel (row bands) and of a projector array (views),
// two StreamFrames ticks, a 3-frame Capture and a RenderFrame after UpdateScene moved a node are byte-identical; Status
// lists both ranks with their timings; SIGTERM to rank 0 stops both ranks with status 0; a killed rank 1 ends the job
// on every rank within seconds and the client sees UNAVAILABLE; a rank started with another daemon config is refused at
// start. docs/CLUSTER.md §8.
#include <fcntl.h>
#include <gmock/gmock.h>
#include <gtest/gtest.h>
#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <fstream>
#include <iostream>
#include <iterator>
#include <thread>

#include "tests/cluster/mpirun_launcher.h"
#include "tests/server/server_fixture.h"

namespace ht::server::test {
namespace {

namespace fs = std::filesystem;
using Clock = std::chrono::steady_clock;
using ::testing::HasSubstr;

// A child process (exec'ed with `argv`), its output in `log`; killed at destruction if still running.
class Child {
 public:
  Child(const std::vector<std::string>& argv, const fs::path& log) : log_(log) {
    std::vector<char*> args;  // built before fork: the child of a multithreaded parent may only exec
    for (const std::string& a : argv) args.push_back(const_cast<char*>(a.c_str()));
    args.push_back(nullptr);
    const int fd = ::open(log.c_str(), O_WRONLY | O_CREAT | O_TRUNC | O_CLOEXEC, 0600);
    pid_ = ::fork();
    if (pid_ == 0) {
      ::setpgid(0, 0);  // its own group: the destructor ends mpirun and its ranks by the group id
      ::dup2(fd, 1);
      ::dup2(fd, 2);
      ::execv(args[0], args.data());
      ::_exit(127);
    }
    ::close(fd);
  }
  ~Child() {
    if (pid_ > 0 && !exited_) {
      ::kill(-pid_, SIGKILL);
      ::waitpid(pid_, nullptr, 0);
    }
  }
  // Exit status (128 + signal when killed), or -1 if it did not exit within `timeout`.
  int waitExit(std::chrono::seconds timeout) {
    for (const auto deadline = Clock::now() + timeout; Clock::now() < deadline;) {
      int status = 0;
      if (::waitpid(pid_, &status, WNOHANG) == pid_) {
        exited_ = true;
        return WIFEXITED(status) ? WEXITSTATUS(status) : 128 + WTERMSIG(status);
      }
      std::this_thread::sleep_for(std::chrono::milliseconds(20));
    }
    return -1;
  }
  std::string output() const {
    std::ifstream in(log_);
    return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
  }

 private:
  fs::path log_;
  pid_t pid_ = -1;
  bool exited_ = false;
};

// A process that exists and is not a zombie (an ended rank waits to be reaped by init for a moment).
bool processAlive(std::uint32_t pid) {
  if (::kill(static_cast<pid_t>(pid), 0) != 0) return false;
  std::ifstream stat("/proc/" + std::to_string(pid) + "/stat");
  std::string text{std::istreambuf_iterator<char>(stat), std::istreambuf_iterator<char>()};
  const auto close = text.rfind(')');
  return close == std::string::npos || close + 2 >= text.size() || text[close + 2] != 'Z';
}

// Waits up to `timeout` for `pid` to end; true when it did.
bool ends(std::uint32_t pid, std::chrono::seconds timeout) {
  for (const auto deadline = Clock::now() + timeout; Clock::now() < deadline;) {
    if (!processAlive(pid)) return true;
    std::this_thread::sleep_for(std::chrono::milliseconds(20));
  }
  return !processAlive(pid);
}

std::string fileBytes(const fs::path& path) {
  std::ifstream in(path, std::ios::binary);
  return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

class ClusterDaemon : public ::testing::Test {
 protected:
  // The launch environment every cluster test uses (tests/cluster/mpirun_launcher.h): as root, no leak check in the
  // ranks under ASan, one Mesa shader cache for the daemons of this program.
  static void SetUpTestSuite() { shaderCache_ = ht::test::prepareMpirunEnvironment(); }
  static void TearDownTestSuite() {
    std::error_code ignored;
    fs::remove_all(shaderCache_, ignored);
  }
  static inline fs::path shaderCache_;

  // A daemon config over the fixture's displays and scenes, its own socket and output root.
  fs::path writeConfig(const std::string& name, const std::string& extra = "") const {
    const fs::path config = files_.dir.path / (name + ".json");
    writeText(config, R"({"displays_dir": "displays", "scene_root": "scenes", "output_root": "out-)" + name +
                          R"(", "listen": ["unix:)" + socketOf(name).string() +
                          R"("], "devices": {"scan": false}, "limits": {"max_capture_frames": 10})" + extra + "}");
    fs::create_directories(files_.dir.path / ("out-" + name));
    return config;
  }
  fs::path socketOf(const std::string& name) const { return files_.dir.path / (name + ".sock"); }

  std::unique_ptr<Child> startSingle(const std::string& name) {
    return std::make_unique<Child>(std::vector<std::string>{HOLOTRACED_EXE, "--config", writeConfig(name).string()},
                                   files_.dir.path / (name + ".log"));
  }
  // mpirun under a watchdog, as tests/cluster/mpirun_test.cpp (mpirun was once seen to outlive its ranks).
  std::unique_ptr<Child> startMpirun(const std::string& name, std::vector<std::string> programs) {
    std::vector<std::string> argv = {"/usr/bin/timeout", "-s", "KILL", "150", MPIEXEC_EXE};
    argv.insert(argv.end(), ht::test::kLauncherFlags.begin(), ht::test::kLauncherFlags.end());
    argv.insert(argv.end(), programs.begin(), programs.end());
    return std::make_unique<Child>(argv, files_.dir.path / (name + ".log"));
  }
  std::unique_ptr<Child> startTwoRanks(const std::string& name) {
    return startMpirun(name, {"-np", "2", HOLOTRACED_EXE, "--config", writeConfig(name).string()});
  }

  // The daemon's stub once Status answers; null after 60 s.
  std::unique_ptr<v1::Holotrace::Stub> waitReady(const std::string& name) const {
    for (const auto deadline = Clock::now() + std::chrono::seconds(60); Clock::now() < deadline;) {
      if (fs::exists(socketOf(name))) {
        auto stub = connect("unix:" + socketOf(name).string());
        grpc::ClientContext context;
        context.set_deadline(std::chrono::system_clock::now() + std::chrono::seconds(5));
        v1::StatusResponse status;
        if (stub->Status(&context, {}, &status).ok()) return stub;
      }
      std::this_thread::sleep_for(std::chrono::milliseconds(50));
    }
    return nullptr;
  }

  DaemonFiles files_;
};

v1::StatusResponse statusOf(v1::Holotrace::Stub& stub) {
  grpc::ClientContext context;
  context.set_deadline(std::chrono::system_clock::now() + std::chrono::seconds(10));
  v1::StatusResponse status;
  EXPECT_TRUE(stub.Status(&context, {}, &status).ok());
  return status;
}

v1::SceneHandle sceneOf(v1::Holotrace::Stub& stub) {
  v1::SceneHandle handle;
  const grpc::Status s = loadScene(stub, "builtin:showcase", &handle);  // glass: its Fresnel choice per target
  EXPECT_TRUE(s.ok()) << s.error_message();
  return handle;
}

v1::RenderRequest withScene(v1::RenderRequest request, const std::string& sceneId) {
  request.set_scene_id(sceneId);
  return request;
}

std::vector<std::uint8_t> frameOf(v1::Holotrace::Stub& stub, const v1::RenderRequest& request) {
  ReceivedFrame frame;
  const grpc::Status s = renderOne(stub, request, &frame);
  EXPECT_TRUE(s.ok()) << s.error_message();
  EXPECT_FALSE(frame.bytes.empty());
  return frame.bytes;
}

std::vector<std::string> captureOf(v1::Holotrace::Stub& stub, const v1::RenderRequest& render, std::uint32_t frames) {
  grpc::ClientContext context;
  context.set_deadline(std::chrono::system_clock::now() + std::chrono::seconds(120));
  v1::CaptureRequest request;
  *request.mutable_render() = render;
  request.set_name("seq");
  request.set_frames(frames);
  auto reader = stub.Capture(&context, request);
  std::vector<std::string> files;
  v1::CaptureProgress progress;
  while (reader->Read(&progress)) files.push_back(progress.file());
  const grpc::Status s = reader->Finish();
  EXPECT_TRUE(s.ok()) << s.error_message();
  return files;
}

// The first `count` frames of a StreamFrames call (seed + tick), then cancelled.
std::vector<std::vector<std::uint8_t>> streamOf(v1::Holotrace::Stub& stub, const v1::RenderRequest& render, int count) {
  grpc::ClientContext context;
  context.set_deadline(std::chrono::system_clock::now() + std::chrono::seconds(60));
  v1::StreamRequest request;
  *request.mutable_render() = render;
  request.set_frames_per_second(1);  // tick k has seed + k while a frame takes < 1 s (a late tick is skipped)
  // Independent frames, the default under mpirun (every rank renders a share); a single daemon defaults to
  // progressive accumulation, so the comparison names the mode.
  request.set_mode(v1::STREAM_MODE_INDEPENDENT);
  auto reader = stub.StreamFrames(&context, request);
  std::vector<std::vector<std::uint8_t>> frames;
  ReceivedFrame frame;
  while (static_cast<int>(frames.size()) < count && readFrame(*reader, frame)) frames.push_back(frame.bytes);
  context.TryCancel();
  while (readFrame(*reader, frame)) {}
  reader->Finish();
  return frames;
}

void moveFirstNode(v1::Holotrace::Stub& stub, const std::string& sceneId, const std::string& node) {
  grpc::ClientContext context;
  context.set_deadline(std::chrono::system_clock::now() + std::chrono::seconds(60));
  v1::UpdateSceneRequest request;
  request.set_scene_id(sceneId);
  v1::NodeTransform& move = *request.add_nodes();
  move.set_node(node);
  for (const double v : {1.0, 0.0, 0.0, 0.0, 0.0, 1.0, 0.0, 0.0, 0.0, 0.0, 1.0, 0.0, 0.15, 0.1, 0.0, 1.0})
    move.add_world(v);
  v1::UpdateSceneResponse response;
  const grpc::Status s = stub.UpdateScene(&context, request, &response);
  EXPECT_TRUE(s.ok()) << s.error_message();
}

TEST_F(ClusterDaemon, FramesCapturesAndEditsAreByteIdenticalToOneProcessAndStatusShowsBothRanks) {
  const auto single = startSingle("single");
  const auto job = startTwoRanks("mpi");
  const auto one = waitReady("single");
  const auto two = waitReady("mpi");
  ASSERT_TRUE(one) << single->output();
  ASSERT_TRUE(two) << job->output();
  const v1::SceneHandle handle = sceneOf(*one);
  const std::string sceneOne = handle.scene_id(), sceneTwo = sceneOf(*two).scene_id();
  ASSERT_FALSE(handle.nodes().empty());

  v1::RenderRequest panel = tinyRequest("");  // 96x64 lenticular: row bands
  panel.set_seed(7);
  const std::vector<std::uint8_t> panelOne = frameOf(*one, withScene(panel, sceneOne));
  EXPECT_TRUE(panelOne == frameOf(*two, withScene(panel, sceneTwo))) << "panel frame";
  v1::RenderRequest wall = tinyRequest("");  // 3 projectors: one unit per view
  wall.set_display_id("wall");
  const std::vector<std::uint8_t> wallOne = frameOf(*one, withScene(wall, sceneOne));
  EXPECT_TRUE(wallOne == frameOf(*two, withScene(wall, sceneTwo))) << "projector frame";

  const auto streamedOne = streamOf(*one, withScene(panel, sceneOne), 2);
  ASSERT_EQ(streamedOne.size(), 2u);
  EXPECT_TRUE(streamedOne == streamOf(*two, withScene(panel, sceneTwo), 2)) << "streamed frames";

  const std::vector<std::string> filesOne = captureOf(*one, withScene(panel, sceneOne), 3);
  const std::vector<std::string> filesTwo = captureOf(*two, withScene(panel, sceneTwo), 3);
  ASSERT_EQ(filesOne.size(), 3u);
  ASSERT_EQ(filesTwo, filesOne);
  for (const std::string& file : filesOne) {
    const std::string expected = fileBytes(files_.dir.path / "out-single" / file);
    ASSERT_FALSE(expected.empty()) << file;
    EXPECT_TRUE(fileBytes(files_.dir.path / "out-mpi" / file) == expected) << file;
  }

  moveFirstNode(*one, sceneOne, handle.nodes(0));  // a new scene version: bytes go to rank 1 again
  moveFirstNode(*two, sceneTwo, handle.nodes(0));
  const std::vector<std::uint8_t> movedOne = frameOf(*one, withScene(panel, sceneOne));
  EXPECT_TRUE(movedOne == frameOf(*two, withScene(panel, sceneTwo))) << "frame after UpdateScene";
  EXPECT_FALSE(movedOne == panelOne) << "the node did not move";

  const v1::StatusResponse status = statusOf(*two);
  ASSERT_EQ(status.ranks_size(), 2);
  std::uint32_t lastUnits = 0;
  for (int r = 0; r < 2; ++r) {
    const v1::RankStatus& rank = status.ranks(r);
    EXPECT_EQ(rank.rank(), static_cast<std::uint32_t>(r));
    EXPECT_FALSE(rank.host().empty());
    EXPECT_TRUE(processAlive(rank.pid()));
    EXPECT_EQ(rank.state(), r == 0 ? "serving" : "ready");
    EXPECT_GE(rank.last_idle_ms(), 0.0);
    EXPECT_GE(rank.total_busy_ms(), rank.last_busy_ms());
    lastUnits += rank.last_units();
  }
  EXPECT_EQ(status.ranks(0).pid(), status.pid());
  EXPECT_GT(status.ranks(1).total_units(), 0u) << "rank 1 rendered nothing in 6 frames";
  EXPECT_GT(status.ranks(1).total_busy_ms(), 0.0);
  EXPECT_GE(status.cluster().frames(), 8u);  // 2 frames, 2+ streamed, 3 captured, 1 after the edit
  EXPECT_EQ(lastUnits, status.cluster().work_units());
  EXPECT_EQ(status.cluster().scene_broadcasts(), 2u);  // the loaded scene, then the edited one
  EXPECT_GT(status.cluster().last_gather_bytes() + status.ranks(0).last_units(), 0u);
  EXPECT_GT(status.cluster().last_frame_ms(), 0.0);
  EXPECT_EQ(statusOf(*one).ranks_size(), 0);  // a single process has no ranks

  // SIGTERM to rank 0: it stops the other rank, and the job ends cleanly.
  const auto rank1 = status.ranks(1).pid();
  ::kill(static_cast<pid_t>(status.pid()), SIGTERM);
  EXPECT_EQ(job->waitExit(std::chrono::seconds(30)), 0) << job->output();
  EXPECT_TRUE(ends(rank1, std::chrono::seconds(5)));
  EXPECT_THAT(job->output(), HasSubstr("rank 1 of 2: stopped by rank 0"));
}

TEST_F(ClusterDaemon, AKilledRankEndsTheDaemonOnEveryRankWithinSeconds) {
  const auto job = startTwoRanks("mpi");
  const auto stub = waitReady("mpi");
  ASSERT_TRUE(stub) << job->output();
  const std::string scene = sceneOf(*stub).scene_id();
  frameOf(*stub, tinyRequest(scene));
  const v1::StatusResponse status = statusOf(*stub);
  ASSERT_EQ(status.ranks_size(), 2);
  const auto start = Clock::now();
  ::kill(static_cast<pid_t>(status.ranks(1).pid()), SIGKILL);
  const int exit = job->waitExit(std::chrono::seconds(60));
  EXPECT_NE(exit, 0) << job->output();
  EXPECT_NE(exit, -1) << "still running 60 s after rank 1 was killed";
  EXPECT_TRUE(ends(status.pid(), std::chrono::seconds(5))) << "rank 0 outlived mpirun";
  const double seconds = std::chrono::duration<double>(Clock::now() - start).count();
  EXPECT_LT(seconds, 15.0);
  std::cout << "job ended " << seconds << " s after rank 1 was killed\n";
  ReceivedFrame frame;
  const grpc::Status after = renderOne(*stub, tinyRequest(scene), &frame);
  EXPECT_EQ(after.error_code(), grpc::StatusCode::UNAVAILABLE) << after.error_message();
}

TEST_F(ClusterDaemon, ARankDyingInsideAFrameEndsTheJobAndTheClientSeesUnavailable) {
  // Rank 1 raises SIGKILL after rendering its first unit, before sending it (cluster/work_dispatch.h): rank 0 is then
  // waiting for those pixels inside a RenderFrame.
  const auto job = startMpirun(
      "mpi", {"-x", "HOLOTRACE_TEST_KILL_RANK=1", "-np", "2", HOLOTRACED_EXE, "--config", writeConfig("mpi").string()});
  const auto stub = waitReady("mpi");
  ASSERT_TRUE(stub) << job->output();
  const std::string scene = sceneOf(*stub).scene_id();
  const auto start = Clock::now();
  grpc::Status failed;
  for (int frame = 0; frame < 20 && failed.ok(); ++frame) {  // until rank 1 gets a unit (rank 0 may take all)
    v1::RenderRequest request = tinyRequest(scene);
    request.set_display_id("wall");  // one unit per projector
    ReceivedFrame received;
    failed = renderOne(*stub, request, &received);
  }
  EXPECT_EQ(failed.error_code(), grpc::StatusCode::UNAVAILABLE) << failed.error_message();
  const int exit = job->waitExit(std::chrono::seconds(60));
  EXPECT_NE(exit, 0) << job->output();
  EXPECT_NE(exit, -1) << "still running 60 s after rank 1 died";
  EXPECT_LT(Clock::now() - start, std::chrono::seconds(20)) << job->output();
}

TEST_F(ClusterDaemon, ARankWithAnotherDaemonConfigIsRefusedAtStart) {
  const fs::path same = writeConfig("mpi");
  const fs::path other = writeConfig("other", R"(, "x_display": ":99")");  // any difference in the file
  const auto job = startMpirun("mpmd", {"-np", "1", HOLOTRACED_EXE, "--config", same.string(), ":", "-np", "1",
                                        HOLOTRACED_EXE, "--config", other.string()});
  EXPECT_NE(job->waitExit(std::chrono::seconds(60)), 0);
  EXPECT_THAT(job->output(), HasSubstr("rank 1 has another render settings than rank 0"));
  EXPECT_THAT(job->output(), HasSubstr("--config"));
  EXPECT_FALSE(fs::exists(socketOf("mpi")));
}

}  // namespace
}  // namespace ht::server::test
