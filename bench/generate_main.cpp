// Prints a generated benchmark program, e.g. to look at it or to time spirec:
//   build/bin/spire_bench_generate 1000 9 > /tmp/bench.spire
#include <cstdio>
#include <cstdlib>
#include <string>

#include "generate_shader.h"

int main(int argc, char** argv) {
  const int components = argc > 1 ? std::atoi(argv[1]) : 1000;
  const int worlds = argc > 2 ? std::atoi(argv[2]) : 9;
  const std::string text = spire::bench::generateShader(components, worlds);
  std::fwrite(text.data(), 1, text.size(), stdout);
  return 0;
}
