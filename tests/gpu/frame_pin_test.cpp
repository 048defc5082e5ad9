// frame_pin_test.cpp - pins the exact bits of small renders of every display model (SHA-256 of the linear float
// RGBA the renderer returns), so a refactoring that must not change any frame can prove it did not.
//
// The pinned digests depend on the Vulkan device and on the code the driver's JIT emits for this CPU (lavapipe's
// LLVM picks the vector width from the host, and used to pick FMA), so the table is keyed by the device name, which for
// lavapipe includes the vector width ("llvmpipe (LLVM 15.0.6, 256 bits)"). On a device with no pinned row the test is
// skipped and prints the digests it computed; a row added for a new machine must come from a build before the change
// under test. Any intended change of the rendered pixels updates the rows in the same commit and says why.
#include <gtest/gtest.h>
#include <openssl/evp.h>

#include <cstdio>
#include <cstring>
#include <map>
#include <string>

#include "camera_models/display_config.h"
#include "camera_models/quilt_layout.h"
#include "camera_models/quilt_setup.h"
#include "camera_models/ray_table.h"
#include "gpu/display_camera.h"
#include "gpu/renderer.h"
#include "gpu_test_util.h"
#include "scene/mesh_generators.h"

namespace ht::test {
namespace {

// A diffuse sphere, a mirror sphere, a glass sphere and a floor under a directional light: primary, shadow,
// reflection and refraction paths all contribute.
Scene pinScene() {
  Scene s;
  s.name = "test:pin";
  const DiffuseMirrorGlass m = addDiffuseMirrorGlass(s);
  makeIcosphere(s, glm::vec3(-0.3f, 0.0f, 0.0f), 0.35f, 3, m.diffuse);
  makeIcosphere(s, glm::vec3(0.35f, 0.1f, -0.2f), 0.3f, 2, m.mirror);
  makeIcosphere(s, glm::vec3(0.05f, -0.15f, 0.35f), 0.2f, 2, m.glass);
  makeQuad(s, glm::vec3(0.0f, -0.4f, 0.0f), glm::vec3(1.0f, 0.0f, 0.0f), glm::vec3(0.0f, 0.0f, -1.0f),
           ht::addMaterial(s, s.materials[m.diffuse]));  // a fourth material, a copy of the diffuse one
  Light sun;
  sun.type = Light::Type::Directional;
  sun.direction = glm::normalize(glm::vec3(0.3f, -1.0f, -0.4f));
  sun.intensity = 2.0f;
  s.lights.push_back(sun);
  return s;
}

std::string sha256Hex(const gpu::RenderResult& r) {
  EVP_MD_CTX* ctx = EVP_MD_CTX_new();
  EVP_DigestInit_ex(ctx, EVP_sha256(), nullptr);
  const std::uint32_t dims[3] = {r.width, r.height, r.views};
  EVP_DigestUpdate(ctx, dims, sizeof dims);
  EVP_DigestUpdate(ctx, r.rgba.data(), r.rgba.size() * sizeof(float));
  unsigned char digest[EVP_MAX_MD_SIZE];
  unsigned int length = 0;
  EVP_DigestFinal_ex(ctx, digest, &length);
  EVP_MD_CTX_free(ctx);
  std::string hex;
  for (unsigned int i = 0; i < length; ++i) {
    char byte[3];
    std::snprintf(byte, sizeof byte, "%02x", digest[i]);
    hex += byte;
  }
  return hex;
}

DisplayConfig smallLenticular(const char* builtin, std::uint32_t w, std::uint32_t h) {
  DisplayConfig c = builtinDisplay(builtin);
  c.calibration->screenW = w;
  c.calibration->screenH = h;
  return c;
}

DisplayConfig parse(const std::string& json) { return parseDisplayConfig(json, "frame_pin_test", HT_TEST_DATA_DIR); }

struct PinCase {
  const char* name;
  gpu::FrameCamera camera;
  gpu::RenderSettings settings;
};

std::shared_ptr<const RayTable> smallRayTable() {
  auto table = std::make_shared<RayTable>();
  table->width = 24;
  table->height = 16;
  for (std::uint32_t y = 0; y < table->height; ++y) {
    for (std::uint32_t x = 0; x < table->width; ++x) {
      const float u = (x + 0.5f) / table->width - 0.5f, v = (y + 0.5f) / table->height - 0.5f;
      table->origins.push_back(glm::vec3(u * 0.8f, v * 0.6f, 2.0f));
      table->directions.push_back(glm::normalize(glm::vec3(u * 0.3f, v * 0.2f, -1.0f)));
    }
  }
  table->normalizeDirections();
  return table;
}

std::vector<PinCase> pinCases(const Bounds3& bounds) {
  std::vector<PinCase> cases;
  const auto add = [&](const char* name, gpu::FrameCamera camera, std::uint32_t spp) {
    gpu::RenderSettings s;
    s.spp = spp;
    s.maxDepth = 3;
    s.seed = 11;
    cases.push_back({name, std::move(camera), s});
  };
  const DisplayConfig portrait = smallLenticular("portrait", 72, 96);
  add("lenticular-portrait", gpu::makeDisplayCamera(portrait, bounds).camera, 2);
  add("lenticular-gen3", gpu::makeDisplayCamera(smallLenticular("gen3-16-landscape", 96, 54), bounds).camera, 1);
  add("quilt-portrait", makeQuiltParams(portrait, bounds, makeQuiltLayout(4, 2, 96, 64, 0.75)), 1);
  add("pinhole",
      gpu::makeDisplayCamera(parse(R"({"model":"pinhole","pinhole":{"width":64,"height":48,
      "fovyDeg":50,"eye":[0,0.3,3],"lookAt":[0,0,0],"distortion":{"k1":-0.1}}})"),
                             bounds)
          .camera,
      2);
  add("projector-array",
      gpu::makeDisplayCamera(parse(R"({"model":"projector-array","camera":{"size":1.5},
      "projectorArray":{"screen":{"width":800,"height":600},"observerDistance":2500,"angularScattering":0.02,
      "image":{"width":40,"height":30},"projectors":[{"position":[-300,50,-1500]},{"position":[100,0,-1500]},
      {"position":[300,10,-1600]}]}})"),
                             bounds)
          .camera,
      1);
  add("integral",
      gpu::makeDisplayCamera(parse(R"({"model":"integral","camera":{"size":1.5},"integral":{
      "panelWidth":64,"panelHeight":48,"pixelPitch":0.1,"lensPitch":0.77,"lensOffset":[0.13,-0.21],
      "lensRotationDeg":7.5,"gap":2.0,"focalLength":2.5,"viewerDistance":500,"frontPlane":120,
      "sampling":"aperture"}})"),
                             bounds)
          .camera,
      2);
  add("capture-grid",
      gpu::makeDisplayCamera(parse(R"({"model":"capture-grid","captureGrid":{"columns":3,"rows":2,
      "spacing":[0.1,0.1],"distance":2.5,"window":{"width":1.6,"height":1.2},"image":{"width":32,"height":24}}})"),
                             bounds)
          .camera,
      1);
  add("oblique",
      gpu::makeDisplayCamera(parse(R"({"model":"oblique","oblique":{"columns":3,"rows":3,
      "horizontalConeDeg":40,"verticalConeDeg":30,"image":{"width":24,"height":24}}})"),
                             bounds)
          .camera,
      1);
  add("ray-table",
      gpu::makeDisplayCamera(parse(R"({"model":"ray-table","rayTable":{"file":"unused.exr"}})"), bounds,
                             gpu::CameraPath::Native, smallRayTable())
          .camera,
      2);
  // The same panel through the other filters and adaptive refinement (its own raygen/resolve pipelines).
  add("lenticular-gaussian", gpu::makeDisplayCamera(portrait, bounds).camera, 2);
  cases.back().settings.filter = gpu::SampleFilter::Gaussian;
  add("lenticular-refined", gpu::makeDisplayCamera(portrait, bounds).camera, 1);
  cases.back().settings.refineSpp = 4;
  cases.back().settings.refineContrast = 0.05f;
  add("pinhole-tent-unspecialized", std::get<gpu_shared::PinholeParams>(cases[3].camera), 2);
  cases.back().settings.filter = gpu::SampleFilter::Tent;
  cases.back().settings.forceAllFeatures = true;
  return cases;
}

// Device name -> case name -> SHA-256 of the frame, rendered by this test. Re-pinned when glass's random Fresnel
// choice became keyed by the frame-wide target and sample instead of the path's index within its chunk
// (gpu/shaders/shade.comp path_sample_key), so that a band of rows or a range of views renders the whole frame's bits;
// again when that choice became keyed by the absolute sample index instead of (sample, spp), the key progressive
// frames use, so that a progressive stream at N samples shows the single N-sample frame's bits (docs/REUSE.md §6);
// again when every float multiply and add of every pass became unfused (gpu/spirv_exact_float.h: lavapipe had
// fused those not marked precise, as the host's FMA allowed; with the old pipelines, fused, the old digests still
// came out) and the resolve pass's mean became an exactly rounded division (common/exact_division.h).
const std::map<std::string, std::map<std::string, std::string>>& pinnedDigests() {
  static const std::map<std::string, std::map<std::string, std::string>> table = {
      {"llvmpipe (LLVM 15.0.6, 256 bits)",  // Mesa 22.3.6 lavapipe, AMD EPYC (AVX2)
       {
           {"lenticular-portrait", "7d69c9bfdca963cb526f20b4f5acdf9f52b4970be5902600f326d0b9e0699cee"},
           {"lenticular-gen3", "adf81cd8bf6a77c0a57fbf158278907f1a0fe9aefd10e49bb24e57da6e713325"},
           {"quilt-portrait", "8741fa283bffde270ac3e33c204928a3cc34f788675dd3d012bac2ef5e3c1d7e"},
           {"pinhole", "834b608091ebd57fc0c50e24defbf2005af112f3406c181a54b69d8db7351a7a"},
           {"projector-array", "27601343de5acb0198e11e214e2d1c76ed636734a786ad92f87ac085dab0ba90"},
           {"integral", "072fbcd0ad39df4bced364122a85919cbf48b8dc825cf46a85a47d8d5dce053b"},
           {"capture-grid", "7b13c3795564c4b19fbeef1eedfe94dd1688ef8d90d0ec64f281896e3ce0b15e"},
           {"oblique", "ba632aba7d2c62025faa1bea0701de263cbd40046c2bef1d7f734373f1e72934"},
           {"ray-table", "6fefa1831ed44d4780810037491537f8d71ee96b705aacc36fc123afb0c06475"},
           {"lenticular-gaussian", "04f9bbf9cf94f548e068d66da75be6d54ec587b9bebebbe4604a1bfe0fcbb3f0"},
           {"lenticular-refined", "62e3514a440fb8613450f0b5d75d0f9502ebbcbd1143c07236835738d7e0c20c"},
           {"pinhole-tent-unspecialized", "b2523f3c2d2c562fb1e70cfb4016af8e9bddbc097d7cc9ca1947aee92c67850c"},
       }},
  };
  return table;
}

TEST(FramePin, EveryModelRendersTheSameBitsAsBefore) {
  const Scene scene = pinScene();
  gpu::Renderer renderer(sharedContext(), scene);
  const std::string device = sharedContext().device().name;
  const auto row = pinnedDigests().find(device);
  std::string printed;
  for (const PinCase& c : pinCases(scene.bounds())) {
    const gpu::RenderResult frame = renderer.render(c.camera, c.settings);
    ASSERT_FALSE(frame.rgba.empty()) << c.name;
    EXPECT_EQ(frame.nonFiniteSamples, 0u) << c.name;
    const std::string digest = sha256Hex(frame);
    printed += "      {\"" + std::string(c.name) + "\", \"" + digest + "\"},\n";
    if (row == pinnedDigests().end()) continue;
    const auto pinned = row->second.find(c.name);
    ASSERT_NE(pinned, row->second.end()) << "no pinned digest for case " << c.name << " on " << device;
    EXPECT_EQ(digest, pinned->second) << "case " << c.name << " renders different bits on " << device;
  }
  if (row == pinnedDigests().end()) {
    GTEST_SKIP() << "no digests pinned for device '" << device << "'; computed here:\n" << printed;
  }
  std::printf("device '%s', digests:\n%s", device.c_str(), printed.c_str());
}

}  // namespace
}  // namespace ht::test
