// The command-line options every engine tool that renders takes, spelled and
// documented once: which device, the bake size, the validation layer, the
// image size.
#pragma once

#include <cstdint>
#include <optional>
#include <string>

namespace CLI {
class App;
}

namespace spire::engine {

// An image's size in pixels, as `--resolution WxH` spells it.
struct ImageSize {
  uint32_t width = 0;
  uint32_t height = 0;
};

// "WxH" with both sides in 1..scene::kMaxImageSide, the scene file's bounds;
// nullopt otherwise.
std::optional<ImageSize> parseImageSize(const std::string& text);

struct EngineOptions {
  std::string device;  // a substring of the device name; empty: llvmpipe
  uint32_t bakeSize = 1024;
  bool validation = false;
  // Replaces the scene's "resolution": the same scene can be measured at
  // another size without a copy of its file, whose relative paths would
  // then have to move with it.
  std::optional<ImageSize> resolution;
};

// --device TEXT, --bake-size N, --validation and --resolution WxH.
void addEngineOptions(CLI::App& app, EngineOptions& options);

// --resolution WxH alone, for the tools that measure through the tuner
// (spire-tune, spire-simplify --search), whose other options differ.
void addResolutionOption(CLI::App& app, std::optional<ImageSize>& resolution);

}  // namespace spire::engine
