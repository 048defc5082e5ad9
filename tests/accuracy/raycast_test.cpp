// `holotrace raycast` and its file formats (cli/rays_file.h): binary and CSV round trips, malformed files
// refused with the file and record named (truncated, bad magic, count mismatch, a huge count claim refused
// before allocation), and the command's hits equal to the CPU reference on the same scene.
#include <gtest/gtest.h>

#include <cstring>
#include <fstream>
#include <limits>
#include <sstream>

#include "bvh/cpu_traversal.h"
#include "cli/cli_app.h"
#include "cli/raycast_command.h"
#include "cli/rays_file.h"
#include "common/error.h"
#include "interior_rays.h"
#include "scene/scene.h"
#include "test_meshes.h"
#include "tests/common/temp_directory.h"

namespace ht::cli {
namespace {

using gpu_shared::HtHit;
using gpu_shared::HtRay;
using ht::test::TempDirectory;

std::vector<HtRay> sampleRays() {
  const float inf = std::numeric_limits<float>::infinity();
  auto rays = accuracy::mixedInteriorRays(accuracy::icosphere(2), 97, 4);
  rays.push_back(HtRay{{1e-30f, -3e38f, 0.1f}, 0.0f, {0.0f, 1.0f, 0.0f}, inf});
  return rays;
}

void writeBytes(const std::filesystem::path& path, const std::string& bytes) {
  std::ofstream(path, std::ios::binary) << bytes;
}

std::string readBytes(const std::filesystem::path& path) {
  std::ifstream in(path, std::ios::binary);
  std::ostringstream s;
  s << in.rdbuf();
  return s.str();
}

// The IoError message of reading `path`, or "" if it was read.
std::string readError(const std::filesystem::path& path) {
  try {
    readRaysFile(path);
  } catch (const IoError& e) { return e.what(); }
  return "";
}

TEST(RaysFile, BinaryAndCsvRoundTripsAreExact) {
  TempDirectory dir;
  const auto rays = sampleRays();
  for (const char* name : {"rays.bin", "rays.csv"}) {
    writeRaysFile(dir.path() / name, rays);
    const auto back = readRaysFile(dir.path() / name);
    ASSERT_EQ(back.size(), rays.size()) << name;
    EXPECT_EQ(std::memcmp(back.data(), rays.data(), rays.size() * sizeof(HtRay)), 0) << name;
  }
  EXPECT_EQ(readBytes(dir.path() / "rays.bin").size(), kRaysHeaderBytes + rays.size() * kRayRecordBytes);
  const std::vector<HtHit> hits = {{1.5f, 7u, 0.25f, 0.5f}, {3e38f, gpu_shared::HT_MISS, 0.0f, 0.0f}};
  writeHitsFile(dir.path() / "hits.bin", hits);
  const auto hitsBack = readHitsFile(dir.path() / "hits.bin");
  ASSERT_EQ(hitsBack.size(), hits.size());
  EXPECT_EQ(std::memcmp(hitsBack.data(), hits.data(), hits.size() * sizeof(HtHit)), 0);
}

TEST(RaysFile, MalformedBinaryFilesNameTheFileAndProblem) {
  TempDirectory dir;
  const auto rays = sampleRays();
  writeRaysFile(dir.path() / "good.bin", rays);
  const std::string good = readBytes(dir.path() / "good.bin");

  writeBytes(dir.path() / "truncated.bin", good.substr(0, good.size() - 5));
  EXPECT_NE(readError(dir.path() / "truncated.bin").find("truncated"), std::string::npos);
  writeBytes(dir.path() / "short.bin", good.substr(0, 10));
  EXPECT_NE(readError(dir.path() / "short.bin").find("header: truncated"), std::string::npos);

  std::string magic = good;
  magic[0] = 'X';
  writeBytes(dir.path() / "magic.bin", magic);
  EXPECT_NE(readError(dir.path() / "magic.bin").find("bad magic"), std::string::npos);

  std::string extra = good + std::string(32, '\0');  // one record more than the header claims
  writeBytes(dir.path() / "extra.bin", extra);
  const std::string extraError = readError(dir.path() / "extra.bin");
  EXPECT_NE(extraError.find("extra.bin"), std::string::npos);
  EXPECT_NE(extraError.find("count " + std::to_string(rays.size())), std::string::npos) << extraError;

  // 2^61 rays claimed by a 16-byte file: refused from the header alone (no 64 EiB allocation attempted).
  std::string huge = good.substr(0, 16);
  const std::uint64_t claim = std::uint64_t(1) << 61;
  std::memcpy(huge.data() + 8, &claim, sizeof(claim));
  writeBytes(dir.path() / "huge.bin", huge);
  EXPECT_NE(readError(dir.path() / "huge.bin").find("does not match the file size"), std::string::npos);

  std::string badRecord = good;
  const float nan = std::numeric_limits<float>::quiet_NaN();
  std::memcpy(badRecord.data() + 16 + 3 * 32 + 28, &nan, sizeof(nan));  // record 3's tmax
  writeBytes(dir.path() / "record.bin", badRecord);
  EXPECT_NE(readError(dir.path() / "record.bin").find("record 3"), std::string::npos);

  EXPECT_NE(readError(dir.path() / "absent.bin").find("cannot open"), std::string::npos);
}

TEST(RaysFile, MalformedCsvNamesTheLine) {
  TempDirectory dir;
  writeBytes(dir.path() / "a.csv", "ox,oy,oz,tmin,dx,dy,dz,tmax\n0,0,0,0,0,0,1,10\n# note\n0,0,0,0,0,1\n");
  EXPECT_NE(readError(dir.path() / "a.csv").find("line 4: expected 8"), std::string::npos);
  writeBytes(dir.path() / "b.csv", "0,0,0,0,0,0,1,10\n0,0,zero,0,0,0,1,10\n");
  EXPECT_NE(readError(dir.path() / "b.csv").find("line 2: field 3 'zero'"), std::string::npos);
  writeBytes(dir.path() / "c.csv", "0,0,0,5,0,0,1,1\n");
  EXPECT_NE(readError(dir.path() / "c.csv").find("line 1: tmin/tmax"), std::string::npos);
}

TEST(RaycastCommand, HitsEqualTheCpuReference) {
  TempDirectory dir;
  const Scene scene = loadScene("builtin:sphere");
  std::vector<HtRay> rays;
  for (int i = 0; i < 64; ++i) {
    const float x = -1.5f + 3.0f * static_cast<float>(i) / 63.0f;
    rays.push_back(HtRay{{x, 0.1f, 5.0f}, 0.0f, {0.0f, 0.0f, -1.0f}, 3e38f});
  }
  writeRaysFile(dir.path() / "rays.bin", rays);
  std::ostringstream out;
  const std::vector<std::string> args = {"--scene", "builtin:sphere",
                                         "--rays",  (dir.path() / "rays.bin").string(),
                                         "-o",      (dir.path() / "hits.bin").string()};
  ASSERT_EQ(runRaycast(args, out), kExitOk) << out.str();
  const auto hits = readHitsFile(dir.path() / "hits.bin");
  const bvh::GpuBvh bvh = bvh::buildGpuBvh(scene.positions, scene.triangles, bvh::BuildOptions{});
  ASSERT_EQ(hits.size(), rays.size());
  int hitCount = 0;
  for (size_t i = 0; i < rays.size(); ++i) {
    const HtHit expected = bvh::traceClosest(bvh, rays[i]).hit;
    EXPECT_EQ(hits[i].triId, expected.triId) << "ray " << i;
    EXPECT_EQ(hits[i].t, expected.t) << "ray " << i;
    hitCount += expected.triId != gpu_shared::HT_MISS;
  }
  EXPECT_GT(hitCount, 0);
  EXPECT_LT(hitCount, 64);
}

TEST(RaycastCommand, MissingOptionsAndBadFilesAreErrors) {
  TempDirectory dir;
  std::ostringstream out;
  const std::vector<std::string> noRays = {"--scene", "builtin:sphere", "-o", (dir.path() / "h.bin").string()};
  EXPECT_THROW(runRaycast(noRays, out), UsageError);
  writeBytes(dir.path() / "bad.bin", "HTRY");
  const std::vector<std::string> bad = {
      "--scene", "builtin:sphere", "--rays", (dir.path() / "bad.bin").string(), "-o", (dir.path() / "h.bin").string()};
  EXPECT_THROW(runRaycast(bad, out), IoError);
  EXPECT_FALSE(std::filesystem::exists(dir.path() / "h.bin"));
}

}  // namespace
}  // namespace ht::cli
