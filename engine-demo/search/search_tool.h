// `spire-simplify --search` (docs/simplify.md, "Search"): He et al.
// 2015's greedy simplification of a scene's shader, measured by rendering
// the scene as spire-tune does, written as a level-of-detail chain.
#pragma once

#include <iosfwd>
#include <string>
#include <vector>

namespace spire::search {

// Exit status: 0 success, 1 errors in the inputs or while measuring, 2 bad
// usage, 3 no usable Vulkan device.
int runSearchTool(const std::vector<std::string>& args, std::ostream& out, std::ostream& err);

// Whether `args` ask for the search rather than spire-simplify's one step.
bool wantsSearch(const std::vector<std::string>& args);

}  // namespace spire::search
