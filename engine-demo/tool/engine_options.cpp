#include "tool/engine_options.h"

#include <fmt/format.h>
#include <CLI/CLI.hpp>

#include <charconv>
#include <string_view>

#include "scene/scene_file.h"

namespace spire::engine {

namespace {

using scene::kMaxImageSide;

// A side of "WxH": digits only, in 1..kMaxImageSide.
std::optional<uint32_t> parseSide(std::string_view text) {
  uint32_t value = 0;
  const auto [end, error] = std::from_chars(text.data(), text.data() + text.size(), value);
  if (text.empty() || error != std::errc() || end != text.data() + text.size()) return std::nullopt;
  if (value < 1 || value > kMaxImageSide) return std::nullopt;
  return value;
}

}  // namespace

std::optional<ImageSize> parseImageSize(const std::string& text) {
  const size_t x = text.find('x');
  if (x == std::string::npos) return std::nullopt;
  const std::optional<uint32_t> width = parseSide(std::string_view(text).substr(0, x));
  const std::optional<uint32_t> height = parseSide(std::string_view(text).substr(x + 1));
  if (!width || !height) return std::nullopt;
  return ImageSize{*width, *height};
}

void addEngineOptions(CLI::App& app, EngineOptions& options) {
  app.add_option("--device", options.device, "Use the Vulkan device whose name contains TEXT (default: llvmpipe)")
      ->type_name("TEXT");
  app.add_option("--bake-size", options.bakeSize, "PrebakeTex texture size without a TextureSize hint")
      ->check(CLI::Range(1, 8192))
      ->type_name("N");
  app.add_flag("--validation", options.validation,
               "Enable VK_LAYER_KHRONOS_validation; any message makes the run fail");
  addResolutionOption(app, options.resolution);
}

void addResolutionOption(CLI::App& app, std::optional<ImageSize>& resolution) {
  app.add_option_function<std::string>(
         "--resolution", [&resolution](const std::string& text) { resolution = parseImageSize(text); },
         "Render at W x H pixels instead of the scene's \"resolution\"")
      ->check(CLI::Validator(
          [](const std::string& text) {
            return parseImageSize(text) ? std::string()
                                        : fmt::format("'{}' is not WxH with each side in 1..{}", text, kMaxImageSide);
          },
          ""))
      ->type_name("WxH");
}

}  // namespace spire::engine
