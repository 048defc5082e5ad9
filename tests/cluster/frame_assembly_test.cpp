// Frame assembly: units placed in any order give the whole frame; wrong sizes and repeated units are refused.
#include <gtest/gtest.h>

#include <algorithm>

#include "cluster/cluster_error.h"
#include "cluster/frame_assembly.h"

namespace ht::cluster {
namespace {

// The value every float of pixel (view, row, x, channel) has in the expected frame.
float valueAt(std::uint32_t view, std::uint32_t row, std::uint32_t x, std::uint32_t c) {
  return static_cast<float>(((view * 100 + row) * 100 + x) * 4 + c);
}

std::vector<float> unitPixels(const WorkUnit& u, std::uint32_t width) {
  std::vector<float> rgba;
  for (std::uint32_t v = u.region.viewFirst; v < u.region.viewFirst + u.region.viewCount; ++v)
    for (std::uint32_t r = u.region.rowFirst; r < u.region.rowFirst + u.region.rowCount; ++r)
      for (std::uint32_t x = 0; x < width; ++x)
        for (std::uint32_t c = 0; c < 4; ++c) rgba.push_back(valueAt(v, r, x, c));
  return rgba;
}

TEST(FrameAssembly, UnitsInAnyOrderMakeTheWholeFrames) {
  gpu::FrameShape shape;
  shape.width = 5;
  shape.height = 9;
  shape.views = 1;
  const std::vector<WorkUnit> units = planWork(shape, 1, 2, WorkGrain::Auto);
  ASSERT_GT(units.size(), 1u);
  FrameAssembly assembly(shape, units);
  std::vector<std::size_t> order(units.size());
  for (std::size_t i = 0; i < order.size(); ++i) order[i] = order.size() - 1 - i;
  for (std::size_t k = 0; k < order.size(); ++k) {
    const auto done = assembly.place(order[k], unitPixels(units[order[k]], shape.width));
    EXPECT_EQ(done.has_value(), k + 1 == order.size());
  }
  const gpu::RenderResult frame = assembly.take(0);
  EXPECT_EQ(frame.rgba, unitPixels({0, {0, 1, 0, 9}}, 5));
}

TEST(FrameAssembly, ViewsOfSeveralFramesAreKeptApart) {
  gpu::FrameShape shape;
  shape.width = 3;
  shape.height = 2;
  shape.views = 4;
  std::vector<WorkUnit> units;
  for (std::uint32_t f = 0; f < 2; ++f)
    for (std::uint32_t v = 0; v < 4; ++v) units.push_back({f, {v, 1, 0, 2}});
  FrameAssembly assembly(shape, units);
  for (std::size_t u = 0; u < 3; ++u) EXPECT_FALSE(assembly.place(u + 4, unitPixels(units[u + 4], 3)));
  EXPECT_THROW(assembly.take(1), ClusterError);  // not complete yet
  EXPECT_EQ(assembly.place(7, unitPixels(units[7], 3)), 1u);
  EXPECT_EQ(assembly.take(1).rgba.size(), 3u * 2 * 4 * 4);
  for (std::size_t u = 0; u < 3; ++u) EXPECT_FALSE(assembly.place(u, unitPixels(units[u], 3)));
  EXPECT_EQ(assembly.place(3, unitPixels(units[3], 3)), 0u);
  EXPECT_EQ(assembly.take(0).rgba, unitPixels({0, {0, 4, 0, 2}}, 3));
}

TEST(FrameAssembly, WrongSizesAndRepeatedUnitsAreRefused) {
  gpu::FrameShape shape;
  shape.width = 2;
  shape.height = 2;
  const std::vector<WorkUnit> units = {{0, {0, 1, 0, 1}}, {0, {0, 1, 1, 1}}};
  FrameAssembly assembly(shape, units);
  EXPECT_THROW(assembly.place(0, std::vector<float>(7)), ClusterError);
  EXPECT_FALSE(assembly.place(0, std::vector<float>(8)));
  EXPECT_THROW(assembly.place(0, std::vector<float>(8)), ClusterError);
  EXPECT_THROW(assembly.place(2, std::vector<float>(8)), ClusterError);
}

}  // namespace
}  // namespace ht::cluster
