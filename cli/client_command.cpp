// client_command.cpp - see client_command.h.
#include "cli/client_command.h"

#include <grpcpp/grpcpp.h>

#include <array>
#include <chrono>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iterator>

#include "cli/arguments.h"
#include "common/error.h"
#include "frame_io/atomic_output_file.h"
#include "holotrace/v1/holotrace.grpc.pb.h"

namespace ht::cli {
namespace {

namespace v1 = holotrace::v1;
using Stub = v1::Holotrace::Stub;
constexpr const char* kCommand = "holotrace client";

const std::array<OptionSpec, 16> kOptions = {{
    {"--socket", "", "ADDR", "daemon address (default unix:$XDG_RUNTIME_DIR/holotrace/holotraced.sock)"},
    {"--scene", "", "SPEC", "scene below the daemon's scene root, or builtin:NAME (default builtin:showcase)"},
    {"--upload", "", "FILE",
     "send this local scene file's (or quilt image's, NAME_qs8x6a0.75.png) bytes instead of --scene"},
    {"--display", "", "ID", "display id from `client displays` (default builtin:portrait)"},
    {"--format", "", "FMT", "rgba8 | rgba16f | png (render/stream; default png for render)"},
    {"--spp", "", "N", "samples per subpixel (default: the display's)"},
    {"--refine-spp", "", "N", "adaptive refinement: high-contrast subpixels again at N spp (default 0 = off)"},
    {"--refine-contrast", "", "X", "sRGB step to a neighbour that triggers refinement, 0-1 (default 0.08)"},
    {"--out", "-o", "FILE", "render: write the frame bytes here"},
    {"--fps", "", "N", "stream: requested frames per second (default 10)"},
    {"--frames", "", "N", "stream: stop after N frames (default 10); capture: file count (default 1)"},
    {"--mode", "", "MODE",
     "stream: progressive (default: frames add samples until converged, then the stream ends here) | independent"},
    {"--present-on", "", "ID",
     "stream: also show every frame on display ID's panel sink (the daemon config's \"present\")"},
    {"--name", "", "NAME", "capture: file name prefix under the daemon's output root"},
    {"--exr", "", "", "capture: linear half EXR instead of 8-bit PNG"},
    {"--move", "", "NODE=X,Y,Z",
     "load/render/stream/capture: set scene node NODE's world matrix (names: `client load`) "
     "to a translation by X,Y,Z (built-in objects: an offset from where they are made)"},
}};

std::string defaultSocket() {
  const char* runtime = std::getenv("XDG_RUNTIME_DIR");
  return std::string("unix:") + (runtime && *runtime ? std::string(runtime) : std::string("/run")) +
         "/holotrace/holotraced.sock";
}

void check(const grpc::Status& status, const std::string& what) {
  if (!status.ok()) {
    throw IoError(std::string(kCommand) + ": " + what + " failed: status " + std::to_string(status.error_code()) +
                  ": " + status.error_message());
  }
}

std::unique_ptr<Stub> connectTo(const ParsedArguments& a) {
  grpc::ChannelArguments args;
  args.SetMaxReceiveMessageSize(64 << 20);
  return v1::Holotrace::NewStub(
      grpc::CreateCustomChannel(a.textOr("--socket", defaultSocket()), grpc::InsecureChannelCredentials(), args));
}

int listDisplays(Stub& stub, std::ostream& out) {
  grpc::ClientContext context;
  v1::ListDisplaysResponse response;
  check(stub.ListDisplays(&context, {}, &response), "ListDisplays");
  for (const auto& d : response.displays()) {
    out << d.id() << "  " << d.model() << "  " << d.panel_width() << "x" << d.panel_height() << "  " << d.name()
        << "  [" << (d.source().empty() ? "builtin" : d.source()) << "]\n";
  }
  return 0;
}

v1::SceneHandle uploadScene(Stub& stub, const std::string& file) {
  std::ifstream in(file, std::ios::binary);
  if (!in) throw IoError(std::string(kCommand) + ": cannot read " + file);
  const std::string bytes{std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
  grpc::ClientContext context;
  v1::SceneHandle handle;
  auto writer = stub.UploadScene(&context, &handle);
  v1::UploadSceneChunk chunk;
  chunk.mutable_info()->set_file_name(std::filesystem::path(file).filename().string());
  chunk.mutable_info()->set_total_bytes(bytes.size());
  constexpr std::size_t kChunk = 1 << 20;
  bool open = writer->Write(chunk);
  for (std::size_t offset = 0; open && offset < bytes.size(); offset += kChunk) {
    chunk.set_data(bytes.substr(offset, kChunk));
    open = writer->Write(chunk);
  }
  writer->WritesDone();
  check(writer->Finish(), "UploadScene");
  return handle;
}

// --move NODE=X,Y,Z: the node's world matrix becomes a translation by (X, Y, Z) (UpdateScene nodes).
void moveNode(Stub& stub, const std::string& sceneId, const std::string& spec, std::ostream& out) {
  const auto eq = spec.rfind('=');
  std::array<double, 3> t{};
  bool ok = eq != std::string::npos && eq > 0;
  std::size_t pos = eq + 1;
  for (int k = 0; ok && k < 3; ++k) {
    char* end = nullptr;
    t[static_cast<std::size_t>(k)] = std::strtod(spec.c_str() + pos, &end);
    ok = end != spec.c_str() + pos && std::isfinite(t[static_cast<std::size_t>(k)]);
    pos = static_cast<std::size_t>(end - spec.c_str());
    if (ok && k < 2) ok = pos < spec.size() && spec[pos++] == ',';
  }
  if (!ok || pos != spec.size()) {
    throw UsageError(
        usageMessage(kCommand, "--move expects NODE=X,Y,Z (e.g. glass-sphere=0,0.3,0), not '" + spec + "'"));
  }
  grpc::ClientContext context;
  v1::UpdateSceneRequest request;
  request.set_scene_id(sceneId);
  v1::NodeTransform* node = request.add_nodes();
  node->set_node(spec.substr(0, eq));
  for (int k = 0; k < 16; ++k) node->add_world(k % 5 == 0 ? 1.0 : 0.0);  // identity, column-major
  for (int k = 0; k < 3; ++k) node->set_world(12 + k, t[static_cast<std::size_t>(k)]);
  v1::UpdateSceneResponse response;
  check(stub.UpdateScene(&context, request, &response), "UpdateScene");
  out << "moved " << node->node() << ": world = translate(" << t[0] << ", " << t[1] << ", " << t[2]
      << "), BVH updated in " << response.rebuild_ms() << " ms (" << response.bvh_layout() << ", "
      << response.bvh_full_builds() << " full build(s), " << response.bvh_instance_updates() << " move update(s))\n";
}

v1::SceneHandle openScene(Stub& stub, const ParsedArguments& a, std::ostream& out) {
  v1::SceneHandle handle;
  if (auto file = a.text("--upload")) {
    handle = uploadScene(stub, *file);
  } else {
    grpc::ClientContext context;
    v1::LoadSceneRequest request;
    request.set_path(a.textOr("--scene", "builtin:showcase"));
    check(stub.LoadScene(&context, request, &handle), "LoadScene");
  }
  out << "scene " << handle.scene_id() << ": " << handle.triangles() << " triangles, BVH " << handle.bvh_build_ms()
      << " ms, SAH " << handle.sah_cost() << (handle.reused() ? " (shared)" : "") << "\n";
  std::string nodes;
  for (const std::string& n : handle.nodes()) nodes += (nodes.empty() ? "" : ", ") + n;
  out << "  nodes: " << (nodes.empty() ? "none" : nodes) << "; lights: " << handle.lights() << "\n";
  if (auto move = a.text("--move")) moveNode(stub, handle.scene_id(), *move, out);
  return handle;
}

// Ends the session when the command is done, also on errors (best effort: a session the daemon did not hear about
// ends after its idle TTL, docs/SERVICE.md §5 "Scene sessions and memory").
struct SessionRelease {
  Stub& stub;
  std::string sceneId;
  ~SessionRelease() {
    grpc::ClientContext context;
    context.set_deadline(std::chrono::system_clock::now() + std::chrono::seconds(5));
    v1::UnloadSceneRequest request;
    request.set_scene_id(sceneId);
    v1::UnloadSceneResponse response;
    stub.UnloadScene(&context, request, &response);
  }
};

v1::PixelFormat pixelFormat(const ParsedArguments& a, const std::string& fallback) {
  const std::string f = a.textOr("--format", fallback);
  if (f == "rgba8") return v1::PIXEL_FORMAT_RGBA8;
  if (f == "rgba16f") return v1::PIXEL_FORMAT_RGBA16F;
  if (f == "png") return v1::PIXEL_FORMAT_PNG;
  throw UsageError(usageMessage(kCommand, "--format must be rgba8, rgba16f or png, not '" + f + "'"));
}

v1::RenderRequest renderRequest(const ParsedArguments& a, const std::string& sceneId, const std::string& format) {
  v1::RenderRequest request;
  request.set_scene_id(sceneId);
  request.set_display_id(a.textOr("--display", "builtin:portrait"));
  request.set_format(pixelFormat(a, format));
  request.set_spp(a.unsignedValue("--spp", 1, 4096).value_or(0));
  request.set_refine_spp(a.unsignedValue("--refine-spp", 0, 4096).value_or(0));
  request.set_refine_contrast(static_cast<float>(a.numberValue("--refine-contrast", 0.0, 1.0).value_or(0.0)));
  return request;
}

// Reads header + chunks of one frame; false at end of stream.
bool readFrame(grpc::ClientReaderInterface<v1::FramePart>& reader, v1::FrameHeader& header, std::string& bytes) {
  v1::FramePart part;
  if (!reader.Read(&part) || !part.has_header()) return false;
  header = part.header();
  bytes.clear();
  while (bytes.size() < header.total_bytes() && reader.Read(&part) && part.has_chunk()) bytes += part.chunk().data();
  return bytes.size() == header.total_bytes();
}

void printFrame(std::ostream& out, const v1::FrameHeader& h) {
  out << "frame " << h.frame_id() << ": " << h.width() << "x" << h.height() << ", " << h.total_bytes() << " bytes, "
      << h.render_ms() << " ms render, " << h.queue_ms() << " ms queued";
  if (h.dropped_frames()) out << ", " << h.dropped_frames() << " dropped";
  if (h.state() != v1::STREAM_STATE_UNSPECIFIED) {
    out << ", " << h.accumulated_spp() << "-" << h.accumulated_spp_max() << " spp accumulated, error "
        << h.error_estimate() << (h.state() == v1::STREAM_STATE_CONVERGED ? ", converged" : "");
  }
  out << "\n";
}

int render(Stub& stub, const ParsedArguments& a, std::ostream& out) {
  const v1::SceneHandle scene = openScene(stub, a, out);
  const SessionRelease release{stub, scene.scene_id()};
  grpc::ClientContext context;
  auto reader = stub.RenderFrame(&context, renderRequest(a, scene.scene_id(), "png"));
  v1::FrameHeader header;
  std::string bytes;
  const bool got = readFrame(*reader, header, bytes);
  check(reader->Finish(), "RenderFrame");
  if (!got) throw IoError(std::string(kCommand) + ": the daemon sent an incomplete frame");
  printFrame(out, header);
  for (const auto& s : header.stages()) out << "  " << s.name() << " " << s.ms() << " ms\n";
  if (auto file = a.text("--out")) {  // atomically, as `holotrace render` writes: never a partial PNG
    const frame_io::OutputFile png{*file, {bytes.begin(), bytes.end()}};
    frame_io::writeFilesAtomically({&png, 1});
    out << "wrote " << *file << "\n";
  }
  return 0;
}

int stream(Stub& stub, const ParsedArguments& a, std::ostream& out) {
  const v1::SceneHandle scene = openScene(stub, a, out);
  const SessionRelease release{stub, scene.scene_id()};
  v1::StreamRequest request;
  *request.mutable_render() = renderRequest(a, scene.scene_id(), "rgba8");
  request.set_frames_per_second(a.unsignedValue("--fps", 1, 120).value_or(10));
  const std::string mode = a.textOr("--mode", "progressive");
  if (mode != "progressive" && mode != "independent") {
    throw UsageError(usageMessage(kCommand, "--mode " + mode + ": expected progressive or independent"));
  }
  request.set_mode(mode == "progressive" ? v1::STREAM_MODE_PROGRESSIVE : v1::STREAM_MODE_INDEPENDENT);
  request.set_present_on(a.textOr("--present-on", ""));
  const std::uint32_t frames = a.unsignedValue("--frames", 1, 1'000'000).value_or(10);
  grpc::ClientContext context;
  auto reader = stub.StreamFrames(&context, request);
  v1::FrameHeader header;
  std::string bytes;
  const auto start = std::chrono::steady_clock::now();
  std::uint32_t received = 0;
  while (received < frames && readFrame(*reader, header, bytes)) {
    printFrame(out, header);
    ++received;
    if (header.state() == v1::STREAM_STATE_CONVERGED) break;  // a converged stream sends nothing more
  }
  const double s = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  context.TryCancel();
  while (readFrame(*reader, header, bytes)) {}
  const grpc::Status status = reader->Finish();
  if (status.error_code() != grpc::StatusCode::CANCELLED) check(status, "StreamFrames");
  out << received << " frames in " << s << " s (" << (s > 0 ? received / s : 0.0) << " frames/s)\n";
  return 0;
}

int capture(Stub& stub, const ParsedArguments& a, std::ostream& out) {
  const auto name = a.text("--name");
  if (!name) throw UsageError(usageMessage(kCommand, "capture needs --name NAME"));
  const v1::SceneHandle scene = openScene(stub, a, out);
  const SessionRelease release{stub, scene.scene_id()};
  v1::CaptureRequest request;
  *request.mutable_render() = renderRequest(a, scene.scene_id(), "png");
  request.set_name(*name);
  request.set_frames(a.unsignedValue("--frames", 1, 100'000).value_or(1));
  request.set_format(a.has("--exr") ? v1::CAPTURE_FORMAT_EXR : v1::CAPTURE_FORMAT_PNG);
  grpc::ClientContext context;
  auto reader = stub.Capture(&context, request);
  v1::CaptureProgress progress;
  while (reader->Read(&progress)) {
    out << "[" << progress.frames_done() << "/" << progress.frames_total() << "] " << progress.file() << "\n";
  }
  check(reader->Finish(), "Capture");
  return 0;
}

}  // namespace

std::string clientHelp() {
  return "Usage: holotrace client displays|load|render|stream|capture [options]\n\n"
         "Talks to a running holotraced (docs/SERVICE.md).\n"
         "  displays  list the daemon's displays\n"
         "  load      load (--scene) or upload (--upload) a scene, print its handle and BVH report\n"
         "  render    render one frame, print timings, optionally save it (--out)\n"
         "  stream    receive --frames frames at --fps, then cancel\n"
         "  capture   write --frames native panel files NAME_fNNNN.png|.exr under the daemon's output root\n\n"
         "Options:\n" +
         formatOptions(kOptions);
}

int runClient(std::span<const std::string> args, std::ostream& out) {
  if (args.empty())
    throw UsageError(usageMessage(kCommand, "missing subcommand (displays|load|render|stream|capture)"));
  const std::string sub = args[0];
  const ParsedArguments a = parseArguments(kCommand, kOptions, args.subspan(1));
  auto stub = connectTo(a);
  if (sub == "displays") return listDisplays(*stub, out);
  if (sub == "load") return openScene(*stub, a, out), 0;
  if (sub == "render") return render(*stub, a, out);
  if (sub == "stream") return stream(*stub, a, out);
  if (sub == "capture") return capture(*stub, a, out);
  throw UsageError(usageMessage(kCommand, "unknown subcommand '" + sub + "'"));
}

}  // namespace ht::cli
