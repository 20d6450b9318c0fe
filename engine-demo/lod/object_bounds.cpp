#include "lod/object_bounds.h"

#include <glm/common.hpp>
#include <glm/geometric.hpp>
#include <glm/mat3x3.hpp>

#include <algorithm>

namespace spire::lod {

ObjectBounds ObjectBounds::sphere(const glm::vec3& center, float radius) {
  return {center, radius, center, glm::vec3(radius)};
}

ObjectBounds ObjectBounds::box(const glm::vec3& lo, const glm::vec3& hi, float radius) {
  const glm::vec3 center = (lo + hi) * 0.5F;
  return {center, radius, center, (hi - lo) * 0.5F};
}

ObjectBounds ObjectBounds::transformed(const glm::mat4& model) const {
  const glm::mat3 linear(model);
  const float scale = std::max({glm::length(linear[0]), glm::length(linear[1]), glm::length(linear[2])});
  // Each world axis of the box reaches as far as the model's row, taken in
  // absolute value, reaches along the local half extents.
  glm::mat3 absolute;
  for (int c = 0; c < 3; ++c) absolute[c] = glm::abs(linear[c]);
  return {glm::vec3(model * glm::vec4(center, 1.0F)), radius * scale, glm::vec3(model * glm::vec4(boxCenter, 1.0F)),
          absolute * halfExtent};
}

float ObjectBounds::nearest(const glm::vec3& point) const {
  const float toSphere = std::max(0.0F, glm::distance(point, center) - radius);
  const float toBox = glm::length(glm::max(glm::abs(point - boxCenter) - halfExtent, glm::vec3(0.0F)));
  return std::max(toSphere, toBox);
}

float ObjectBounds::farthest(const glm::vec3& point) const {
  const float toSphere = glm::distance(point, center) + radius;
  const float toBox = glm::length(glm::abs(point - boxCenter) + halfExtent);
  return std::min(toSphere, toBox);
}

}  // namespace spire::lod
