// render_worker_test.cpp - RenderWorker's scheduling, observed directly: jobs are taken round-robin across clients,
// so a client that keeps its queue full (a flood) delays another client's job by at most one job per other busy
// client, never by its whole backlog; the per-client in-flight limit refuses before queueing.
#include "server/render_worker.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <future>
#include <mutex>
#include <thread>
#include <vector>

#include "server/path_rules.h"

namespace ht::server::test {
namespace {

struct RunLog {
  std::mutex mutex;
  std::vector<std::string> order;
  RenderWorker::Job job(const std::string& name) {
    return [this, name](gpu::VulkanContext&) {
      std::lock_guard lock(mutex);
      order.push_back(name);
    };
  }
};

class RenderWorkerTest : public ::testing::Test {
 protected:
  static void SetUpTestSuite() { context_ = new gpu::VulkanContext({-1, false}); }
  static void TearDownTestSuite() { delete context_; }
  static gpu::VulkanContext* context_;
};
gpu::VulkanContext* RenderWorkerTest::context_ = nullptr;

TEST_F(RenderWorkerTest, FloodingClientsDelayAnotherClientByOneJobEach) {
  constexpr int kFlooders = 5, kDepth = 4;
  RenderWorker worker(*context_, kDepth);
  RunLog log;
  std::promise<void> gate;
  std::shared_future<void> open = gate.get_future().share();
  auto blocker = worker.submit("blocker", [open](gpu::VulkanContext&) { open.wait(); });
  std::vector<std::future<void>> done;
  for (int f = 0; f < kFlooders; ++f) {  // each flooder's whole backlog is queued before the victim arrives
    for (int j = 0; j < kDepth; ++j) {
      const std::string name = "flood" + std::to_string(f) + "." + std::to_string(j);
      done.push_back(worker.submit("flood" + std::to_string(f), log.job(name)));
    }
  }
  done.push_back(worker.submit("victim", log.job("victim")));
  gate.set_value();
  for (auto& d : done) d.get();
  blocker.get();
  const auto at = std::find(log.order.begin(), log.order.end(), "victim") - log.order.begin();
  EXPECT_EQ(at, kFlooders) << "FIFO would run it at " << kFlooders * kDepth;  // one job of each flooder first
  for (int f = 0; f < kFlooders; ++f) EXPECT_EQ(log.order[f], "flood" + std::to_string(f) + ".0");
}

TEST_F(RenderWorkerTest, PerClientInFlightLimitRefusesBeforeQueueing) {
  RenderWorker worker(*context_, 2);
  std::promise<void> gate;
  std::shared_future<void> open = gate.get_future().share();
  auto a = worker.submit("c", [open](gpu::VulkanContext&) { open.wait(); });
  auto b = worker.submit("c", [](gpu::VulkanContext&) {});
  EXPECT_THROW(worker.submit("c", [](gpu::VulkanContext&) {}), LimitExceeded);
  auto other = worker.submit("other", [](gpu::VulkanContext&) {});  // the limit is per client
  gate.set_value();
  a.get();
  b.get();
  other.get();
  EXPECT_NO_THROW(worker.submit("c", [](gpu::VulkanContext&) {}).get());  // slots come back when jobs finish
}

TEST_F(RenderWorkerTest, StopFailsQueuedJobsWithShuttingDown) {
  RenderWorker worker(*context_, 4);
  std::promise<void> gate, started;
  std::shared_future<void> open = gate.get_future().share();
  auto running = worker.submit("c", [open, &started](gpu::VulkanContext&) {
    started.set_value();
    open.wait();
  });
  auto queued = worker.submit("c", [](gpu::VulkanContext&) {});
  started.get_future().wait();
  std::thread stopper([&] { worker.stop(); });
  std::this_thread::sleep_for(std::chrono::milliseconds(50));
  gate.set_value();
  stopper.join();
  EXPECT_NO_THROW(running.get());
  EXPECT_THROW(queued.get(), ShuttingDown);
  EXPECT_THROW(worker.submit("c", [](gpu::VulkanContext&) {}), ShuttingDown);
}

}  // namespace
}  // namespace ht::server::test
