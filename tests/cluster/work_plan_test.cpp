// The work plan: units cover every pixel of every frame exactly once, in frame, view and row order.
#include <gtest/gtest.h>

#include "cluster/work_plan.h"

namespace ht::cluster {
namespace {

gpu::FrameShape shapeOf(std::uint32_t width, std::uint32_t height, std::uint32_t views) {
  gpu::FrameShape s;
  s.width = width;
  s.height = height;
  s.views = views;
  return s;
}

TEST(WorkPlan, APanelIsCutIntoContiguousBandsThatCoverEveryRow) {
  for (const std::uint32_t height : {1u, 3u, 4u, 17u, 40u, 1000u}) {
    for (const int ranks : {1, 2, 3, 8}) {
      const std::vector<WorkUnit> units = planWork(shapeOf(8, height, 1), 1, ranks, WorkGrain::Auto);
      ASSERT_FALSE(units.empty());
      EXPECT_LE(units.size(), kBandsPerRank * static_cast<std::uint32_t>(ranks));
      std::uint32_t row = 0;
      for (const WorkUnit& u : units) {
        EXPECT_EQ(u.region.rowFirst, row);
        EXPECT_GE(u.region.rowCount, std::min(height, kMinBandRows));
        EXPECT_EQ(u.region.viewCount, 1u);
        row += u.region.rowCount;
      }
      EXPECT_EQ(row, height) << height << " rows, " << ranks << " ranks";
    }
  }
}

TEST(WorkPlan, MultiViewFramesAreCutByViewAndSequencesByFrame) {
  const std::vector<WorkUnit> views = planWork(shapeOf(8, 6, 5), 1, 2, WorkGrain::Auto);
  ASSERT_EQ(views.size(), 5u);
  for (std::uint32_t v = 0; v < 5; ++v) {
    EXPECT_EQ(views[v].region.viewFirst, v);
    EXPECT_EQ(views[v].region.viewCount, 1u);
    EXPECT_EQ(views[v].region.rowCount, 6u);
  }
  const std::vector<WorkUnit> frames = planWork(shapeOf(8, 6, 5), 6, 3, WorkGrain::Auto);
  ASSERT_EQ(frames.size(), 6u);
  EXPECT_EQ(frames[4].frame, 4u);
  EXPECT_EQ(frames[4].region.viewCount, 5u);
  EXPECT_EQ(planWork(shapeOf(8, 40, 1), 1, 4, WorkGrain::WholeViews).size(), 1u);
  EXPECT_EQ(planWork(shapeOf(8, 6, 5), 1, 4, WorkGrain::WholeFrames).size(), 1u);
}

TEST(WorkPlan, StaticOwnersAreContiguousBlocksOfNearlyEqualSize) {
  std::vector<int> count(3, 0);
  int last = 0;
  for (std::size_t u = 0; u < 70; ++u) {
    const int owner = staticOwner(u, 70, 3);
    EXPECT_GE(owner, last);
    last = owner;
    ++count[static_cast<std::size_t>(owner)];
  }
  for (const int c : count) EXPECT_NEAR(c, 70 / 3, 1);
}

}  // namespace
}  // namespace ht::cluster
