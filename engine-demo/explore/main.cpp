#include <iostream>

#include "explore/explore_cli.h"

int main(int argc, char** argv) {
  const std::vector<std::string> args(argv + 1, argv + argc);
  return spire::explore::runExploreTool(args, std::cout, std::cerr);
}
