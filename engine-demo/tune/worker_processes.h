// spire-tune --jobs N: N copies of the tuner's own executable as worker
// processes (started with --worker K), which take chunks of the points from
// the work queue and append their rows to their shard; lavapipe is limited
// to one thread in each so that the workers share the cores instead of
// fighting over them.
#pragma once

#include <cstddef>
#include <filesystem>
#include <ostream>
#include <string>
#include <vector>

namespace spire::tune {

struct WorkerPlan {
  std::string program;                        // the spire-tune executable
  std::vector<std::string> args;              // the coordinator's arguments; each worker adds --worker K
  std::vector<std::filesystem::path> shards;  // one per worker: the rows it measured
};

enum class WorkersEnd {
  Finished,     // every worker exited with 0
  Crashed,      // every one that did not exit with 0 was ended by a signal it did not get from us
  Failed,       // one could not start or exited with another status (it said why)
  Interrupted,  // a stop was requested (StopRequest) and passed on; they stopped between variants
};

// Runs the workers to the end, showing progress from the rows they add to
// their shards (rows an interrupted run left there are in `already`); a
// worker that does not exit with 0 is named on `err` with how it ended.
WorkersEnd runWorkers(const WorkerPlan& plan, size_t already, size_t total, std::ostream& err);

// In a worker: stop (as on SIGTERM) when the coordinator that started it
// is gone, however it ended, so that no worker writes into a directory
// that another run may have taken over.
void followCoordinator();

}  // namespace spire::tune
