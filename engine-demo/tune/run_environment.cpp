#include "tune/run_environment.h"

#include <cstdlib>

namespace spire::tune {

RunEnvironment::~RunEnvironment() {
  // Latest first, so a variable set twice gets its original value back.
  for (auto it = saved_.rbegin(); it != saved_.rend(); ++it) {
    if (it->second)
      ::setenv(it->first.c_str(), it->second->c_str(), 1);
    else
      ::unsetenv(it->first.c_str());
  }
}

void RunEnvironment::set(const std::string& name, const std::string& value) {
  const char* old = std::getenv(name.c_str());
  saved_.emplace_back(name, old ? std::optional<std::string>(old) : std::nullopt);
  ::setenv(name.c_str(), value.c_str(), 1);
}

}  // namespace spire::tune
