#include "driver/ordered_jobs.h"

#include <algorithm>
#include <atomic>
#include <exception>
#include <mutex>
#include <optional>
#include <thread>
#include <vector>

namespace spire {
namespace {

// Holds prepared jobs until their turn; whichever thread hands in the job
// that is next in order runs every finish that is then ready, so no thread
// ever blocks on another's turn.
class InOrderFinisher {
 public:
  explicit InOrderFinisher(size_t count) : ready_(count) {}

  void submit(size_t job, JobFinish finish) {
    std::unique_lock lock(mutex_);
    ready_[job] = std::move(finish);
    if (finishing_) return;  // the thread that is finishing will take it
    finishing_ = true;
    while (next_ < ready_.size() && ready_[next_]) {
      JobFinish current = std::move(*ready_[next_]);
      ready_[next_].reset();
      ++next_;
      lock.unlock();
      run(current);
      lock.lock();
    }
    finishing_ = false;
  }

  void fail(std::exception_ptr error) {
    std::scoped_lock lock(mutex_);
    if (!firstError_) firstError_ = std::move(error);
  }

  void rethrowFirstError() const {
    if (firstError_) std::rethrow_exception(firstError_);
  }

 private:
  void run(const JobFinish& finish) {
    try {
      if (finish) finish();
    } catch (...) {
      fail(std::current_exception());
    }
  }

  std::mutex mutex_;
  std::vector<std::optional<JobFinish>> ready_;
  size_t next_ = 0;
  bool finishing_ = false;
  std::exception_ptr firstError_;
};

}  // namespace

void runOrderedJobs(size_t count, unsigned threads, const std::function<JobFinish(size_t)>& prepare) {
  InOrderFinisher finisher(count);
  std::atomic<size_t> nextJob{0};
  const auto work = [&] {
    for (size_t job; (job = nextJob.fetch_add(1)) < count;) {
      JobFinish finish;
      try {
        finish = prepare(job);
      } catch (...) {
        finisher.fail(std::current_exception());
      }
      finisher.submit(job, std::move(finish));
    }
  };
  const size_t helpers = std::min<size_t>(std::max(1U, threads), count) - (count > 0 ? 1 : 0);
  {
    std::vector<std::jthread> pool;
    for (size_t i = 0; i < helpers; ++i) pool.emplace_back(work);
    work();
  }
  finisher.rethrowFirstError();
}

}  // namespace spire
