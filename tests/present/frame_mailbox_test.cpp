// frame_mailbox_test.cpp - one slot: the newest frame wins, replaced frames are counted, the putter never waits.
#include <gtest/gtest.h>

#include <thread>

#include "present/frame_mailbox.h"

namespace ht::present {
namespace {

PanelFrame frameOf(std::uint8_t value) {
  PanelFrame f;
  f.width = 1;
  f.height = 1;
  f.rgba = {value, value, value, 255};
  return f;
}

TEST(FrameMailbox, NewestFrameWinsAndDropsAreCounted) {
  FrameMailbox box;
  for (std::uint8_t i = 1; i <= 20; ++i) box.put(frameOf(i));
  auto f = box.take(std::chrono::milliseconds(0));
  ASSERT_TRUE(f);
  EXPECT_EQ(f->rgba[0], 20);
  EXPECT_EQ(f->sequence, 20u);
  EXPECT_EQ(box.submitted(), 20u);
  EXPECT_EQ(box.dropped(), 19u);
  EXPECT_EQ(box.take(std::chrono::milliseconds(1)), nullptr);  // taken frames are gone
}

TEST(FrameMailbox, TakenFramesAreNotDrops) {
  FrameMailbox box;
  box.put(frameOf(1));
  ASSERT_TRUE(box.take(std::chrono::milliseconds(0)));
  box.put(frameOf(2));
  ASSERT_TRUE(box.take(std::chrono::milliseconds(0)));
  EXPECT_EQ(box.dropped(), 0u);
}

TEST(FrameMailbox, TakeWakesOnPutAndOnClose) {
  FrameMailbox box;
  std::thread putter([&] {
    std::this_thread::sleep_for(std::chrono::milliseconds(20));
    box.put(frameOf(7));
  });
  auto f = box.take(std::chrono::seconds(10));
  putter.join();
  ASSERT_TRUE(f);
  EXPECT_EQ(f->rgba[0], 7);
  EXPECT_NE(f->done, Clock::time_point{});
  std::thread closer([&] {
    std::this_thread::sleep_for(std::chrono::milliseconds(20));
    box.close();
  });
  auto start = Clock::now();
  EXPECT_EQ(box.take(std::chrono::seconds(10)), nullptr);
  closer.join();
  EXPECT_LT(Clock::now() - start, std::chrono::seconds(5));
}

}  // namespace
}  // namespace ht::present
