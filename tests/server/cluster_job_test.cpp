// cluster_job_test.cpp - the frame job rank 0 of holotraced under mpirun sends its ranks (server/cluster_job.h):
// every field survives the bytes; a cut or padded job is a ClusterError, never a partial job.
#include <gtest/gtest.h>

#include "cluster/cluster_error.h"
#include "server/cluster_job.h"

namespace ht::server {
namespace {

ClusterJob fullJob() {
  ClusterJob job;
  job.sceneVersion = 42;
  job.sceneBytes = {1, 2, 3, 4, 5};
  job.dropVersions = {7, 9};
  job.loadBounds.extend({-1.0f, -2.0f, -3.0f});
  job.loadBounds.extend({1.0f, 2.0f, 3.0f});
  job.displayId = "wall";
  job.cameraDigest = std::string(64, 'a');
  job.cameraTarget = glm::dvec3(0.5, -0.25, 2.0);
  job.observerHeight = 12.5;
  job.path = gpu::CameraPath::Quilt;
  job.settings.spp = 3;
  job.settings.filter = gpu::SampleFilter::Tent;
  job.settings.maxDepth = 2;
  job.settings.seed = 77;
  job.settings.refineSpp = 8;
  job.settings.refineContrast = 0.125f;
  job.settings.forceAllFeatures = true;
  return job;
}

TEST(ClusterJobTest, EveryFieldSurvivesTheBytes) {
  const ClusterJob in = fullJob();
  const ClusterJob out = decodeClusterJob(encodeClusterJob(in));
  EXPECT_EQ(out.kind, ClusterJob::Kind::Frame);
  EXPECT_EQ(out.sceneVersion, 42u);
  EXPECT_EQ(out.sceneBytes, in.sceneBytes);
  EXPECT_EQ(out.dropVersions, in.dropVersions);
  EXPECT_EQ(out.loadBounds.lo, in.loadBounds.lo);
  EXPECT_EQ(out.loadBounds.hi, in.loadBounds.hi);
  EXPECT_EQ(out.displayId, "wall");
  EXPECT_EQ(out.cameraDigest, in.cameraDigest);
  ASSERT_TRUE(out.cameraTarget);
  EXPECT_EQ(*out.cameraTarget, *in.cameraTarget);
  EXPECT_FALSE(out.cameraSize);
  EXPECT_FALSE(out.observerDistance);
  ASSERT_TRUE(out.observerHeight);
  EXPECT_EQ(*out.observerHeight, 12.5);
  EXPECT_EQ(out.path, gpu::CameraPath::Quilt);
  EXPECT_EQ(out.settings.spp, 3u);
  EXPECT_EQ(out.settings.filter, gpu::SampleFilter::Tent);
  EXPECT_EQ(out.settings.maxDepth, 2u);
  EXPECT_EQ(out.settings.seed, 77u);
  EXPECT_EQ(out.settings.refineSpp, 8u);
  EXPECT_EQ(out.settings.refineContrast, 0.125f);
  EXPECT_TRUE(out.settings.forceAllFeatures);
}

TEST(ClusterJobTest, AStopJobCarriesNothingElse) {
  ClusterJob stop;
  stop.kind = ClusterJob::Kind::Stop;
  const ClusterJob out = decodeClusterJob(encodeClusterJob(stop));
  EXPECT_EQ(out.kind, ClusterJob::Kind::Stop);
  EXPECT_TRUE(out.sceneBytes.empty());
  EXPECT_TRUE(out.displayId.empty());
}

TEST(ClusterJobTest, ACutOrPaddedJobIsRefused) {
  const std::vector<std::uint8_t> bytes = encodeClusterJob(fullJob());
  for (const std::size_t keep : {std::size_t{0}, std::size_t{10}, bytes.size() - 1}) {
    EXPECT_THROW(decodeClusterJob(std::span(bytes.data(), keep)), cluster::ClusterError) << keep;
  }
  std::vector<std::uint8_t> padded = bytes;
  padded.push_back(0);
  EXPECT_THROW(decodeClusterJob(padded), cluster::ClusterError);
}

}  // namespace
}  // namespace ht::server
