// server_rpc_test.cpp - holotraced end to end through the C++ stubs: displays, scene loading and upload, frames,
// streams, capture, and misbehaving clients (each answered with the right status while others keep working).
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <chrono>
#include <fstream>
#include <iostream>
#include <limits>
#include <thread>

#include "tests/server/server_fixture.h"

namespace ht::server::test {
namespace {

using grpc::StatusCode;
using Clock = std::chrono::steady_clock;

class ServerTest : public InProcessDaemonTest<ServerTest> {};

TEST_F(ServerTest, ListsBuiltinAndDirectoryDisplays) {
  grpc::ClientContext context;
  v1::ListDisplaysResponse response;
  ASSERT_TRUE(stub_->ListDisplays(&context, {}, &response).ok());
  bool tiny = false, portrait = false;
  for (const auto& d : response.displays()) {
    if (d.id() == "tiny") tiny = d.panel_width() == kTinyWidth && d.panel_height() == kTinyHeight;
    if (d.id() == "builtin:portrait") portrait = d.model() == "lenticular";
  }
  EXPECT_TRUE(tiny);
  EXPECT_TRUE(portrait);
}

TEST_F(ServerTest, GetDisplayReturnsOpticsAndCalibrationVerbatim) {
  grpc::ClientContext context;
  v1::GetDisplayRequest request;
  request.set_display_id("tiny");
  v1::Display display;
  ASSERT_TRUE(stub_->GetDisplay(&context, request, &display).ok());
  EXPECT_EQ(display.calibration_json(), tinyDisplayJson());
  EXPECT_DOUBLE_EQ(display.optics().pitch(), 52.59);
  EXPECT_DOUBLE_EQ(display.optics().view_cone_deg(), 40.0);
  EXPECT_EQ(display.default_spp(), 1u);
}

TEST_F(ServerTest, UnknownDisplayIsNotFound) {
  grpc::ClientContext context;
  v1::GetDisplayRequest request;
  request.set_display_id("no-such-panel");
  v1::Display display;
  EXPECT_EQ(stub_->GetDisplay(&context, request, &display).error_code(), StatusCode::NOT_FOUND);
  auto render = tinyRequest(sceneId_);
  render.set_display_id("no-such-panel");
  EXPECT_EQ(renderOne(*stub_, render).error_code(), StatusCode::NOT_FOUND);
}

TEST_F(ServerTest, LoadByPathSharesTheBvhBetweenSessions) {
  v1::SceneHandle first, second;
  ASSERT_TRUE(loadScene(*stub_, "cube.obj", &first).ok());
  ASSERT_TRUE(loadScene(*stub_, "./cube.obj", &second).ok());
  EXPECT_EQ(first.triangles(), 12u);
  EXPECT_NE(first.scene_id(), second.scene_id());
  EXPECT_TRUE(second.reused());
  EXPECT_GT(first.sah_cost(), 0.0);
}

TEST_F(ServerTest, PathsOutsideTheSceneRootArePermissionDenied) {
  EXPECT_EQ(loadScene(*stub_, "../secret.obj").error_code(), StatusCode::PERMISSION_DENIED);
  EXPECT_EQ(loadScene(*stub_, (files_->dir.path / "secret.obj").string()).error_code(), StatusCode::PERMISSION_DENIED);
  EXPECT_EQ(loadScene(*stub_, "a/../../secret.obj").error_code(), StatusCode::PERMISSION_DENIED);
  std::filesystem::create_symlink(files_->dir.path / "secret.obj", files_->sceneRoot() / "link.obj");
  EXPECT_EQ(loadScene(*stub_, "link.obj").error_code(), StatusCode::PERMISSION_DENIED);
  EXPECT_EQ(loadScene(*stub_, "missing.obj").error_code(), StatusCode::INVALID_ARGUMENT);
}

grpc::Status upload(v1::Holotrace::Stub& stub, const std::string& name, const std::string& bytes,
                    std::uint64_t declared, std::size_t chunkBytes, v1::SceneHandle* handle) {
  grpc::ClientContext context;
  context.set_deadline(std::chrono::system_clock::now() + std::chrono::seconds(60));
  auto writer = stub.UploadScene(&context, handle);
  v1::UploadSceneChunk chunk;
  chunk.mutable_info()->set_file_name(name);
  chunk.mutable_info()->set_total_bytes(declared);
  bool open = writer->Write(chunk);
  for (std::size_t offset = 0; open && offset < bytes.size(); offset += chunkBytes) {
    chunk.set_data(bytes.substr(offset, chunkBytes));
    open = writer->Write(chunk);
  }
  writer->WritesDone();
  return writer->Finish();
}

TEST_F(ServerTest, UploadedBytesLoadAndShareContentWithThePathLoad) {
  v1::SceneHandle byPath, byUpload;
  ASSERT_TRUE(loadScene(*stub_, "cube.obj", &byPath).ok());
  const std::string obj = cubeObj();
  const grpc::Status status = upload(*stub_, "mesh.obj", obj, obj.size(), 50, &byUpload);
  ASSERT_TRUE(status.ok()) << status.error_message();
  EXPECT_EQ(byUpload.triangles(), 12u);
  EXPECT_TRUE(byUpload.reused());
  ASSERT_TRUE(renderOne(*stub_, tinyRequest(byUpload.scene_id())).ok());
}

TEST_F(ServerTest, CorruptOversizedAndMisnamedUploadsAreRefused) {
  v1::SceneHandle handle;
  const std::string junk = "\x01\x02 this is not a glb file at all";
  EXPECT_EQ(upload(*stub_, "bad.glb", junk, junk.size(), 1024, &handle).error_code(), StatusCode::INVALID_ARGUMENT);
  EXPECT_EQ(upload(*stub_, "big.obj", "", 2u << 20, 1024, &handle).error_code(), StatusCode::RESOURCE_EXHAUSTED);
  EXPECT_EQ(upload(*stub_, "../x.obj", "v 0 0 0", 7, 1024, &handle).error_code(), StatusCode::PERMISSION_DENIED);
  EXPECT_EQ(upload(*stub_, "x.exe", "v 0 0 0", 7, 1024, &handle).error_code(), StatusCode::INVALID_ARGUMENT);
  const std::string big(300u << 10, 'v');  // one message over limits.max_message_bytes (256 KiB)
  EXPECT_EQ(upload(*stub_, "m.obj", big, big.size(), big.size(), &handle).error_code(), StatusCode::RESOURCE_EXHAUSTED);
  ASSERT_TRUE(renderOne(*stub_, tinyRequest(sceneId_)).ok());  // the daemon is still fine
}

TEST_F(ServerTest, RenderFrameInEachPixelFormat) {
  ReceivedFrame frame;
  ASSERT_TRUE(renderOne(*stub_, tinyRequest(sceneId_, v1::PIXEL_FORMAT_RGBA8), &frame).ok());
  EXPECT_EQ(frame.header.width(), kTinyWidth);
  EXPECT_EQ(frame.header.height(), kTinyHeight);
  EXPECT_EQ(frame.bytes.size(), std::size_t{kTinyWidth} * kTinyHeight * 4);
  EXPECT_GT(frame.header.stages_size(), 0);
  std::size_t lit = 0;
  for (std::size_t i = 0; i < frame.bytes.size(); i += 4) lit += frame.bytes[i] + frame.bytes[i + 1] > 0;
  EXPECT_GT(lit, frame.bytes.size() / 40);  // the plain scene is visible, not a black frame

  ASSERT_TRUE(renderOne(*stub_, tinyRequest(sceneId_, v1::PIXEL_FORMAT_RGBA16F), &frame).ok());
  EXPECT_EQ(frame.bytes.size(), std::size_t{kTinyWidth} * kTinyHeight * 8);
  const grpc::Status png = renderOne(*stub_, tinyRequest(sceneId_, v1::PIXEL_FORMAT_PNG), &frame);
  ASSERT_TRUE(png.ok()) << png.error_message();
  ASSERT_GT(frame.bytes.size(), 8u);
  EXPECT_EQ(frame.bytes[1], 'P');
  EXPECT_EQ(frame.header.format(), v1::PIXEL_FORMAT_PNG);
}

// A refined frame reports the refine stage; threshold 0 refines every subpixel, so the frame equals the frame at the
// refinement spp (the request's default contrast cannot ask for that: 0 means 0.08).
TEST_F(ServerTest, RenderFrameWithAdaptiveRefinement) {
  auto request = tinyRequest(sceneId_, v1::PIXEL_FORMAT_RGBA16F);
  request.set_spp(1);
  request.set_refine_spp(4);
  ReceivedFrame refined, direct;
  ASSERT_TRUE(renderOne(*stub_, request, &refined).ok());
  bool hasRefineStage = false;
  for (const auto& stage : refined.header.stages()) hasRefineStage = hasRefineStage || stage.name() == "refine";
  EXPECT_TRUE(hasRefineStage);
  request.set_refine_spp(0);
  ASSERT_TRUE(renderOne(*stub_, request, &direct).ok());
  EXPECT_EQ(refined.bytes.size(), direct.bytes.size());
  EXPECT_NE(refined.bytes, direct.bytes);  // the plain scene has edges, and they were refined
  for (float bad : {-0.5f, 1.5f, std::numeric_limits<float>::quiet_NaN()}) {
    request.set_refine_spp(4);
    request.set_refine_contrast(bad);
    const grpc::Status status = renderOne(*stub_, request);
    EXPECT_EQ(status.error_code(), StatusCode::INVALID_ARGUMENT) << bad;
    EXPECT_NE(status.error_message().find("refine_contrast"), std::string::npos);
  }
  request.set_refine_contrast(0.1f);
  request.set_refine_spp(1000);
  EXPECT_EQ(renderOne(*stub_, request).error_code(), StatusCode::INVALID_ARGUMENT);
}

TEST_F(ServerTest, RequestLimitsAnswerPreciseStatuses) {
  auto request = tinyRequest(sceneId_);
  request.set_spp(1000);
  const grpc::Status spp = renderOne(*stub_, request);
  EXPECT_EQ(spp.error_code(), StatusCode::INVALID_ARGUMENT);
  EXPECT_NE(spp.error_message().find("spp"), std::string::npos);
  request = tinyRequest(sceneId_);
  request.set_display_id("builtin:portrait");  // 1536x2048 > limits.max_panel_pixels
  EXPECT_EQ(renderOne(*stub_, request).error_code(), StatusCode::RESOURCE_EXHAUSTED);
  request = tinyRequest("s999-nope");
  EXPECT_EQ(renderOne(*stub_, request).error_code(), StatusCode::NOT_FOUND);
}

TEST_F(ServerTest, UpdateSceneMovesTheCamera) {
  ReceivedFrame before, after;
  ASSERT_TRUE(renderOne(*stub_, tinyRequest(sceneId_), &before).ok());
  grpc::ClientContext context;
  v1::UpdateSceneRequest update;
  update.set_scene_id(sceneId_);
  update.mutable_target()->set_x(100.0);  // look far away from the scene
  update.set_size(0.5);
  v1::UpdateSceneResponse response;
  ASSERT_TRUE(stub_->UpdateScene(&context, update, &response).ok());
  ASSERT_TRUE(renderOne(*stub_, tinyRequest(sceneId_), &after).ok());
  EXPECT_NE(before.bytes, after.bytes);
  grpc::ClientContext bad;
  update.set_size(-1.0);
  EXPECT_EQ(stub_->UpdateScene(&bad, update, &response).error_code(), StatusCode::INVALID_ARGUMENT);
}

v1::NodeTransform translation(const std::string& node, double x, double y, double z) {
  v1::NodeTransform t;
  t.set_node(node);
  for (int k = 0; k < 16; ++k) t.add_world(k % 5 == 0 ? 1.0 : 0.0);
  t.set_world(12, x);
  t.set_world(13, y);
  t.set_world(14, z);
  return t;
}

grpc::Status updateScene(v1::Holotrace::Stub& stub, const v1::UpdateSceneRequest& request,
                         v1::UpdateSceneResponse* response = nullptr) {
  grpc::ClientContext context;
  v1::UpdateSceneResponse local;
  return stub.UpdateScene(&context, request, response ? response : &local);
}

// Moving a node changes this session's frames only: a second session of the same content (one shared BVH) keeps
// rendering the original; the handle names the nodes; refused edits change nothing.
TEST_F(ServerTest, UpdateSceneMovesANodeForThisSessionOnly) {
  v1::SceneHandle other;
  ASSERT_TRUE(loadScene(*stub_, "builtin:plain", &other).ok());
  EXPECT_TRUE(other.reused());
  EXPECT_THAT(std::vector<std::string>(other.nodes().begin(), other.nodes().end()),
              ::testing::ElementsAre("room", "orange-sphere", "teal-box", "violet-sphere", "yellow-box"));
  ReceivedFrame before, otherBefore, moved, otherAfter, refused;
  ASSERT_TRUE(renderOne(*stub_, tinyRequest(sceneId_), &before).ok());
  ASSERT_TRUE(renderOne(*stub_, tinyRequest(other.scene_id()), &otherBefore).ok());
  ASSERT_EQ(before.bytes, otherBefore.bytes);

  v1::UpdateSceneRequest request;
  request.set_scene_id(sceneId_);
  *request.add_nodes() = translation("violet-sphere", -0.5, 0.4, 0.0);
  v1::UpdateSceneResponse response;
  ASSERT_TRUE(updateScene(*stub_, request, &response).ok());
  EXPECT_GT(response.rebuild_ms(), 0.0);
  EXPECT_EQ(response.bvh_layout(), "two-level");  // a moving scene's BVH: sah_cost is that of a flattened BVH only
  ASSERT_TRUE(renderOne(*stub_, tinyRequest(sceneId_), &moved).ok());
  ASSERT_TRUE(renderOne(*stub_, tinyRequest(other.scene_id()), &otherAfter).ok());
  EXPECT_NE(moved.bytes, before.bytes);
  EXPECT_EQ(otherAfter.bytes, otherBefore.bytes);

  // Refused: an unknown node (named in the message), a 15-value matrix, a singular one. The frame stays `moved`.
  v1::UpdateSceneRequest bad;
  bad.set_scene_id(sceneId_);
  *bad.add_nodes() = translation("violet-sphere", 0, 0, 0);
  *bad.add_nodes() = translation("green-cube", 0, 0, 0);
  const grpc::Status unknown = updateScene(*stub_, bad);
  EXPECT_EQ(unknown.error_code(), StatusCode::INVALID_ARGUMENT);
  EXPECT_THAT(unknown.error_message(), ::testing::HasSubstr("'green-cube'"));
  bad.clear_nodes();
  *bad.add_nodes() = translation("teal-box", 0, 0, 0);
  bad.mutable_nodes(0)->mutable_world()->RemoveLast();
  EXPECT_EQ(updateScene(*stub_, bad).error_code(), StatusCode::INVALID_ARGUMENT);
  bad.mutable_nodes(0)->add_world(1.0);
  bad.mutable_nodes(0)->set_world(0, 0.0);  // x axis collapsed
  EXPECT_EQ(updateScene(*stub_, bad).error_code(), StatusCode::INVALID_ARGUMENT);
  ASSERT_TRUE(renderOne(*stub_, tinyRequest(sceneId_), &refused).ok());
  EXPECT_EQ(refused.bytes, moved.bytes);
}

// Node moves take the two-level BVH's fast path (docs/BVH.md §9): the session's first edit builds the two-level BVH,
// every later move refits the moved node and rebuilds the top level, never the whole BVH (counted by the renderer).
TEST_F(ServerTest, UpdateSceneNodeMovesAfterTheFirstDoNotRebuildTheBvh) {
  ReceivedFrame first, second, third;
  v1::UpdateSceneRequest request;
  request.set_scene_id(sceneId_);
  v1::UpdateSceneResponse response;
  *request.add_nodes() = translation("violet-sphere", -0.5, 0.4, 0.0);
  ASSERT_TRUE(updateScene(*stub_, request, &response).ok());
  EXPECT_EQ(response.bvh_layout(), "two-level");
  EXPECT_EQ(response.bvh_full_builds(), 1u);
  EXPECT_EQ(response.bvh_instance_updates(), 0u);
  ASSERT_TRUE(renderOne(*stub_, tinyRequest(sceneId_), &first).ok());
  *request.mutable_nodes(0) = translation("violet-sphere", 0.3, 0.2, 0.1);
  ASSERT_TRUE(updateScene(*stub_, request, &response).ok());
  ASSERT_TRUE(renderOne(*stub_, tinyRequest(sceneId_), &second).ok());
  *request.mutable_nodes(0) = translation("orange-sphere", 0.1, 0.0, 0.2);
  ASSERT_TRUE(updateScene(*stub_, request, &response).ok());
  ASSERT_TRUE(renderOne(*stub_, tinyRequest(sceneId_), &third).ok());
  EXPECT_EQ(response.bvh_layout(), "two-level");
  EXPECT_EQ(response.bvh_full_builds(), 1u) << "a node move rebuilt the BVH";
  EXPECT_EQ(response.bvh_instance_updates(), 2u);
  EXPECT_NE(second.bytes, first.bytes);
  EXPECT_NE(third.bytes, second.bytes);
}

// RenderRequest.reuse_after_edits (docs/REUSE.md §3-§4): after a light edit the frame re-shades the cached hits, after
// a node move it re-traces only the targets near the node, and each equals a full render of the edited scene bit
// for bit. A frame without the flag drops the kept state (the next one records afresh).
TEST_F(ServerTest, FramesReuseTheirPredecessorAfterEdits) {
  v1::SceneHandle showcase;
  ASSERT_TRUE(loadScene(*stub_, "builtin:showcase", &showcase).ok());
  v1::RenderRequest reusing = tinyRequest(showcase.scene_id());
  reusing.set_reuse_after_edits(true);
  const v1::RenderRequest full = tinyRequest(showcase.scene_id());
  v1::UpdateSceneRequest lightEdit;
  lightEdit.set_scene_id(showcase.scene_id());
  v1::LightUpdate* light = lightEdit.add_lights();
  light->set_index(0);
  light->set_intensity(1.0);
  ASSERT_TRUE(updateScene(*stub_, lightEdit).ok());  // the session's first edit: its own renderer from here on
  ReceivedFrame recorded, relit, relitFull, again, moved, movedFull;
  ASSERT_TRUE(renderOne(*stub_, reusing, &recorded).ok());
  EXPECT_EQ(recorded.header.reuse(), v1::FRAME_REUSE_NONE);
  light->set_intensity(3.0);
  ASSERT_TRUE(updateScene(*stub_, lightEdit).ok());
  ASSERT_TRUE(renderOne(*stub_, reusing, &relit).ok());
  ASSERT_TRUE(renderOne(*stub_, full, &relitFull).ok());
  EXPECT_EQ(relit.header.reuse(), v1::FRAME_REUSE_CACHED_PRIMARY_HITS);
  EXPECT_EQ(relitFull.header.reuse(), v1::FRAME_REUSE_NONE);
  EXPECT_NE(relit.bytes, recorded.bytes) << "the light edit changed nothing";
  EXPECT_EQ(relit.bytes, relitFull.bytes) << "the re-shaded frame differs from a full render";

  ASSERT_TRUE(renderOne(*stub_, reusing, &again).ok());
  EXPECT_EQ(again.header.reuse(), v1::FRAME_REUSE_NONE) << "a frame without the flag left state behind";
  v1::UpdateSceneRequest move;
  move.set_scene_id(showcase.scene_id());
  *move.add_nodes() = translation("glow-sphere", 0.05, 0.0, 0.0);
  ASSERT_TRUE(updateScene(*stub_, move).ok());
  ASSERT_TRUE(renderOne(*stub_, reusing, &moved).ok());
  ASSERT_TRUE(renderOne(*stub_, full, &movedFull).ok());
  EXPECT_EQ(moved.header.reuse(), v1::FRAME_REUSE_PARTIAL_RETRACE);
  EXPECT_LT(moved.header.traced_targets(), movedFull.header.traced_targets());
  EXPECT_GT(movedFull.header.traced_targets(), 0u);
  EXPECT_NE(moved.bytes, again.bytes) << "the node move changed nothing";
  EXPECT_EQ(moved.bytes, movedFull.bytes) << "the partial re-render differs from a full render";
}

// A session's first edit reuses too: a frame that keeps reuse state gives the session its own renderer first. Another
// session of the same scene keeps the loaded content.
TEST_F(ServerTest, TheFirstEditOfASessionReusesItsFrame) {
  v1::SceneHandle showcase, other;
  ASSERT_TRUE(loadScene(*stub_, "builtin:showcase", &showcase).ok());
  ASSERT_TRUE(loadScene(*stub_, "builtin:showcase", &other).ok());
  v1::RenderRequest reusing = tinyRequest(showcase.scene_id());
  reusing.set_reuse_after_edits(true);
  ReceivedFrame recorded, relit, relitFull, otherFrame, otherBefore;
  ASSERT_TRUE(renderOne(*stub_, tinyRequest(other.scene_id()), &otherBefore).ok());
  ASSERT_TRUE(renderOne(*stub_, reusing, &recorded).ok());
  EXPECT_EQ(recorded.header.reuse(), v1::FRAME_REUSE_NONE);
  v1::UpdateSceneRequest lightEdit;
  lightEdit.set_scene_id(showcase.scene_id());
  v1::LightUpdate* light = lightEdit.add_lights();
  light->set_index(0);
  light->set_intensity(3.0);
  ASSERT_TRUE(updateScene(*stub_, lightEdit).ok());
  ASSERT_TRUE(renderOne(*stub_, reusing, &relit).ok());
  ASSERT_TRUE(renderOne(*stub_, tinyRequest(showcase.scene_id()), &relitFull).ok());
  EXPECT_EQ(relit.header.reuse(), v1::FRAME_REUSE_CACHED_PRIMARY_HITS);
  EXPECT_NE(relit.bytes, recorded.bytes) << "the light edit changed nothing";
  EXPECT_EQ(relit.bytes, relitFull.bytes) << "the re-shaded frame differs from a full render";
  ASSERT_TRUE(renderOne(*stub_, tinyRequest(other.scene_id()), &otherFrame).ok());
  EXPECT_EQ(otherFrame.bytes, otherBefore.bytes) << "the other session saw the edit";
}

// Lights: a dimmed, recoloured light changes the frame; an index past the scene's lights is refused.
TEST_F(ServerTest, UpdateSceneChangesALight) {
  v1::SceneHandle showcase;
  ASSERT_TRUE(loadScene(*stub_, "builtin:showcase", &showcase).ok());
  EXPECT_EQ(showcase.lights(), 2u);
  ReceivedFrame before, after;
  ASSERT_TRUE(renderOne(*stub_, tinyRequest(showcase.scene_id()), &before).ok());
  v1::UpdateSceneRequest request;
  request.set_scene_id(showcase.scene_id());
  v1::LightUpdate* light = request.add_lights();
  light->set_index(0);
  light->set_intensity(1.0);
  light->mutable_color()->set_x(0.2);
  light->mutable_color()->set_y(0.4);
  light->mutable_color()->set_z(1.0);
  ASSERT_TRUE(updateScene(*stub_, request).ok());
  ASSERT_TRUE(renderOne(*stub_, tinyRequest(showcase.scene_id()), &after).ok());
  EXPECT_NE(after.bytes, before.bytes);
  // A second light-only edit of the session re-uploads the lights into its renderer (no BVH rebuild).
  ReceivedFrame brighter;
  light->set_intensity(8.0);
  ASSERT_TRUE(updateScene(*stub_, request).ok());
  ASSERT_TRUE(renderOne(*stub_, tinyRequest(showcase.scene_id()), &brighter).ok());
  EXPECT_NE(brighter.bytes, after.bytes);
  light->set_index(2);
  const grpc::Status missing = updateScene(*stub_, request);
  EXPECT_EQ(missing.error_code(), StatusCode::INVALID_ARGUMENT);
  EXPECT_THAT(missing.error_message(), ::testing::HasSubstr("light 2"));
}

TEST_F(ServerTest, StreamDeliversFramesUntilCancelledWhileOthersRender) {
  grpc::ClientContext context;
  v1::StreamRequest request;
  request.set_mode(v1::STREAM_MODE_INDEPENDENT);  // continuous frames (progressive converges and goes quiet)
  *request.mutable_render() = tinyRequest(sceneId_);
  request.set_frames_per_second(30);
  auto reader = stub_->StreamFrames(&context, request);
  ReceivedFrame frame;
  std::uint64_t lastId = 0;
  for (int i = 0; i < 3; ++i) {
    ASSERT_TRUE(readFrame(*reader, frame));
    EXPECT_GT(frame.header.frame_id(), lastId);
    lastId = frame.header.frame_id();
  }
  auto other = connect(files_->socketAddress());
  EXPECT_TRUE(renderOne(*other, tinyRequest(sceneId_)).ok());  // a second client is served meanwhile
  context.TryCancel();
  while (readFrame(*reader, frame)) {}
  EXPECT_EQ(reader->Finish().error_code(), StatusCode::CANCELLED);
}

TEST_F(ServerTest, SlowConsumerGetsNewestFramesAndDoesNotBlockOthers) {
  grpc::ClientContext context;
  v1::StreamRequest request;
  request.set_mode(v1::STREAM_MODE_INDEPENDENT);  // continuous frames (progressive converges and goes quiet)
  *request.mutable_render() = tinyRequest(sceneId_, v1::PIXEL_FORMAT_RGBA16F);
  request.set_frames_per_second(60);
  auto reader = stub_->StreamFrames(&context, request);
  ReceivedFrame frame;
  ASSERT_TRUE(readFrame(*reader, frame));
  auto other = connect(files_->socketAddress());
  const auto start = Clock::now();
  for (int i = 0; i < 3; ++i) ASSERT_TRUE(renderOne(*other, tinyRequest(sceneId_)).ok());
  EXPECT_LT(Clock::now() - start, std::chrono::seconds(20));
  std::this_thread::sleep_for(std::chrono::milliseconds(1500));  // not reading
  std::uint64_t dropped = 0;
  for (int i = 0; i < 400 && dropped == 0 && readFrame(*reader, frame); ++i) dropped += frame.header.dropped_frames();
  EXPECT_GT(dropped, 0u);  // missed ticks were skipped, not queued
  context.TryCancel();
  while (readFrame(*reader, frame)) {}
  reader->Finish();
}

v1::StatusResponse daemonStatus(v1::Holotrace::Stub& stub) {
  grpc::ClientContext context;
  v1::StatusResponse response;
  EXPECT_TRUE(stub.Status(&context, {}, &response).ok());
  return response;
}

TEST_F(ServerTest, ClientThatDisconnectsMidStreamIsCleanedUp) {
  {
    auto vanishing = connect(files_->socketAddress());
    grpc::ClientContext context;
    v1::StreamRequest request;
    request.set_mode(v1::STREAM_MODE_INDEPENDENT);  // continuous frames (progressive converges and goes quiet)
    *request.mutable_render() = tinyRequest(sceneId_);
    request.set_frames_per_second(30);
    auto reader = vanishing->StreamFrames(&context, request);
    ReceivedFrame frame;
    ASSERT_TRUE(readFrame(*reader, frame));
    context.TryCancel();  // destroying a call mid-stream requires cancelling it first (grpcpp ClientContext)
  }
  const auto deadline = Clock::now() + std::chrono::seconds(10);
  while (daemonStatus(*stub_).active_streams() != 0 && Clock::now() < deadline) {
    std::this_thread::sleep_for(std::chrono::milliseconds(20));
  }
  EXPECT_EQ(daemonStatus(*stub_).active_streams(), 0u);
  EXPECT_TRUE(renderOne(*stub_, tinyRequest(sceneId_)).ok());
  EXPECT_GT(daemonStatus(*stub_).devices(0).frames_rendered(), 0u);
}

TEST_F(ServerTest, TooManyStreamingClientsIsResourceExhausted) {
  struct Stream {
    grpc::ClientContext context;
    std::unique_ptr<grpc::ClientReader<v1::FramePart>> reader;
  };
  std::vector<std::unique_ptr<Stream>> streams;
  v1::StreamRequest request;
  request.set_mode(v1::STREAM_MODE_INDEPENDENT);  // continuous frames (progressive converges and goes quiet)
  *request.mutable_render() = tinyRequest(sceneId_);
  request.set_frames_per_second(1);
  for (std::uint32_t i = 0; i < files_->config().limits.maxClients; ++i) {
    auto s = std::make_unique<Stream>();
    s->reader = stub_->StreamFrames(&s->context, request);
    ReceivedFrame frame;
    ASSERT_TRUE(readFrame(*s->reader, frame));
    streams.push_back(std::move(s));
  }
  const grpc::Status refused = renderOne(*stub_, tinyRequest(sceneId_));
  EXPECT_EQ(refused.error_code(), StatusCode::RESOURCE_EXHAUSTED);
  EXPECT_NE(refused.error_message().find("max_clients"), std::string::npos);
  for (auto& s : streams) s->context.TryCancel();
  for (auto& s : streams) s->reader->Finish();
  const auto deadline = Clock::now() + std::chrono::seconds(5);  // slots come back promptly after cancel
  while (daemonStatus(*stub_).active_streams() != 0 && Clock::now() < deadline) {
    std::this_thread::sleep_for(std::chrono::milliseconds(10));
  }
  EXPECT_EQ(daemonStatus(*stub_).active_streams(), 0u);
}

grpc::Status capture(v1::Holotrace::Stub& stub, const std::string& name, std::uint32_t frames,
                     const v1::RenderRequest& render, std::vector<std::string>* files = nullptr,
                     bool overwrite = false) {
  grpc::ClientContext context;
  context.set_deadline(std::chrono::system_clock::now() + std::chrono::seconds(60));
  v1::CaptureRequest request;
  *request.mutable_render() = render;
  request.set_name(name);
  request.set_frames(frames);
  request.set_overwrite(overwrite);
  auto reader = stub.Capture(&context, request);
  v1::CaptureProgress progress;
  while (reader->Read(&progress)) {
    if (files) files->push_back(progress.file());
  }
  return reader->Finish();
}

TEST_F(ServerTest, CaptureWritesOnlyCompleteFilesBeneathTheOutputRoot) {
  std::vector<std::string> files;
  const grpc::Status status = capture(*stub_, "shot", 2, tinyRequest(sceneId_), &files);
  ASSERT_TRUE(status.ok()) << status.error_message();
  ASSERT_EQ(files, (std::vector<std::string>{"shot_f0000.png", "shot_f0001.png"}));
  for (const auto& f : files) EXPECT_TRUE(isCompletePng(files_->outputRoot() / f)) << f;
  for (const auto& entry : std::filesystem::directory_iterator(files_->outputRoot())) {
    EXPECT_NE(entry.path().filename().string().front(), '.') << "temp file left: " << entry.path();
  }
  EXPECT_EQ(capture(*stub_, "../evil", 1, tinyRequest(sceneId_)).error_code(), StatusCode::PERMISSION_DENIED);
  EXPECT_EQ(capture(*stub_, "/tmp/evil", 1, tinyRequest(sceneId_)).error_code(), StatusCode::PERMISSION_DENIED);
  EXPECT_EQ(capture(*stub_, "a b", 1, tinyRequest(sceneId_)).error_code(), StatusCode::INVALID_ARGUMENT);
  EXPECT_EQ(capture(*stub_, "many", 51, tinyRequest(sceneId_)).error_code(), StatusCode::RESOURCE_EXHAUSTED);
  EXPECT_FALSE(std::filesystem::exists(files_->dir.path / "evil_f0000.png"));
}

v1::RenderRequest multiViewRequest(const std::string& sceneId, const std::string& display, v1::PixelFormat format) {
  v1::RenderRequest request = tinyRequest(sceneId, format);
  request.set_display_id(display);
  return request;
}

TEST_F(ServerTest, MultiViewFramesCarryEveryViewAndPngIsTheQuilt) {
  ReceivedFrame frame;
  ASSERT_TRUE(renderOne(*stub_, multiViewRequest(sceneId_, "rig", v1::PIXEL_FORMAT_RGBA8), &frame).ok());
  EXPECT_EQ(frame.header.views(), 6u);
  EXPECT_EQ(frame.header.width(), 24u);
  EXPECT_EQ(frame.bytes.size(), 6u * 24 * 16 * 4);
  ASSERT_TRUE(renderOne(*stub_, multiViewRequest(sceneId_, "rig", v1::PIXEL_FORMAT_PNG), &frame).ok());
  EXPECT_EQ(frame.header.width(), 72u);  // the 3x2 quilt of 24x16 tiles
  EXPECT_EQ(frame.header.height(), 32u);
  v1::RenderRequest quilt = tinyRequest(sceneId_);
  quilt.set_display_id("wall");
  quilt.set_quilt(true);  // only lenticular displays have quilt cameras
  EXPECT_EQ(renderOne(*stub_, quilt).error_code(), StatusCode::INVALID_ARGUMENT);
}

TEST_F(ServerTest, CaptureWritesQuiltPerViewAndMultiViewFiles) {
  std::vector<std::string> files;
  ASSERT_TRUE(captureFrame(*stub_, "rigq", multiViewRequest(sceneId_, "rig", v1::PIXEL_FORMAT_RGBA8),
                           v1::CAPTURE_FORMAT_PNG, v1::CAPTURE_LAYOUT_AUTO, files)
                  .ok());
  ASSERT_EQ(files, (std::vector<std::string>{"rigq_f0000_qs3x2a1.5.png", "rigq_f0000_qs3x2a1.5.json"}));
  EXPECT_TRUE(isCompletePng(files_->outputRoot() / files[0]));
  files.clear();
  ASSERT_TRUE(captureFrame(*stub_, "walls", multiViewRequest(sceneId_, "wall", v1::PIXEL_FORMAT_RGBA8),
                           v1::CAPTURE_FORMAT_PNG, v1::CAPTURE_LAYOUT_AUTO, files)
                  .ok());
  EXPECT_EQ(files, (std::vector<std::string>{"walls_f0000_v00.png", "walls_f0000_v01.png", "walls_f0000_v02.png"}));
  files.clear();
  ASSERT_TRUE(captureFrame(*stub_, "wallx", multiViewRequest(sceneId_, "wall", v1::PIXEL_FORMAT_RGBA8),
                           v1::CAPTURE_FORMAT_EXR, v1::CAPTURE_LAYOUT_AUTO, files)
                  .ok());
  EXPECT_EQ(files, (std::vector<std::string>{"wallx_f0000.exr"}));
  files.clear();
  EXPECT_EQ(captureFrame(*stub_, "wallq", multiViewRequest(sceneId_, "wall", v1::PIXEL_FORMAT_RGBA8),
                         v1::CAPTURE_FORMAT_PNG, v1::CAPTURE_LAYOUT_QUILT, files)
                .error_code(),
            StatusCode::INVALID_ARGUMENT);
  EXPECT_FALSE(std::filesystem::exists(files_->outputRoot() / "wallq_f0000.png"));
}

// The tracked observer of an HPO display (UpdateScene): moving it changes the double-perspective rays, hence the
// frame; moving it back restores the frame exactly.
TEST_F(ServerTest, UpdateSceneMovesTheTrackedObserver) {
  auto frameBytes = [&] {
    ReceivedFrame frame;
    EXPECT_TRUE(renderOne(*stub_, multiViewRequest(sceneId_, "wall", v1::PIXEL_FORMAT_RGBA8), &frame).ok());
    return frame.bytes;
  };
  auto moveObserver = [&](double distance, double height) {
    grpc::ClientContext context;
    v1::UpdateSceneRequest request;
    request.set_scene_id(sceneId_);
    request.set_observer_distance(distance);
    request.set_observer_height(height);
    v1::UpdateSceneResponse response;
    return stub_->UpdateScene(&context, request, &response);
  };
  const auto before = frameBytes();
  ASSERT_TRUE(moveObserver(300, 40).ok());
  EXPECT_NE(frameBytes(), before);
  ASSERT_TRUE(moveObserver(300, 0).ok());
  EXPECT_EQ(frameBytes(), before);
  EXPECT_EQ(moveObserver(-1, 0).error_code(), StatusCode::INVALID_ARGUMENT);
}

TEST_F(ServerTest, CaptureOverAnExistingSymlinkDoesNotFollowIt) {
  // A planted symlink named like a capture output is an existing name; with overwrite it is removed (unlink, never
  // followed) and replaced, the target is never written.
  const auto outside = files_->dir.path / "victim.png";
  writeText(outside, "untouched");
  std::filesystem::create_symlink(outside, files_->outputRoot() / "trap_f0000.png");
  EXPECT_EQ(capture(*stub_, "trap", 1, tinyRequest(sceneId_)).error_code(), StatusCode::ALREADY_EXISTS);
  ASSERT_TRUE(capture(*stub_, "trap", 1, tinyRequest(sceneId_), nullptr, true).ok());
  std::ifstream in(outside);
  std::string text;
  std::getline(in, text);
  EXPECT_EQ(text, "untouched");
  EXPECT_TRUE(isCompletePng(files_->outputRoot() / "trap_f0000.png"));
}

}  // namespace
}  // namespace ht::server::test
