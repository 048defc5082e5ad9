// The start-up check's digests and verdicts: another display, scene or setting is named with its rank.
#include <gtest/gtest.h>

#include "camera_models/display_config.h"
#include "cluster/cluster_error.h"
#include "cluster/communicator.h"
#include "cluster/rank_identity.h"
#include "gpu/display_camera.h"

namespace ht::cluster {
namespace {

TEST(RankIdentity, DigestsFollowTheDisplayAndTheSettings) {
  const Bounds3 bounds = loadScene("builtin:sphere").bounds();
  DisplayConfig portrait = builtinDisplay("portrait");
  const std::string a = displayDigest(portrait.name, gpu::makeDisplayCamera(portrait, bounds));
  EXPECT_EQ(a, displayDigest(portrait.name, gpu::makeDisplayCamera(portrait, bounds)));
  EXPECT_EQ(a.size(), 64u);
  portrait.calibration->center += 0.01;
  EXPECT_NE(a, displayDigest(portrait.name, gpu::makeDisplayCamera(portrait, bounds)));
  const DisplayConfig go = builtinDisplay("go");
  EXPECT_NE(a, displayDigest(go.name, gpu::makeDisplayCamera(go, bounds)));
  gpu::RenderSettings settings;
  const std::string s = settingsDigest(settings);
  settings.seed = 1;
  EXPECT_NE(s, settingsDigest(settings));
  settings.progress = [](double) {};  // does not change pixels
  settings.region.rowFirst = 3;       // set per unit, not per job
  settings.seed = 0;
  EXPECT_EQ(s, settingsDigest(settings));
}

TEST(RankIdentity, MismatchesNameTheRankAndWhatDiffers) {
  const RankIdentity root{buildId(), "d0", "s0", "r0"};
  EXPECT_TRUE(identityMismatches({root, root, root}).empty());
  RankIdentity otherDisplay = root;
  otherDisplay.display = "d1";
  RankIdentity otherBuild = root;
  otherBuild.build = "holotrace 0.0.9";
  const std::vector<std::string> lines = identityMismatches({root, otherDisplay, root, otherBuild});
  ASSERT_EQ(lines.size(), 2u);
  EXPECT_NE(lines[0].find("rank 1 has another display config"), std::string::npos) << lines[0];
  EXPECT_NE(lines[1].find("rank 3 has another build"), std::string::npos) << lines[1];
}

TEST(RankIdentity, AOneRankJobAgreesWithItself) {
  const auto solo = Communicator::solo();
  EXPECT_NO_THROW(checkRankIdentities(*solo, {buildId(), "d", "s", "r"}));
  EXPECT_NE(buildId().find("holotrace "), std::string::npos);
}

}  // namespace
}  // namespace ht::cluster
