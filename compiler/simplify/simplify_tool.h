// spire-simplify's command line (docs/simplify.md).
#pragma once

#include <iosfwd>
#include <string>
#include <vector>

namespace spire::simplify {

// `libraryDir`: the Spire library shipped with the tool (stdlib/,
// pipelines/), searched after -I; empty: none.
int runSimplifyTool(const std::vector<std::string>& args, std::ostream& out, std::ostream& err,
                    const std::string& libraryDir = {});

}  // namespace spire::simplify
