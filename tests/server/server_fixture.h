// server_fixture.h - an in-process holotraced on a temporary unix socket with a tiny lenticular display (96x64),
// a small OBJ scene below its scene root and an output root, plus helpers to drive it through the C++ stubs.
#pragma once
#include <grpcpp/grpcpp.h>
#include <gtest/gtest.h>

#include <filesystem>
#include <iostream>
#include <memory>
#include <string>
#include <vector>

#include "holotrace/v1/holotrace.grpc.pb.h"
#include "server/daemon.h"
#include "server/daemon_config.h"

namespace ht::server::test {

namespace v1 = holotrace::v1;

inline constexpr std::uint32_t kTinyWidth = 96, kTinyHeight = 64;

// A fresh directory under /tmp, removed at destruction.
struct TempDir {
  TempDir();
  ~TempDir();
  std::filesystem::path path;
};

std::string tinyDisplayJson();  // lenticular, 96x64 panel, spp 1
std::string cubeObj();          // 12 triangles
void writeText(const std::filesystem::path& file, const std::string& text);

// Everything a test daemon needs on disk; `config()` points at it.
struct DaemonFiles {
  TempDir dir;
  DaemonFiles();
  DaemonConfig config() const;  // small limits, see server_fixture.cpp
  std::string socketAddress() const;
  std::filesystem::path outputRoot() const { return dir.path / "out"; }
  std::filesystem::path sceneRoot() const { return dir.path / "scenes"; }
};

struct ReceivedFrame {
  v1::FrameHeader header;
  std::vector<std::uint8_t> bytes;
};

// Reads one header + its chunks; false at end of stream.
bool readFrame(grpc::ClientReaderInterface<v1::FramePart>& reader, ReceivedFrame& frame);

std::unique_ptr<v1::Holotrace::Stub> connect(const std::string& address);
grpc::Status loadScene(v1::Holotrace::Stub& stub, const std::string& path, v1::SceneHandle* handle = nullptr);
// UploadScene of `bytes` named `name` in one data message; returns the final status.
grpc::Status uploadScene(v1::Holotrace::Stub& stub, const std::string& name, const std::string& bytes,
                         v1::SceneHandle* handle = nullptr);
v1::RenderRequest tinyRequest(const std::string& sceneId, v1::PixelFormat format = v1::PIXEL_FORMAT_RGBA8);
// Renders one frame; returns the final status.
grpc::Status renderOne(v1::Holotrace::Stub& stub, const v1::RenderRequest& request, ReceivedFrame* frame = nullptr);

// One Capture of one frame; returns the final status and appends the files it reported to `files`.
grpc::Status captureFrame(v1::Holotrace::Stub& stub, const std::string& name, const v1::RenderRequest& render,
                          v1::CaptureFormat format, v1::CaptureLayout layout, std::vector<std::string>& files);

bool isCompletePng(const std::filesystem::path& file);  // signature + IEND trailer

// One in-process daemon per test suite (started in SetUpTestSuite), a client stub and a loaded builtin:plain scene
// per test. Each suite deriving from it gets its own daemon (the statics are per template instance).
template <class Suite>
class InProcessDaemonTest : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    files_ = new DaemonFiles();
    daemon_ = new Daemon(files_->config(), std::cerr);
    daemon_->start();
  }
  static void TearDownTestSuite() {
    delete daemon_;
    delete files_;
    daemon_ = nullptr;
    files_ = nullptr;
  }
  void SetUp() override {
    stub_ = connect(files_->socketAddress());
    v1::SceneHandle handle;
    ASSERT_TRUE(loadScene(*stub_, "builtin:plain", &handle).ok());
    sceneId_ = handle.scene_id();
  }

  static inline DaemonFiles* files_ = nullptr;
  static inline Daemon* daemon_ = nullptr;
  std::unique_ptr<v1::Holotrace::Stub> stub_;
  std::string sceneId_;
};

}  // namespace ht::server::test
