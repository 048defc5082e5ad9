// dispatchWork in a one-rank job (no MPI): every unit is rendered once and reaches the sink once, dynamic or static;
// a failing unit's exception comes out of dispatchWork.
#include <gtest/gtest.h>

#include <atomic>
#include <chrono>
#include <stdexcept>
#include <thread>

#include "cluster/communicator.h"
#include "cluster/work_dispatch.h"

namespace ht::cluster {
namespace {

TEST(WorkDispatch, EveryUnitIsRenderedOnceAndCollectedOnce) {
  gpu::FrameShape shape;
  shape.width = 4;
  shape.height = 30;
  const std::vector<WorkUnit> units = planWork(shape, 1, 3, WorkGrain::Auto);
  for (const Assignment assignment : {Assignment::Dynamic, Assignment::Static}) {
    const auto comm = Communicator::solo();
    std::vector<int> rendered(units.size(), 0), collected(units.size(), 0);
    const DispatchReport report = dispatchWork(
        *comm, units,
        [&](const WorkUnit& u) {
          ++rendered[static_cast<std::size_t>(&u - units.data())];
          return std::vector<float>(u.pixels(shape.width) * 4, static_cast<float>(u.region.rowFirst));
        },
        [&](std::size_t unit, std::vector<float>&& rgba) {
          ++collected[unit];
          EXPECT_EQ(rgba.size(), units[unit].pixels(shape.width) * 4);
          EXPECT_EQ(rgba.front(), static_cast<float>(units[unit].region.rowFirst));
        },
        assignment);
    EXPECT_EQ(rendered, std::vector<int>(units.size(), 1));
    EXPECT_EQ(collected, std::vector<int>(units.size(), 1));
    ASSERT_EQ(report.ranks.size(), 1u);
    EXPECT_EQ(report.ranks[0].units, units.size());
    EXPECT_EQ(report.gatherBytes, 0u);
  }
}

TEST(WorkDispatch, ARenderFailureLeavesDispatchWork) {
  const auto comm = Communicator::solo();
  gpu::FrameShape shape;
  shape.width = 2;
  shape.height = 2;
  shape.views = 3;
  const std::vector<WorkUnit> units = planWork(shape, 1, 1, WorkGrain::Auto);
  EXPECT_THROW(dispatchWork(
                   *comm, units,
                   [](const WorkUnit& u) -> std::vector<float> {
                     if (u.region.viewFirst == 1) throw std::runtime_error("unit failed");
                     return std::vector<float>(16, 0.0f);
                   },
                   [](std::size_t, std::vector<float>&&) {}),
               std::runtime_error);
}

TEST(WorkDispatch, AFailingSinkStopsRankZerosRenderingEarly) {
  const auto comm = Communicator::solo();
  gpu::FrameShape shape;
  shape.width = 1;
  shape.height = 1;
  shape.views = 100;
  const std::vector<WorkUnit> units = planWork(shape, 1, 1, WorkGrain::Auto);
  std::atomic<int> rendered{0};
  EXPECT_THROW(dispatchWork(
                   *comm, units,
                   [&](const WorkUnit&) {
                     ++rendered;
                     std::this_thread::sleep_for(std::chrono::milliseconds(5));
                     return std::vector<float>(4, 0.0f);
                   },
                   [](std::size_t, std::vector<float>&&) { throw std::runtime_error("disk full"); }),
               std::runtime_error);
  EXPECT_LT(rendered.load(), 100);  // not the whole job after the failure
}

}  // namespace
}  // namespace ht::cluster
