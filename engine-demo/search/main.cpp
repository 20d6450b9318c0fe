// spire-simplify: the compiler-only tool (compiler/simplify), and with
// --search the greedy search, which renders (engine-demo/search). The plain
// tool never opens a device.
#include <iostream>

#include "driver/library_location.h"
#include "search/search_tool.h"
#include "simplify/simplify_tool.h"

int main(int argc, char** argv) {
  const std::vector<std::string> args(argv + 1, argv + argc);
  if (spire::search::wantsSearch(args)) return spire::search::runSearchTool(args, std::cout, std::cerr);
  std::string libraryDir;
  if (const auto self = spire::runningExecutable()) {
    if (const auto library = spire::bundledLibraryDir(*self)) libraryDir = library->string();
  }
  return spire::simplify::runSimplifyTool(args, std::cout, std::cerr, libraryDir);
}
