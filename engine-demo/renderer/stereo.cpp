#include "renderer/stereo.h"

#include <glm/geometric.hpp>

#include <algorithm>

namespace spire::engine {

std::array<scene::CameraView, 2> eyeViews(const scene::CameraView& view, const glm::vec3& up, float separation) {
  const glm::vec3 right = glm::normalize(glm::cross(view.target - view.position, up));
  const glm::vec3 offset = right * (separation * 0.5F);
  scene::CameraView left = view;
  scene::CameraView rightEye = view;
  left.position -= offset;
  left.target -= offset;
  rightEye.position += offset;
  rightEye.target += offset;
  return {left, rightEye};
}

namespace {

// Each row of `left` followed by the same row of `right`; rows are
// `rowLength` elements long in both.
template <class T>
std::vector<T> joinRows(const std::vector<T>& left, const std::vector<T>& right, size_t rowLength) {
  std::vector<T> joined(left.size() + right.size());
  const size_t rows = rowLength == 0 ? 0 : left.size() / rowLength;
  for (size_t y = 0; y < rows; ++y) {
    const auto row = static_cast<std::ptrdiff_t>(y * rowLength);
    const auto length = static_cast<std::ptrdiff_t>(rowLength);
    auto out = joined.begin() + 2 * row;
    out = std::copy(left.begin() + row, left.begin() + row + length, out);
    std::copy(right.begin() + row, right.begin() + row + length, out);
  }
  return joined;
}

}  // namespace

measure::FloatImage sideBySide(const measure::FloatImage& left, const measure::FloatImage& right) {
  measure::FloatImage joined;
  joined.width = left.width * 2;
  joined.height = left.height;
  joined.rgba = joinRows(left.rgba, right.rgba, size_t{left.width} * 4);
  return joined;
}

std::vector<uint8_t> sideBySide(const std::vector<uint8_t>& left, const std::vector<uint8_t>& right, uint32_t width) {
  return joinRows(left, right, width);
}

}  // namespace spire::engine
