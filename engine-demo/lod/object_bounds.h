// How far an object is from the camera, for level selection: its extent in
// world space as a sphere and an axis-aligned box, both containing it.
// Either alone can be far from the object's shape: the sphere of a flat
// terrain tile reaches half the tile's width above the ground, so a camera
// flying over the tile is inside it, at distance 0, wherever the ground is,
// and the tile is drawn at the nearest level. Every point of the object is
// in both, so its nearest point is at least as far as either's nearest
// point: the larger of the two distances is the closer bound (and the
// smaller of the two farthest distances).
#pragma once

#include <glm/mat4x4.hpp>
#include <glm/vec3.hpp>

namespace spire::lod {

struct ObjectBounds {
  glm::vec3 center{0.0F};  // of the sphere
  float radius = 0.0F;
  glm::vec3 boxCenter{0.0F};
  glm::vec3 halfExtent{0.0F};  // of the box, per axis

  // A sphere alone: its box is the cube around it.
  static ObjectBounds sphere(const glm::vec3& center, float radius);
  // Points from `lo` to `hi` per axis whose farthest from the box's center
  // is `radius` away (at most half the box's diagonal).
  static ObjectBounds box(const glm::vec3& lo, const glm::vec3& hi, float radius);

  // The bounds of the same object placed by `model`, an affine transform:
  // the sphere scaled by the largest axis scale, the box around the
  // transformed box.
  ObjectBounds transformed(const glm::mat4& model) const;

  // From `point` to the nearest point of both bounds (0 inside them) and to
  // the farthest.
  float nearest(const glm::vec3& point) const;
  float farthest(const glm::vec3& point) const;
};

}  // namespace spire::lod
