// spire-simplify: the compiler-only tool (compiler/simplify), and with
// --search the greedy search, which renders (engine-demo/search). The plain
// tool never opens a device.
#include <algorithm>
#include <iostream>
#include <string>
#include <vector>

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
  const int status = spire::simplify::runSimplifyTool(args, std::cout, std::cerr, libraryDir);
  const auto help = [&](const std::string& arg) { return arg == "-h" || arg == "--help"; };
  if (std::any_of(args.begin(), args.end(), help)) {
    std::cout << "\nWith --search, the greedy search on a scene instead (spire-simplify --search --help).\n";
  }
  return status;
}
