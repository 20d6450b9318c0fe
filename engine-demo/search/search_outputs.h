// What `spire-simplify --search` writes, as one set (replaced atomically):
// the module of the chain's definitions, one decision file per level
// (level0.decisions is the original), chain.csv, report.md and the chain's
// error-against-time plot, error_time.png.
#pragma once

#include <string>

#include "search/chain.h"
#include "search/search_options.h"
#include "support/atomic_directory.h"
#include "support/expected.h"

namespace spire::search {

struct OutputRequest {
  ModuleHeader header;  // with the `using` path relative to the output folder
  const SearchOptions* options = nullptr;
  double referenceMs = 0.0;  // level 0's median frame time in this run
};

// The module's file name: the derived shader's name + ".spire".
std::string moduleFileName(const ModuleHeader& header);

Expected<FileSet, Failure> searchOutputs(const Chain& chain, const OutputRequest& request);

}  // namespace spire::search
