#include "tune/shader_cache.h"

#include <fmt/format.h>

#include <cerrno>
#include <cstdlib>
#include <cstring>

namespace spire::tune {

namespace fs = std::filesystem;

ShaderCacheSetting::~ShaderCacheSetting() {
  for (const auto& [name, value] : saved_) {
    if (value)
      ::setenv(name.c_str(), value->c_str(), 1);
    else
      ::unsetenv(name.c_str());
  }
  std::error_code ec;
  if (!directory_.empty()) fs::remove_all(directory_, ec);
}

Expected<void, Failure> ShaderCacheSetting::apply(const std::string& mode) {
  if (mode == "inherit") return {};
  if (mode == "off") {
    set("MESA_SHADER_CACHE_DISABLE", "true");
    return {};
  }
  std::string pattern = (fs::temp_directory_path() / "spire-tune-shader-cache.XXXXXX").string();
  if (::mkdtemp(pattern.data()) == nullptr) {
    return Failure{fmt::format("cannot create a shader cache directory like '{}': {}", pattern, std::strerror(errno))};
  }
  directory_ = pattern;
  set("MESA_SHADER_CACHE_DISABLE", "false");
  set("MESA_SHADER_CACHE_DIR", pattern);
  return {};
}

void ShaderCacheSetting::set(const std::string& name, const std::string& value) {
  const char* old = std::getenv(name.c_str());
  saved_.emplace_back(name, old ? std::optional<std::string>(old) : std::nullopt);
  ::setenv(name.c_str(), value.c_str(), 1);
}

}  // namespace spire::tune
