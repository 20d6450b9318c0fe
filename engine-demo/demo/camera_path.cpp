#include "demo/camera_path.h"

#include <glm/common.hpp>
#include <glm/geometric.hpp>
#include <glm/gtc/constants.hpp>
#include <glm/gtc/quaternion.hpp>

#include <algorithm>
#include <cmath>

namespace spire::demo {

namespace {

// Closest the orbit gets to looking straight along the up axis, in radians.
constexpr float kMinPolarAngle = 0.05F;

}  // namespace

scene::CameraView cameraOnLoop(std::span<const scene::CameraView> views, double t) {
  const auto count = static_cast<double>(views.size());
  const double wrapped = t - std::floor(t / count) * count;  // in [0, count), also for negative t
  const auto index = std::min(static_cast<size_t>(wrapped), views.size() - 1);
  const scene::CameraView& from = views[index];
  const scene::CameraView& to = views[(index + 1) % views.size()];
  const auto s = static_cast<float>(wrapped - static_cast<double>(index));
  const float eased = s * s * (3.0F - 2.0F * s);
  scene::CameraView view = from;
  view.position = glm::mix(from.position, to.position, eased);
  view.target = glm::mix(from.target, to.target, eased);
  return view;
}

scene::CameraView orbit(const scene::CameraView& view, glm::vec3 up, float yaw, float pitch) {
  const glm::vec3 offset = view.position - view.target;
  const float radius = glm::length(offset);
  if (radius == 0.0F || glm::length(up) == 0.0F) return view;
  const glm::vec3 axis = glm::normalize(up);
  const glm::vec3 turned = glm::angleAxis(yaw, axis) * offset;
  const glm::vec3 side = glm::cross(axis, turned);
  scene::CameraView result = view;
  // Looking along the up axis already: there is no direction to pitch in.
  if (glm::length(side) < 1e-6F * radius) {
    result.position = view.target + turned;
    return result;
  }
  const float polar = std::acos(std::clamp(glm::dot(turned, axis) / radius, -1.0F, 1.0F));
  const float pitched = std::clamp(polar - pitch, kMinPolarAngle, glm::pi<float>() - kMinPolarAngle);
  // Turning about up x offset by a positive angle tilts the offset away from up.
  result.position = view.target + glm::angleAxis(pitched - polar, glm::normalize(side)) * turned;
  return result;
}

scene::CameraView flyThroughView(std::span<const scene::CameraView> views, double frame, uint32_t frames) {
  return cameraOnLoop(views, frame * static_cast<double>(views.size()) / std::max<uint32_t>(frames, 1));
}

}  // namespace spire::demo
