// progressive_stream_test.cpp - progressive StreamFrames through the daemon (issue 16, docs/REUSE.md §1-§2 and §5,
// docs/SERVICE.md §4.1): a stream accumulates until the stop rule holds, then sends nothing more
// and renders nothing (the daemon's CPU goes idle); a new caller of the same stream gets the converged frame at once;
// an UpdateScene during accumulation restarts the sums, and the converged frame equals that of a fresh stream of the
// edited scene bit for bit (no frame mixes samples of two scene versions); over limits.max_accumulator_bytes the call
// fails with RESOURCE_EXHAUSTED naming the limit.
#include <gtest/gtest.h>

#include <chrono>
#include <iostream>
#include <thread>

#include "tests/server/server_fixture.h"

namespace ht::server::test {
namespace {

using Clock = std::chrono::steady_clock;

class ProgressiveStreamTest : public InProcessDaemonTest<ProgressiveStreamTest> {
 protected:
  v1::StreamRequest progressiveRequest(const std::string& sceneId) const {
    v1::StreamRequest request;
    *request.mutable_render() = tinyRequest(sceneId, v1::PIXEL_FORMAT_RGBA16F);
    request.mutable_render()->set_spp(2);
    request.set_frames_per_second(100);
    request.set_target_error(0.05f);
    request.set_max_spp(16);
    return request;
  }
  v1::StatusResponse status() const {
    grpc::ClientContext context;
    v1::StatusResponse response;
    EXPECT_TRUE(stub_->Status(&context, {}, &response).ok());
    return response;
  }
};

// Reads frames until one is converged (at most `limit`); the frames read.
std::vector<ReceivedFrame> readUntilConverged(grpc::ClientReaderInterface<v1::FramePart>& reader, int limit) {
  std::vector<ReceivedFrame> frames;
  ReceivedFrame frame;
  while (static_cast<int>(frames.size()) < limit && readFrame(reader, frame)) {
    frames.push_back(frame);
    if (frame.header.state() == v1::STREAM_STATE_CONVERGED) break;
  }
  return frames;
}

// Frames that arrive on `reader` within `duration` (the call is cancelled then).
int framesWithin(grpc::ClientContext& context, grpc::ClientReaderInterface<v1::FramePart>& reader,
                 std::chrono::milliseconds duration) {
  std::thread cancel([&] {
    std::this_thread::sleep_for(duration);
    context.TryCancel();
  });
  int frames = 0;
  ReceivedFrame frame;
  while (readFrame(reader, frame)) ++frames;
  cancel.join();
  reader.Finish();
  return frames;
}

TEST_F(ProgressiveStreamTest, ConvergesThenSendsAndRendersNothingAndANewCallerGetsTheFrameAtOnce) {
  grpc::ClientContext context;
  auto reader = stub_->StreamFrames(&context, progressiveRequest(sceneId_));
  const std::vector<ReceivedFrame> frames = readUntilConverged(*reader, 64);
  ASSERT_FALSE(frames.empty());
  const ReceivedFrame& last = frames.back();
  ASSERT_EQ(last.header.state(), v1::STREAM_STATE_CONVERGED) << frames.size() << " frames";
  EXPECT_EQ(frames.front().header.state(), v1::STREAM_STATE_ACCUMULATING);
  EXPECT_EQ(frames.front().header.accumulated_spp(), 2u);
  for (std::size_t i = 1; i < frames.size(); ++i) {
    EXPECT_GE(frames[i].header.accumulated_spp(), frames[i - 1].header.accumulated_spp());
  }
  EXPECT_LE(last.header.accumulated_spp_max(), 16u);
  EXPECT_EQ(last.header.unconverged_targets(), 0u);

  const v1::StatusResponse converged = status();
  ASSERT_EQ(converged.streams_size(), 1);
  EXPECT_EQ(converged.streams(0).state(), v1::STREAM_STATE_CONVERGED);
  EXPECT_EQ(converged.streams(0).clients(), 1u);
  EXPECT_GT(converged.accumulator_bytes(), 0u);

  // Converged: at 100 fps for 1.5 s nothing is rendered or sent, and the process (daemon + this client) is idle.
  const auto t0 = Clock::now();
  std::thread second([&] {
    // Meanwhile a second caller of the same stream gets the converged frame at once, rendered by nobody.
    auto stub = connect(files_->socketAddress());
    grpc::ClientContext secondContext;
    auto secondReader = stub->StreamFrames(&secondContext, progressiveRequest(sceneId_));
    ReceivedFrame frame;
    ASSERT_TRUE(readFrame(*secondReader, frame));
    EXPECT_EQ(frame.header.state(), v1::STREAM_STATE_CONVERGED);
    EXPECT_EQ(frame.bytes, last.bytes);
    secondContext.TryCancel();
    while (readFrame(*secondReader, frame)) {}
    secondReader->Finish();
  });
  second.join();
  const std::uint64_t renderedBefore = status().devices(0).frames_rendered();
  const double cpuBefore = status().cpu_seconds();
  const int more = framesWithin(context, *reader, std::chrono::milliseconds(1500));
  const double seconds = std::chrono::duration<double>(Clock::now() - t0).count();
  const double cpu = status().cpu_seconds() - cpuBefore;
  EXPECT_EQ(more, 0) << "a converged stream kept sending";
  EXPECT_EQ(status().devices(0).frames_rendered(), renderedBefore) << "a converged stream kept rendering";
  std::cout << "after convergence: " << cpu << " s CPU of the process in " << seconds << " s\n";
  EXPECT_LT(cpu, 0.25 * seconds);  // rendering at 100 fps keeps a core busy; idle is a few ms
}

TEST_F(ProgressiveStreamTest, AnEditDuringAccumulationRestartsAndConvergesToTheEditedScenesFrame) {
  v1::UpdateSceneRequest edit;
  edit.set_scene_id(sceneId_);
  v1::NodeTransform& move = *edit.add_nodes();  // a node move: a new scene version (BVH rebuilt)
  move.set_node("teal-box");
  for (int i = 0; i < 16; ++i) move.add_world(i % 5 == 0 ? 1.0 : 0.0);
  move.set_world(13, 0.2);  // lifted by 0.2
  grpc::ClientContext context;
  auto reader = stub_->StreamFrames(&context, progressiveRequest(sceneId_));
  ReceivedFrame frame;
  ASSERT_TRUE(readFrame(*reader, frame));
  ASSERT_TRUE(readFrame(*reader, frame));
  ASSERT_EQ(frame.header.state(), v1::STREAM_STATE_ACCUMULATING);
  ASSERT_EQ(frame.header.accumulated_spp(), 4u);
  {
    grpc::ClientContext editContext;
    v1::UpdateSceneResponse response;
    const grpc::Status updated = stub_->UpdateScene(&editContext, edit, &response);
    ASSERT_TRUE(updated.ok()) << updated.error_code() << " " << updated.error_message();
  }
  // At most one frame in flight still shows the old scene; then the sums restart at the frame's spp.
  bool restarted = false;
  for (int i = 0; i < 3 && !restarted; ++i) {
    ASSERT_TRUE(readFrame(*reader, frame));
    restarted = frame.header.accumulated_spp() == 2u;
  }
  EXPECT_TRUE(restarted) << "the accumulation went on across the edit";
  std::vector<ReceivedFrame> frames = readUntilConverged(*reader, 64);
  ASSERT_FALSE(frames.empty());
  ASSERT_EQ(frames.back().header.state(), v1::STREAM_STATE_CONVERGED);
  context.TryCancel();
  while (readFrame(*reader, frame)) {}
  reader->Finish();

  // A fresh session of the same scene with the same edit, streamed from the start, converges to the same bits.
  v1::SceneHandle fresh;
  ASSERT_TRUE(loadScene(*stub_, "builtin:plain", &fresh).ok());
  edit.set_scene_id(fresh.scene_id());
  {
    grpc::ClientContext editContext;
    v1::UpdateSceneResponse response;
    const grpc::Status updated = stub_->UpdateScene(&editContext, edit, &response);
    ASSERT_TRUE(updated.ok()) << updated.error_code() << " " << updated.error_message();
  }
  grpc::ClientContext freshContext;
  auto freshReader = stub_->StreamFrames(&freshContext, progressiveRequest(fresh.scene_id()));
  const std::vector<ReceivedFrame> reference = readUntilConverged(*freshReader, 64);
  ASSERT_FALSE(reference.empty());
  ASSERT_EQ(reference.back().header.state(), v1::STREAM_STATE_CONVERGED);
  EXPECT_EQ(reference.back().header.accumulated_spp(), frames.back().header.accumulated_spp());
  EXPECT_TRUE(reference.back().bytes == frames.back().bytes) << "the edited stream mixed samples of two scene versions";
  freshContext.TryCancel();
  while (readFrame(*freshReader, frame)) {}
  freshReader->Finish();
}

// A move of `node` to the world matrix that lifts it by `height` (column-major, translation in elements 12-14).
v1::UpdateSceneRequest liftNode(const std::string& sceneId, const std::string& node, double height) {
  v1::UpdateSceneRequest edit;
  edit.set_scene_id(sceneId);
  v1::NodeTransform& move = *edit.add_nodes();
  move.set_node(node);
  for (int i = 0; i < 16; ++i) move.add_world(i % 5 == 0 ? 1.0 : 0.0);
  move.set_world(13, height);
  return edit;
}

v1::UpdateSceneRequest liftTealBox(const std::string& sceneId, double height) {
  return liftNode(sceneId, "teal-box", height);
}

// Streams `request` until converged, moves `node` to `height` (liftNode), and checks the stream's answer: the
// converged stream wakes up, only the targets whose recorded paths met the node's old or new bounds start over
// (reset_targets), the others keep their samples, and it converges to the bits of a fresh stream of a session of
// `sceneName` that made only that move.
void expectAMoveRestartsOnlyNearbyTargets(v1::Holotrace::Stub& stub, const v1::StreamRequest& request, double height,
                                          const std::string& sceneName = "builtin:plain",
                                          const std::string& node = "teal-box") {
  grpc::ClientContext context;
  auto reader = stub.StreamFrames(&context, request);
  const std::vector<ReceivedFrame> before = readUntilConverged(*reader, 64);
  ASSERT_FALSE(before.empty());
  ASSERT_EQ(before.back().header.state(), v1::STREAM_STATE_CONVERGED);
  v1::UpdateSceneResponse response;
  {
    grpc::ClientContext editContext;
    ASSERT_TRUE(stub.UpdateScene(&editContext, liftNode(request.render().scene_id(), node, height), &response).ok());
  }
  EXPECT_EQ(response.bvh_instance_updates(), 1u);  // the two-level fast path, no rebuild
  const std::vector<ReceivedFrame> after = readUntilConverged(*reader, 64);
  ASSERT_FALSE(after.empty());
  const v1::FrameHeader& first = after.front().header;
  const std::uint64_t targets = std::uint64_t{kTinyWidth} * kTinyHeight * 3;  // subpixels of the lenticular panel
  EXPECT_GT(first.reset_targets(), 0u);
  EXPECT_LT(first.reset_targets(), targets / 2) << "a small box's move restarted most of the panel";
  EXPECT_EQ(first.accumulated_spp(), 2u);                                      // restarted targets
  EXPECT_GT(first.accumulated_spp_max(), 2u) << "no target kept its samples";  // kept targets
  ASSERT_EQ(after.back().header.state(), v1::STREAM_STATE_CONVERGED);
  context.TryCancel();
  ReceivedFrame frame;
  while (readFrame(*reader, frame)) {}
  reader->Finish();

  v1::SceneHandle fresh;
  ASSERT_TRUE(loadScene(stub, sceneName, &fresh).ok());
  {
    grpc::ClientContext editContext;
    ASSERT_TRUE(stub.UpdateScene(&editContext, liftNode(fresh.scene_id(), node, height), &response).ok());
  }
  v1::StreamRequest freshRequest = request;
  freshRequest.mutable_render()->set_scene_id(fresh.scene_id());
  grpc::ClientContext freshContext;
  auto freshReader = stub.StreamFrames(&freshContext, freshRequest);
  const std::vector<ReceivedFrame> reference = readUntilConverged(*freshReader, 64);
  ASSERT_FALSE(reference.empty());
  ASSERT_EQ(reference.back().header.state(), v1::STREAM_STATE_CONVERGED);
  EXPECT_EQ(reference.back().header.reset_targets(), 0u);
  EXPECT_TRUE(reference.back().bytes == after.back().bytes) << "the partly restarted stream converged elsewhere";
  freshContext.TryCancel();
  while (readFrame(*freshReader, frame)) {}
  freshReader->Finish();
}

// The session's second node move: its renderer is its own, on the two-level BVH, since the first.
TEST_F(ProgressiveStreamTest, ALaterMoveRestartsOnlyNearbyTargetsAndConvergesToTheEditedScenesFrame) {
  v1::SceneHandle scene;
  ASSERT_TRUE(loadScene(*stub_, "builtin:plain", &scene).ok());
  v1::UpdateSceneResponse response;
  {
    grpc::ClientContext editContext;
    ASSERT_TRUE(stub_->UpdateScene(&editContext, liftTealBox(scene.scene_id(), 0.1), &response).ok());
  }
  expectAMoveRestartsOnlyNearbyTargets(*stub_, progressiveRequest(scene.scene_id()), 0.25);
}

// A stream with reuse_after_edits records segment cells from its first frame (docs/REUSE.md §7), so that even the
// session's first node move restarts only the targets near the node. Without the flag that move gives the session
// its own renderer and the accumulation starts over (AnEditDuringAccumulationRestarts... above).
TEST_F(ProgressiveStreamTest, WithReuseAfterEditsTheFirstMoveRestartsOnlyNearbyTargets) {
  v1::SceneHandle scene;
  ASSERT_TRUE(loadScene(*stub_, "builtin:plain", &scene).ok());
  v1::StreamRequest request = progressiveRequest(scene.scene_id());
  request.mutable_render()->set_reuse_after_edits(true);
  expectAMoveRestartsOnlyNearbyTargets(*stub_, request, 0.25);
}

// The same when the session already has its own renderer on the flattened BVH: a reusing RenderFrame of
// builtin:showcase, a static scene the flattened BVH traces faster, made it. The reusing stream moves that renderer
// to the two-level BVH before its first frame.
TEST_F(ProgressiveStreamTest, AReusingStreamMovesTheSessionsFlattenedRendererToTheTwoLevelBvh) {
  v1::SceneHandle scene;
  ASSERT_TRUE(loadScene(*stub_, "builtin:showcase", &scene).ok());
  v1::RenderRequest frame = tinyRequest(scene.scene_id());
  frame.set_reuse_after_edits(true);
  ASSERT_TRUE(renderOne(*stub_, frame).ok());
  v1::StreamRequest request = progressiveRequest(scene.scene_id());
  request.mutable_render()->set_reuse_after_edits(true);
  expectAMoveRestartsOnlyNearbyTargets(*stub_, request, 0.05, "builtin:showcase", "glow-sphere");
}

TEST(ProgressiveStreamLimit, OverTheAccumulatorLimitIsResourceExhaustedNamingTheLimit) {
  DaemonFiles files;
  DaemonConfig config = files.config();
  config.limits.maxAccumulatorBytes = 100'000;  // the tiny display needs 96 x 64 x 3 targets x 64 B = 1,179,648
  Daemon daemon(config, std::cerr);
  daemon.start();
  auto stub = connect(files.socketAddress());
  v1::SceneHandle handle;
  ASSERT_TRUE(loadScene(*stub, "builtin:plain", &handle).ok());
  v1::StreamRequest request;
  *request.mutable_render() = tinyRequest(handle.scene_id());
  request.set_frames_per_second(10);
  grpc::ClientContext context;
  auto reader = stub->StreamFrames(&context, request);
  ReceivedFrame frame;
  EXPECT_FALSE(readFrame(*reader, frame));
  const grpc::Status refused = reader->Finish();
  EXPECT_EQ(refused.error_code(), grpc::StatusCode::RESOURCE_EXHAUSTED);
  EXPECT_NE(refused.error_message().find("limits.max_accumulator_bytes = 100000"), std::string::npos)
      << refused.error_message();
  EXPECT_NE(refused.error_message().find("1179648"), std::string::npos) << refused.error_message();
  // Independent frames need no accumulator.
  request.set_mode(v1::STREAM_MODE_INDEPENDENT);
  grpc::ClientContext independent;
  auto frames = stub->StreamFrames(&independent, request);
  EXPECT_TRUE(readFrame(*frames, frame));
  independent.TryCancel();
  while (readFrame(*frames, frame)) {}
  frames->Finish();
}

}  // namespace
}  // namespace ht::server::test
