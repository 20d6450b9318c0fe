#include "explore/live_compiler.h"

#include <chrono>

namespace spire::explore {

LiveCompiler::LiveCompiler(CompileFunction compile) : compile_(std::move(compile)), worker_([this] { run(); }) {}

LiveCompiler::~LiveCompiler() {
  {
    const std::lock_guard lock(mutex_);
    stopping_ = true;
    queued_.reset();
  }
  wake_.notify_all();
  worker_.join();
}

void LiveCompiler::submit(CompileJob job) {
  {
    const std::lock_guard lock(mutex_);
    job.reload = job.reload || (queued_ && queued_->reload);
    queued_ = std::move(job);
  }
  wake_.notify_all();
}

std::optional<CompileOutcome> LiveCompiler::poll() {
  const std::lock_guard lock(mutex_);
  if (done_.empty()) return std::nullopt;
  // Only the newest result is worth showing.
  CompileOutcome outcome = std::move(done_.back());
  done_.clear();
  return outcome;
}

bool LiveCompiler::busy() const {
  const std::lock_guard lock(mutex_);
  return compiling_ || queued_.has_value();
}

void LiveCompiler::run() {
  for (;;) {
    CompileJob job;
    {
      std::unique_lock lock(mutex_);
      wake_.wait(lock, [this] { return stopping_ || queued_.has_value(); });
      if (stopping_) return;
      job = std::move(*queued_);
      queued_.reset();
      compiling_ = true;
    }
    CompileOutcome outcome;
    outcome.request = job.request;
    const auto start = std::chrono::steady_clock::now();
    compile_(job, outcome);
    outcome.milliseconds = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
    const std::lock_guard lock(mutex_);
    done_.push_back(std::move(outcome));
    compiling_ = false;
  }
}

}  // namespace spire::explore
