#include <iostream>

#include "tune/tune_cli.h"

int main(int argc, char** argv) {
  const std::vector<std::string> args(argv + 1, argv + argc);
  return spire::tune::runTune(args, std::cout, std::cerr);
}
