#include "explore/explorer_model.h"

#include <algorithm>
#include <array>

namespace spire::explore {
namespace {

constexpr size_t kWindowFrames = 60;  // the sliding window of frame times

constexpr std::array<std::pair<std::string_view, ViewMode>, 5> kModes{{{"variant", ViewMode::Variant},
                                                                       {"reference", ViewMode::Reference},
                                                                       {"error", ViewMode::Error},
                                                                       {"hazards", ViewMode::Hazards},
                                                                       {"split", ViewMode::Split}}};

}  // namespace

const char* viewModeName(ViewMode mode) {
  for (const auto& [name, m] : kModes) {
    if (m == mode) return name.data();
  }
  return "variant";
}

std::optional<ViewMode> viewModeNamed(std::string_view name) {
  for (const auto& [n, mode] : kModes) {
    if (n == name) return mode;
  }
  return std::nullopt;
}

double Metrics::medianGpuMs() const {
  if (gpuMs.empty()) return 0.0;
  std::vector<double> sorted(gpuMs.begin(), gpuMs.end());
  std::nth_element(sorted.begin(), sorted.begin() + static_cast<std::ptrdiff_t>(sorted.size() / 2), sorted.end());
  return sorted[sorted.size() / 2];
}

void Metrics::addFrame(double ms) {
  gpuMs.push_back(ms);
  while (gpuMs.size() > kWindowFrames) gpuMs.pop_front();
}

}  // namespace spire::explore
