#include <iostream>

#include "demo/demo.h"

int main(int argc, char** argv) {
  const std::vector<std::string> args(argv + 1, argv + argc);
  return spire::demo::runDemo(args, std::cout, std::cerr);
}
