// `spirec --batch FILE`: many spirec runs in one process, so that a build of
// thousands of shaders pays glslang's process start-up and built-in symbol
// tables once instead of per shader, and its jobs share the machine's cores.
#pragma once

#include <functional>
#include <iosfwd>
#include <optional>
#include <string>
#include <vector>

#include "driver/spirec.h"

namespace spire {

// A spirec run that has compiled but not yet written anything: writes its
// files and prints what the run prints, and returns its exit status.
using SpirecFinish = std::function<int(std::ostream& out, std::ostream& err)>;

// Compiles one job as spirec would with its arguments; runSpirec's own
// parsing, so that a batch line and a command line cannot mean different
// things.
using SpirecJobPreparer = SpirecFinish (*)(const std::vector<std::string>& args, const SpirecEnvironment& environment);

// What `spirec --batch` is asked to do.
struct BatchRequest {
  std::string file;
  unsigned jobs = 0;  // jobs compiled at once; 0: one per hardware thread
};

// The request when `args` are exactly batch mode: `--batch FILE` (or
// `--batch=FILE`) and at most one `-j N` (`-jN`, `--jobs N`, `--jobs=N`),
// N at least 1, in either order. nullopt otherwise.
std::optional<BatchRequest> batchRequest(const std::vector<std::string>& args);

// True when `args` name --batch but are not exactly batch mode.
bool batchMisuse(const std::vector<std::string>& args);

// Runs every job of the batch file through `prepare`, request.jobs at a
// time, and finishes them in file order: each job's files are written, its
// output goes to `out`, and its diagnostics go to `err` after a line naming
// the job and its place in the file, exactly as if the jobs had run one
// after another. Returns 0 when every job succeeded, else the highest job
// status; a batch file that cannot be read or has a malformed line runs no
// job.
int runSpirecBatch(const BatchRequest& request, SpirecJobPreparer prepare, std::ostream& out, std::ostream& err,
                   const SpirecEnvironment& environment);

}  // namespace spire
