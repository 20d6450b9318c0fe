#include "lod/object_bounds.h"

#include <gtest/gtest.h>
#include <glm/ext/matrix_transform.hpp>
#include <glm/geometric.hpp>

#include <algorithm>
#include <random>
#include <vector>

namespace spire::lod {
namespace {

// A terrain tile, 50 wide and 1 high, seen from 14 above its centre: inside
// its bounding sphere (radius ~35), yet the ground is 13.5 away.
TEST(ObjectBoundsTest, AFlatTileIsAsFarAsItsBoxWhenTheCameraIsInsideItsSphere) {
  const ObjectBounds tile =
      ObjectBounds::box({-25.0F, -0.5F, -25.0F}, {25.0F, 0.5F, 25.0F}, glm::length(glm::vec3(25.0F, 0.5F, 25.0F)));
  EXPECT_FLOAT_EQ(tile.nearest({0.0F, 14.0F, 0.0F}), 13.5F);
  EXPECT_FLOAT_EQ(tile.nearest({30.0F, 0.0F, 0.0F}), 5.0F);  // beside it
  EXPECT_FLOAT_EQ(tile.nearest({0.0F, 0.0F, 0.0F}), 0.0F);   // in it
  // Farthest: the far corner of the box, nearer than the sphere's far side.
  EXPECT_FLOAT_EQ(tile.farthest({0.0F, 14.0F, 0.0F}), glm::length(glm::vec3(25.0F, 14.5F, 25.0F)));
  const ObjectBounds ball = ObjectBounds::sphere({0.0F, 0.0F, 10.0F}, 2.0F);
  EXPECT_FLOAT_EQ(ball.nearest({0.0F, 0.0F, 0.0F}), 8.0F);
  EXPECT_FLOAT_EQ(ball.farthest({0.0F, 0.0F, 0.0F}), 12.0F);
}

// Property: for random point clouds placed by random rotations, uniform
// scales and translations, the transformed bounds contain every placed
// point: no camera is farther from the nearest point than `nearest` says,
// or nearer to the farthest than `farthest` says; and the bound is never
// looser than the sphere alone.
TEST(ObjectBoundsTest, TransformedBoundsHoldEveryPointOfTheObject) {
  std::mt19937 rng(5);
  std::uniform_real_distribution<float> unit(-1.0F, 1.0F);
  for (int trial = 0; trial < 200; ++trial) {
    const glm::vec3 stretch(1.0F + 4.0F * std::abs(unit(rng)), 0.1F + std::abs(unit(rng)), 1.0F + std::abs(unit(rng)));
    std::vector<glm::vec3> points(8 + rng() % 40);
    glm::vec3 lo(1e9F);
    glm::vec3 hi(-1e9F);
    for (glm::vec3& p : points) {
      p = glm::vec3(unit(rng), unit(rng), unit(rng)) * stretch;
      lo = glm::min(lo, p);
      hi = glm::max(hi, p);
    }
    float radius = 0.0F;
    for (const glm::vec3& p : points) radius = std::max(radius, glm::distance(p, (lo + hi) * 0.5F));
    glm::mat4 model = glm::translate(glm::mat4(1.0F), glm::vec3(unit(rng), unit(rng), unit(rng)) * 20.0F);
    model = glm::rotate(model, 3.2F * unit(rng), glm::normalize(glm::vec3(unit(rng), unit(rng), unit(rng)) + 1e-3F));
    model = glm::scale(model, glm::vec3(0.5F + 2.0F * std::abs(unit(rng))));
    const ObjectBounds placed = ObjectBounds::box(lo, hi, radius).transformed(model);
    for (int c = 0; c < 20; ++c) {
      const glm::vec3 camera = glm::vec3(unit(rng), unit(rng), unit(rng)) * 40.0F;
      float nearestPoint = 1e9F;
      float farthestPoint = 0.0F;
      for (const glm::vec3& p : points) {
        const float d = glm::distance(camera, glm::vec3(model * glm::vec4(p, 1.0F)));
        nearestPoint = std::min(nearestPoint, d);
        farthestPoint = std::max(farthestPoint, d);
      }
      ASSERT_LE(placed.nearest(camera), nearestPoint + 1e-3F) << "trial " << trial;
      ASSERT_GE(placed.farthest(camera), farthestPoint - 1e-3F) << "trial " << trial;
      const float sphereOnly = std::max(0.0F, glm::distance(camera, placed.center) - placed.radius);
      ASSERT_GE(placed.nearest(camera), sphereOnly);
    }
  }
}

}  // namespace
}  // namespace spire::lod
