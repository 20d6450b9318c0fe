// The `spire-tune` command line (paper section 7.4): explores the product of
// a shader's selected choices on a scene, measures every variant's speed and
// error against the full-quality reference, and writes the table, the Pareto
// front, the best variants under budgets as decision files, a plot and a
// report. Callable in-process so tests see what a user sees.
#pragma once

#include <iosfwd>
#include <string>
#include <vector>

namespace spire::tune {

// Exit status: 0 success, 1 errors in the input or while measuring, 2 bad
// usage, 3 no usable Vulkan device. `workerProgram` is the spire-tune
// executable that --jobs starts as worker processes; without one (a caller
// that is not spire-tune) every variant is measured in this process.
int runTune(const std::vector<std::string>& args, std::ostream& out, std::ostream& err,
            const std::string& workerProgram = {});

}  // namespace spire::tune
