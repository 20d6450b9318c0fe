#include <iostream>

#include "driver/library_location.h"
#include "simplify/simplify_tool.h"

int main(int argc, char** argv) {
  const std::vector<std::string> args(argv + 1, argv + argc);
  std::string libraryDir;
  if (const auto self = spire::runningExecutable()) {
    if (const auto library = spire::bundledLibraryDir(*self)) libraryDir = library->string();
  }
  return spire::simplify::runSimplifyTool(args, std::cout, std::cerr, libraryDir);
}
