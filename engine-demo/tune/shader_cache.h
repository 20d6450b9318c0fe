#pragma once

#include <filesystem>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "support/expected.h"
#include "tune/run_environment.h"

namespace spire::tune {

// lavapipe's (Mesa's) on-disk shader cache for one run. In mode "run", a
// fresh directory that every worker shares and that is removed at the end:
// kernels that many variants share (the vertex and bake kernels) then reach
// LLVM once per run rather than once per variant, while nothing that an
// earlier run or another program cached can make a first use look cheap.
// "off" compiles every pipeline in full; "inherit" leaves the environment
// alone. Mesa reads the variables when a Vulkan device is created, so this
// comes first; the workers inherit them; the destructor restores what the
// environment had, for callers that run the tuner in their own process.
class ShaderCacheSetting {
 public:
  ShaderCacheSetting() = default;
  ShaderCacheSetting(const ShaderCacheSetting&) = delete;
  ShaderCacheSetting& operator=(const ShaderCacheSetting&) = delete;
  ~ShaderCacheSetting();

  // Applies `mode` ("run", "off" or "inherit"); an error when the
  // directory cannot be made.
  Expected<void, Failure> apply(const std::string& mode);

 private:
  // Declared after the directory: the variables are restored first.
  std::filesystem::path directory_;
  RunEnvironment environment_;
};

}  // namespace spire::tune
