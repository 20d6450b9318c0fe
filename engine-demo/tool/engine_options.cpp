#include "tool/engine_options.h"

#include <CLI/CLI.hpp>

namespace spire::engine {

void addEngineOptions(CLI::App& app, EngineOptions& options) {
  app.add_option("--device", options.device, "Use the Vulkan device whose name contains TEXT (default: llvmpipe)")
      ->type_name("TEXT");
  app.add_option("--bake-size", options.bakeSize, "PrebakeTex texture size without a TextureSize hint")
      ->check(CLI::Range(1, 8192))
      ->type_name("N");
  app.add_flag("--validation", options.validation,
               "Enable VK_LAYER_KHRONOS_validation; any message makes the run fail");
}

}  // namespace spire::engine
