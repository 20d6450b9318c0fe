// Runs spirec in-process and keeps what a user would see: the exit code,
// stdout and stderr.
#pragma once

#include <sstream>
#include <string>
#include <vector>

#include "driver/spirec.h"

namespace spire::test {

struct SpirecRun {
  int exitCode;
  std::string out;
  std::string err;
};

inline SpirecRun spirec(const std::vector<std::string>& args, const SpirecEnvironment& environment = {}) {
  std::ostringstream out, err;
  const int code = runSpirec(args, out, err, environment);
  return {code, out.str(), err.str()};
}

}  // namespace spire::test
