// The `spirec` command line, callable in-process so tests see exactly what a
// user sees.
#pragma once

#include <iosfwd>
#include <string>
#include <vector>

namespace spire {

enum ExitCode : int { kExitSuccess = 0, kExitInputError = 1, kExitUsageError = 2 };

// Runs spirec with `args` (without the program name). Results go to `out`,
// diagnostics and usage errors to `err`.
int runSpirec(const std::vector<std::string>& args, std::ostream& out, std::ostream& err);

}  // namespace spire
