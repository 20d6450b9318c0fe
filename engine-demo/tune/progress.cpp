#include "tune/progress.h"

#include <fmt/format.h>

#include <unistd.h>

#include <string>

namespace spire::tune {

Progress::Progress(std::ostream& err, size_t total, size_t already)
    : err_(err), total_(total), already_(already), tty_(::isatty(STDERR_FILENO) == 1) {}

void Progress::update(size_t done) {
  if (done == last_) return;
  last_ = done;
  const double elapsed = timer_.elapsedMs() / 1000.0;
  const size_t measured = done - already_;
  const double eta = measured == 0 ? 0.0 : elapsed / double(measured) * double(total_ - done);
  if (tty_) {
    const size_t filled = total_ == 0 ? 30 : done * 30 / total_;
    err_ << fmt::format("\r[{}{}] {}/{} variants, ETA {:.0f} s ", std::string(filled, '#'),
                        std::string(30 - filled, '.'), done, total_, eta)
         << std::flush;
    if (done == total_) err_ << "\n";
  } else {
    err_ << fmt::format("tune: {}/{} variants, ETA {:.0f} s\n", done, total_, eta);
  }
}

void Progress::finish() {
  if (tty_ && last_ != static_cast<size_t>(-1) && last_ != total_) err_ << "\n";
}

}  // namespace spire::tune
