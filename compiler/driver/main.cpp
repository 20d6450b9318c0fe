#include <iostream>
#include <string_view>

#include "driver/library_location.h"
#include "driver/process_memory.h"
#include "driver/spirec.h"

int main(int argc, char** argv) {
  spire::useHugePageHeap();
  // A hidden diagnostic, not an option of runSpirec: only this executable
  // sets up its heap, so only it can report on it.
  if (argc == 2 && std::string_view(argv[1]) == "--heap-report") {
    std::cout << spire::describeHeap() << '\n';
    return 0;
  }
  std::ios::sync_with_stdio(false);
  spire::SpirecEnvironment environment;
  if (const auto self = spire::runningExecutable()) {
    if (const auto library = spire::bundledLibraryDir(*self)) environment.libraryDir = library->string();
  }
  return spire::runSpirec(std::vector<std::string>(argv + 1, argv + argc), std::cout, std::cerr, environment);
}
