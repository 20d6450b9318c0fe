// runOrderedJobs: jobs prepared on several threads, finished one at a time
// in order, with no thread waiting on another's turn.
#include "driver/ordered_jobs.h"

#include <gtest/gtest.h>

#include <atomic>
#include <chrono>
#include <condition_variable>
#include <mutex>
#include <set>
#include <stdexcept>
#include <thread>
#include <vector>

namespace spire {
namespace {

using namespace std::chrono_literals;

TEST(OrderedJobs, FinishesInOrderOneAtATimeWhateverOrderJobsArePreparedIn) {
  constexpr size_t kJobs = 64;
  std::vector<size_t> finished;
  std::atomic<int> finishing{0};
  std::atomic<bool> overlapped{false};
  std::mutex idsMutex;
  std::set<std::thread::id> preparers;
  runOrderedJobs(kJobs, 4, [&](size_t job) -> JobFinish {
    {
      std::scoped_lock lock(idsMutex);
      preparers.insert(std::this_thread::get_id());
    }
    // Later jobs are quicker, so they are ready before earlier ones.
    std::this_thread::sleep_for(std::chrono::microseconds((kJobs - job) % 7 * 200));
    return [&, job] {
      if (finishing.fetch_add(1) != 0) overlapped = true;
      finished.push_back(job);
      std::this_thread::sleep_for(50us);
      finishing.fetch_sub(1);
    };
  });
  std::vector<size_t> expected(kJobs);
  for (size_t i = 0; i < kJobs; ++i) expected[i] = i;
  EXPECT_EQ(finished, expected);
  EXPECT_FALSE(overlapped);
  EXPECT_EQ(preparers.size(), 4u);
}

TEST(OrderedJobs, AThreadWhoseJobCannotFinishYetPreparesTheNextJobs) {
  // Job 0 is prepared last of all: it waits until every other job is
  // prepared, which needs the other thread to go on past job 1.
  constexpr size_t kJobs = 6;
  std::mutex mutex;
  std::condition_variable changed;
  size_t prepared = 0;
  bool waitedInVain = false;
  std::vector<size_t> finished;
  runOrderedJobs(kJobs, 2, [&](size_t job) -> JobFinish {
    std::unique_lock lock(mutex);
    if (job == 0) {
      waitedInVain = !changed.wait_for(lock, 10s, [&] { return prepared == kJobs - 1; });
    } else {
      ++prepared;
      changed.notify_all();
    }
    return [&, job] { finished.push_back(job); };
  });
  EXPECT_FALSE(waitedInVain);
  EXPECT_EQ(finished, (std::vector<size_t>{0, 1, 2, 3, 4, 5}));
}

TEST(OrderedJobs, AnExceptionSkipsOnlyItsJobAndIsRethrownAtTheEnd) {
  std::vector<size_t> finished;
  const auto run = [&] {
    runOrderedJobs(5, 3, [&](size_t job) -> JobFinish {
      if (job == 1) throw std::runtime_error("prepare 1");
      return [&, job] {
        if (job == 3) throw std::runtime_error("finish 3");
        finished.push_back(job);
      };
    });
  };
  EXPECT_THROW(run(), std::runtime_error);
  EXPECT_EQ(finished, (std::vector<size_t>{0, 2, 4}));
}

TEST(OrderedJobs, NoJobsOrNoThreadsRequested) {
  size_t calls = 0;
  runOrderedJobs(0, 4, [&](size_t) -> JobFinish { return [&] { ++calls; }; });
  EXPECT_EQ(calls, 0u);
  runOrderedJobs(3, 0, [&](size_t) -> JobFinish { return [&] { ++calls; }; });
  EXPECT_EQ(calls, 3u);
}

}  // namespace
}  // namespace spire
