// The command-line options every engine tool that renders takes, spelled and
// documented once: which device, the bake size, the validation layer.
#pragma once

#include <cstdint>
#include <string>

namespace CLI {
class App;
}

namespace spire::engine {

struct EngineOptions {
  std::string device;  // a substring of the device name; empty: llvmpipe
  uint32_t bakeSize = 1024;
  bool validation = false;
};

// --device TEXT, --bake-size N and --validation.
void addEngineOptions(CLI::App& app, EngineOptions& options);

}  // namespace spire::engine
