// The `spirec` command line, callable in-process so tests see exactly what a
// user sees.
#pragma once

#include <iosfwd>
#include <string>
#include <vector>

#include "driver/exit_codes.h"

namespace spire {

// Runs spirec with `args` (without the program name). Results go to `out`,
// diagnostics and usage errors to `err`. Returns an ExitCode.
int runSpirec(const std::vector<std::string>& args, std::ostream& out, std::ostream& err);

}  // namespace spire
