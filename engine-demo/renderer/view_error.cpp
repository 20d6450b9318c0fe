#include "renderer/view_error.h"

#include <fmt/format.h>

#include <algorithm>

namespace spire::engine {

scene::Expected<measure::ImageError> viewError(const Capture& reference, const Capture& test) {
  if (reference.coverage.size() != test.coverage.size()) {
    return scene::Error{fmt::format("coverage masks of {} and {} pixels cannot be compared", reference.coverage.size(),
                                    test.coverage.size())};
  }
  std::vector<uint8_t> coverage = reference.coverage;
  for (size_t i = 0; i < coverage.size(); ++i) coverage[i] |= test.coverage[i];
  return measure::compareImages(reference.color, test.color, &coverage);
}

scene::Expected<measure::ImageError> viewsError(std::span<const Capture> reference, std::span<const Capture> test) {
  if (reference.size() != test.size()) {
    return scene::Error{fmt::format("{} views cannot be compared with {}", test.size(), reference.size())};
  }
  measure::ErrorAccumulator accumulated;
  for (size_t v = 0; v < reference.size(); ++v) {
    auto error = viewError(reference[v], test[v]);
    if (!error) return error;
    accumulated.add(*error);
  }
  return accumulated.total();
}

void Coverage::add(const Capture& referenceView, const Capture& testView) {
  const auto covered = [](const std::vector<uint8_t>& mask) {
    return static_cast<uint64_t>(std::count_if(mask.begin(), mask.end(), [](uint8_t c) { return c != 0; }));
  };
  reference += covered(referenceView.coverage);
  test += covered(testView.coverage);
}

double Coverage::ratio() const {
  return reference == 0 ? 1.0 : static_cast<double>(test) / static_cast<double>(reference);
}

}  // namespace spire::engine
