// wall_loop_test.cpp - the live wall's frame loop and report in one process (cluster/wall_loop.h, wall_report.h):
// the loop's order of render and present per frame, --seconds ending on a common last frame, and the summary of
// hand-made records of three ranks (late, skipped and timed-out frames, barrier cost, flip skew).
#include "cluster/wall_loop.h"

#include <gtest/gtest.h>

#include "cluster/wall_report.h"

namespace ht::cluster {
namespace {

TEST(WallLoop, OneRankRendersAndPresentsEveryFrameInOrder) {
  const auto comm = Communicator::solo();
  std::vector<std::string> calls;
  WallCallbacks callbacks;
  JobClock clock;
  callbacks.render = [&](std::uint32_t f) { calls.push_back("render " + std::to_string(f)); };
  callbacks.present = [&](std::uint32_t f) {
    calls.push_back("present " + std::to_string(f));
    return clock.nowUs();
  };
  callbacks.warn = [&](const std::string& line) { calls.push_back("warn " + line); };
  WallLoopOptions options;
  options.frames = 3;
  const std::vector<WallFrameRecord> records = runWallLoop(*comm, options, callbacks, clock);
  EXPECT_EQ(calls,
            (std::vector<std::string>{"render 0", "present 0", "render 1", "present 1", "render 2", "present 2"}));
  ASSERT_EQ(records.size(), 3u);
  for (const WallFrameRecord& r : records) {
    EXPECT_EQ(r.outcome, WallOutcome::OnTime);
    EXPECT_EQ(r.firstEntryUs, r.entryUs);
    EXPECT_LE(r.entryUs, r.releaseUs);
    EXPECT_LE(r.releaseUs, r.flipUs);
  }
  const WallSummary s = summarizeWall(records, 1);
  EXPECT_EQ(s.frames, 3u);
  EXPECT_EQ(s.ranks[0].presented, 3u);
  EXPECT_EQ(s.syncedFrames, 3u);
  EXPECT_EQ(s.flipSkewMaxUs, 0.0);
}

TEST(WallLoop, SecondsEndWithOneMoreCommonFrame) {
  const auto comm = Communicator::solo();
  WallCallbacks callbacks;
  JobClock clock;
  std::uint32_t rendered = 0;
  callbacks.render = [&](std::uint32_t) { ++rendered; };
  callbacks.present = [&](std::uint32_t) { return clock.nowUs(); };
  callbacks.warn = [](const std::string&) {};
  WallLoopOptions options;
  options.seconds = 1e-6;  // over before the second frame
  const std::vector<WallFrameRecord> records = runWallLoop(*comm, options, callbacks, clock);
  EXPECT_EQ(rendered, 2u) << "frame 0, then the agreed last frame";
  EXPECT_EQ(records.size(), 2u);
}

WallFrameRecord onTime(std::int64_t entry, std::int64_t release, std::int64_t flip) {
  WallFrameRecord r;
  r.outcome = WallOutcome::OnTime;
  r.renderUs = 1000;
  r.entryUs = entry;
  r.releaseUs = release;
  r.flipUs = flip;
  r.presentUs = 200;
  return r;
}

TEST(WallReport, SummarisesThreeRanksWithALateRank) {
  // Frame 0: all on time, rank 2 enters last (waits 10 us). Frame 1: rank 1 late, the others time out.
  // Frame 2: rank 1 skipped it. Frame 3: all on time again, rank 0 last.
  std::vector<WallFrameRecord> all(12);
  all[0] = onTime(100, 130, 400);
  all[4] = onTime(110, 131, 430);
  all[8] = onTime(120, 130, 410);
  for (int r : {0, 2}) {
    all[std::size_t(r) * 4 + 1] = onTime(2000, 52000, 52100);
    all[std::size_t(r) * 4 + 1].outcome = WallOutcome::TimedOut;
    all[std::size_t(r) * 4 + 2] = onTime(60000, 60100, 60200);
  }
  all[5].outcome = WallOutcome::Late;
  all[5].renderUs = 300000;
  all[5].entryUs = 302000;
  all[5].releaseUs = 302010;
  all[5].lateByUs = 250000;
  all[6].outcome = WallOutcome::Skipped;
  all[6].entryUs = 302020;
  all[3] = onTime(70000, 70005, 70300);
  all[7] = onTime(69000, 70006, 70350);
  all[11] = onTime(69500, 70004, 70320);
  const WallSummary s = summarizeWall(all, 3);
  EXPECT_EQ(s.frames, 4u);
  EXPECT_EQ(s.ranks[0].presented, 4u);
  EXPECT_EQ(s.ranks[0].timedOut, 1u);
  EXPECT_EQ(s.ranks[1].presented, 2u);
  EXPECT_EQ(s.ranks[1].late, 1u);
  EXPECT_EQ(s.ranks[1].skipped, 1u);
  ASSERT_EQ(s.late.size(), 1u);
  EXPECT_EQ(s.late[0].rank, 1);
  EXPECT_EQ(s.late[0].frame, 1u);
  EXPECT_DOUBLE_EQ(s.late[0].lateByMs, 250.0);
  EXPECT_EQ(s.syncedFrames, 2u);                 // frames 0 and 3
  EXPECT_DOUBLE_EQ(s.barrierCostMedianUs, 7.5);  // the last rank's waits: 10 (frame 0) and 5 (frame 3)
  EXPECT_DOUBLE_EQ(s.releaseSkewMedianUs, 1.5);  // 1 and 2
  EXPECT_DOUBLE_EQ(s.flipSkewMedianUs, 40.0);    // 30 and 50
  EXPECT_DOUBLE_EQ(s.flipSkewMaxUs, 50.0);
  EXPECT_THROW(summarizeWall(std::span(all).first(11), 3), ClusterError);
}

}  // namespace
}  // namespace ht::cluster
