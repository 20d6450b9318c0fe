// spire-explore's command line (docs/explorer.md).
#pragma once

#include <iosfwd>
#include <string>
#include <vector>

namespace spire::explore {

int runExploreTool(const std::vector<std::string>& args, std::ostream& out, std::ostream& err);

}  // namespace spire::explore
