// The explorer's compile worker: a request that arrives while another
// compiles replaces any request still waiting, a reload asked for by a
// replaced request is not lost, and results come back tagged.
#include <gtest/gtest.h>

#include <chrono>
#include <condition_variable>
#include <mutex>
#include <thread>
#include <utility>
#include <vector>

#include "explore/live_compiler.h"

namespace spire::explore {
namespace {

TEST(LiveCompiler, TheLatestRequestWinsAndAReloadIsKept) {
  std::mutex mutex;
  std::condition_variable changed;
  bool release = false;
  std::vector<std::pair<uint64_t, bool>> started;
  LiveCompiler compiler([&](const CompileJob& job, CompileOutcome& outcome) {
    std::unique_lock lock(mutex);
    started.emplace_back(job.request, job.reload);
    changed.notify_all();
    changed.wait(lock, [&] { return release; });
    outcome.program = engine::Error{"compiled " + std::to_string(job.request) + " with " +
                                    std::to_string(job.placement.size()) + " decisions"};
  });
  compiler.submit({1, {}, {}, false, {}});
  {
    std::unique_lock lock(mutex);
    ASSERT_TRUE(changed.wait_for(lock, std::chrono::seconds(10), [&] { return !started.empty(); }));
  }
  compiler.submit({2, {}, {}, true, {}});
  compiler.submit({3, {{"albedo", "Fragment"}}, {}, false, {}});
  EXPECT_TRUE(compiler.busy());
  {
    const std::lock_guard lock(mutex);
    release = true;
  }
  changed.notify_all();
  std::optional<CompileOutcome> last;
  const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(10);
  while ((!last || last->request != 3) && std::chrono::steady_clock::now() < deadline) {
    if (auto outcome = compiler.poll()) last = std::move(outcome);
    std::this_thread::sleep_for(std::chrono::milliseconds(1));
  }
  ASSERT_TRUE(last && last->request == 3);
  ASSERT_FALSE(last->program);
  EXPECT_EQ(last->program.error().message, "compiled 3 with 1 decisions");
  EXPECT_GE(last->milliseconds, 0.0);
  const std::lock_guard lock(mutex);
  EXPECT_EQ(started, (std::vector<std::pair<uint64_t, bool>>{{1, false}, {3, true}}));
  EXPECT_FALSE(compiler.busy());
}

}  // namespace
}  // namespace spire::explore
