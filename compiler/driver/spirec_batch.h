// `spirec --batch FILE`: many spirec runs in one process, so that a build of
// thousands of shaders pays glslang's process start-up and built-in symbol
// tables once instead of per shader.
#pragma once

#include <iosfwd>
#include <optional>
#include <string>
#include <vector>

#include "driver/spirec.h"

namespace spire {

// Runs one job as spirec would with its arguments; runSpirec's own parsing,
// so that a batch line and a command line cannot mean different things.
using SpirecJobRunner = int (*)(const std::vector<std::string>& args, std::ostream& out, std::ostream& err,
                                const SpirecEnvironment& environment);

// The batch file when `args` ask for batch mode: exactly `--batch FILE` or
// `--batch=FILE`. An `--batch` among other arguments is not batch mode; the
// caller reports it (batchMisuse).
std::optional<std::string> batchFileArgument(const std::vector<std::string>& args);

// True when `args` name --batch but are not exactly batch mode.
bool batchMisuse(const std::vector<std::string>& args);

// Runs every job of the batch file in file order, each through `runJob`.
// Job output goes to `out` as it would for a separate run; a job's
// diagnostics go to `err` after a line naming the job and its place in the
// file. Returns 0 when every job succeeded, else the highest job status; a
// batch file that cannot be read or has a malformed line runs no job.
int runSpirecBatch(const std::string& path, SpirecJobRunner runJob, std::ostream& out, std::ostream& err,
                   const SpirecEnvironment& environment);

}  // namespace spire
