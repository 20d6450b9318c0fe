// The `spirec` command line, callable in-process so tests see exactly what a
// user sees.
#pragma once

#include <iosfwd>
#include <string>
#include <vector>

#include "driver/exit_codes.h"

namespace spire {

class SpirvCache;

// What spirec takes from its process rather than its arguments.
struct SpirecEnvironment {
  // The Spire library (driver/library_location.h), searched for `using`
  // files after every -I directory; empty: none. The executable passes its
  // own; in-process callers (tests) choose.
  std::string libraryDir;
  // SPIR-V made by earlier runs in this process (spirec --batch); null:
  // none. Never changes what a run writes, only whether glslang runs.
  SpirvCache* spirvCache = nullptr;
};

// Runs spirec with `args` (without the program name). Results go to `out`,
// diagnostics and usage errors to `err`. Returns an ExitCode.
int runSpirec(const std::vector<std::string>& args, std::ostream& out, std::ostream& err,
              const SpirecEnvironment& environment = {});

// Whether a run of `args` is worth sending to the compile server
// (driver/compile_server.h): it makes SPIR-V (a batch may), and --no-server
// is not given. A command line spirec would reject runs in the process
// that prints the usage error.
bool spirecWantsCompileServer(const std::vector<std::string>& args);

}  // namespace spire
