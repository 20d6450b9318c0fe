#include <iostream>

#include "driver/spirec.h"

int main(int argc, char** argv) {
  std::ios::sync_with_stdio(false);
  return spire::runSpirec(std::vector<std::string>(argv + 1, argv + argc), std::cout, std::cerr);
}
