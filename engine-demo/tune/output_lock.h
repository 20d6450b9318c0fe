// One tuning run per output directory: the directory is the run's journal,
// and two runs appending to it would each lose the other's rows. The lock is
// an flock on DIR/.lock, which the kernel drops when its holder exits
// however it exits, so a crashed run never leaves the directory locked.
#pragma once

#include <filesystem>

#include "support/expected.h"

namespace spire::tune {

class OutputLock {
 public:
  // The lock on `directory` (created if missing), or an error naming the
  // process that holds it.
  static Expected<OutputLock, Failure> acquire(const std::filesystem::path& directory);
  OutputLock(OutputLock&& other) noexcept;
  OutputLock& operator=(OutputLock&& other) noexcept;
  OutputLock(const OutputLock&) = delete;
  OutputLock& operator=(const OutputLock&) = delete;
  ~OutputLock();

 private:
  explicit OutputLock(int fd) : fd_(fd) {}
  int fd_ = -1;
};

}  // namespace spire::tune
