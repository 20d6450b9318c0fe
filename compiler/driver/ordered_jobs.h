// Runs numbered jobs on several threads but finishes them in number order:
// what `spirec --batch` needs so that concurrent jobs still write their
// files and print their output exactly as the same jobs run one after
// another would.
#pragma once

#include <cstddef>
#include <functional>

namespace spire {

// What a job does once every earlier job has finished.
using JobFinish = std::function<void()>;

// Calls prepare(i) for every i in [0, count), up to `threads` at a time, and
// the JobFinish each returns in order of i: finish(i) starts only after
// finish(i - 1) has returned, and never alongside another finish. A thread
// whose job cannot finish yet goes on to the next job instead of waiting.
// An exception from prepare or finish skips that job's finish (the others
// still run) and is rethrown, the first one, after every job is done.
void runOrderedJobs(size_t count, unsigned threads, const std::function<JobFinish(size_t)>& prepare);

}  // namespace spire
