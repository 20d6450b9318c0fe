// The tuner's progress on stderr: a bar redrawn in place on a terminal, one
// line per change otherwise (logs), with the time left estimated from the
// variants measured so far in this run (not the ones an earlier run did).
#pragma once

#include <cstddef>
#include <ostream>

#include "vk/timer.h"

namespace spire::tune {

class Progress {
 public:
  Progress(std::ostream& err, size_t total, size_t already);

  // `done` of the total are measured; prints only when that changed.
  void update(size_t done);

  // Ends the bar's line early (a run that stops before the total), so that
  // what is printed next starts on a line of its own.
  void finish();

 private:
  std::ostream& err_;
  size_t total_;
  size_t already_;
  bool tty_;
  size_t last_ = static_cast<size_t>(-1);
  vk::HostTimer timer_;
};

}  // namespace spire::tune
