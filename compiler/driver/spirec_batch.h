// `spirec --batch FILE`: many spirec runs in one process, so that a build of
// thousands of shaders pays glslang's process start-up and built-in symbol
// tables once instead of per shader, and its jobs share the machine's cores.
#pragma once

#include <functional>
#include <iosfwd>
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

// Whether `args` ask for batch mode: one of them is --batch or --batch=FILE.
bool namesBatchMode(const std::vector<std::string>& args);

// `spirec --batch FILE [-j N]`: parses `args` by the tools' argument
// conventions (driver/tool_arguments.h; anything else on the line is a
// usage error), then runs every job of the batch file through `prepare`, N
// at a time (default: one per hardware thread), and finishes them in file
// order: each job's files are written, its output goes to `out`, and its
// diagnostics go to `err` after a line naming the job and its place in the
// file, exactly as if the jobs had run one after another. Returns 0 when
// every job succeeded, else the highest job status; a batch file that cannot
// be read or has a malformed line runs no job.
int runSpirecBatch(const std::vector<std::string>& args, SpirecJobPreparer prepare, std::ostream& out,
                   std::ostream& err, const SpirecEnvironment& environment);

}  // namespace spire
