#include <iostream>

#include "tune/tune_cli.h"

int main(int argc, char** argv) {
  const std::vector<std::string> args(argv + 1, argv + argc);
  // Workers are this same executable, started with --worker.
  return spire::tune::runTune(args, std::cout, std::cerr, "/proc/self/exe");
}
