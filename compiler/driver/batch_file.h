// The text of `spirec --batch FILE`: one spirec job per line, each line the
// arguments of one spirec run. Splitting is deliberately simpler than a
// shell's, so that a build system can write the file without knowing about
// expansions: see docs/integration.md, "Batch mode".
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "support/diagnostic.h"
#include "support/source_manager.h"

namespace spire {

struct BatchJob {
  uint32_t line = 0;  // 1-based, in the batch file
  std::vector<std::string> args;
};

// The jobs of the batch file `file`, in file order. A malformed line reports
// E1105 at the offending character; the caller runs no job when any line is
// malformed, since a half-run batch leaves a build in a state nobody asked
// for.
std::vector<BatchJob> parseBatchFile(const SourceManager& sources, FileId file, DiagnosticList& diags);

}  // namespace spire
