#include <iostream>

#include "driver/library_location.h"
#include "driver/process_memory.h"
#include "driver/spirec.h"

int main(int argc, char** argv) {
  spire::useHugePageHeap();
  std::ios::sync_with_stdio(false);
  spire::SpirecEnvironment environment;
  if (const auto self = spire::runningExecutable()) {
    if (const auto library = spire::bundledLibraryDir(*self)) environment.libraryDir = library->string();
  }
  return spire::runSpirec(std::vector<std::string>(argv + 1, argv + argc), std::cout, std::cerr, environment);
}
