#include "tune/shader_cache.h"

#include <fmt/format.h>

#include <stdlib.h>
#include <cerrno>
#include <cstring>

namespace spire::tune {

namespace fs = std::filesystem;

ShaderCacheSetting::~ShaderCacheSetting() {
  std::error_code ec;
  if (!directory_.empty()) fs::remove_all(directory_, ec);
}

Expected<void, Failure> ShaderCacheSetting::apply(const std::string& mode) {
  if (mode == "inherit") return {};
  if (mode == "off") {
    environment_.set("MESA_SHADER_CACHE_DISABLE", "true");
    return {};
  }
  std::string pattern = (fs::temp_directory_path() / "spire-tune-shader-cache.XXXXXX").string();
  if (::mkdtemp(pattern.data()) == nullptr) {
    return Failure{fmt::format("cannot create a shader cache directory like '{}': {}", pattern, std::strerror(errno))};
  }
  directory_ = pattern;
  environment_.set("MESA_SHADER_CACHE_DISABLE", "false");
  environment_.set("MESA_SHADER_CACHE_DIR", pattern);
  return {};
}

}  // namespace spire::tune
