// Environment variables a tuning run sets for itself and its workers (Mesa
// reads them when a Vulkan device is created), restored when the run ends,
// for callers that run the tuner in their own process.
#pragma once

#include <optional>
#include <string>
#include <utility>
#include <vector>

namespace spire::tune {

class RunEnvironment {
 public:
  RunEnvironment() = default;
  RunEnvironment(const RunEnvironment&) = delete;
  RunEnvironment& operator=(const RunEnvironment&) = delete;
  ~RunEnvironment();

  void set(const std::string& name, const std::string& value);

 private:
  std::vector<std::pair<std::string, std::optional<std::string>>> saved_;  // what each had before
};

}  // namespace spire::tune
