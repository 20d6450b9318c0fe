// Hands out the points of a tuning run to worker processes a chunk at a
// time, in order: a counter in a file, advanced under an exclusive lock.
// Variants differ a lot in cost (a big fragment kernel takes lavapipe ten
// times longer to compile than a small one), so a fixed share per worker
// leaves one idle while another still works; taking the next chunk when one
// is done keeps every core busy to the end. A chunk holds the points that
// differ only in the last explored component, which share every kernel that
// component does not touch: one worker meets them together, so the run's
// shader cache compiles each shared kernel once instead of both workers
// compiling it at the same moment.
#pragma once

#include <cstdint>
#include <filesystem>
#include <optional>
#include <string>

#include "support/expected.h"

namespace spire::tune {

class WorkQueue {
 public:
  // Starts a queue at chunk 0 (the coordinator, before the workers start).
  static Expected<void, Failure> create(const std::filesystem::path& path);

  explicit WorkQueue(std::filesystem::path path) : path_(std::move(path)) {}

  // The next chunk below `chunks`, or nullopt when all are taken; an error
  // when the file cannot be read, locked or written.
  Expected<std::optional<uint64_t>, Failure> next(uint64_t chunks);

 private:
  std::filesystem::path path_;
};

}  // namespace spire::tune
