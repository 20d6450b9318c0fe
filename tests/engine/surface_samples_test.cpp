// Surface samples for uniform bakes (renderer/surface_samples.h): weights by
// area, linear attributes averaged exactly, and a box's average is its
// surface's, not its corners'.
#include "renderer/surface_samples.h"

#include <gtest/gtest.h>

#include <glm/geometric.hpp>
#include <numeric>
#include <random>

namespace spire::engine {
namespace {

template <typename F>
double average(const SurfaceSamples& samples, F value) {
  double sum = 0.0;
  for (size_t i = 0; i < samples.points.size(); ++i) sum += samples.weights[i] * value(samples.points[i]);
  return sum;
}

TEST(SurfaceSamples, WeightsAreAreaSharesThatSumToOne) {
  scene::Mesh mesh;
  // Two triangles, the second three times the area of the first.
  mesh.vertices = {{{0, 0, 0}}, {{1, 0, 0}}, {{0, 1, 0}}, {{10, 0, 0}}, {{13, 0, 0}}, {{10, 1, 0}}};
  mesh.indices = {0, 1, 2, 3, 4, 5};
  const SurfaceSamples samples = sampleSurface(mesh, 400);
  ASSERT_EQ(samples.points.size(), samples.weights.size());
  EXPECT_NEAR(std::accumulate(samples.weights.begin(), samples.weights.end(), 0.0), 1.0, 1e-12);
  double second = 0.0;
  for (size_t i = 0; i < samples.points.size(); ++i) {
    EXPECT_GT(samples.weights[i], 0.0);
    if (samples.points[i].position.x > 5.0F) second += samples.weights[i];
  }
  EXPECT_NEAR(second, 0.75, 1e-12);
  EXPECT_GE(samples.points.size(), 200U);
  EXPECT_LE(samples.points.size(), 800U);
}

// The centroid rule integrates linear functions exactly, so over any mesh the
// samples' average position is the area-weighted mean of the triangles'
// centroids. Random meshes, seeded.
TEST(SurfaceSamples, AverageALinearAttributeExactlyOnRandomMeshes) {
  std::mt19937 random(7);
  std::uniform_real_distribution<float> coordinate(-5.0F, 5.0F);
  for (int trial = 0; trial < 50; ++trial) {
    scene::Mesh mesh;
    const int triangles = 1 + trial % 9;
    for (int t = 0; t < 3 * triangles; ++t) {
      mesh.vertices.push_back({{coordinate(random), coordinate(random), coordinate(random)}});
      mesh.indices.push_back(static_cast<uint32_t>(t));
    }
    glm::dvec3 expected(0.0);
    double total = 0.0;
    for (int t = 0; t < triangles; ++t) {
      const glm::dvec3 a = mesh.vertices[3 * t].position, b = mesh.vertices[3 * t + 1].position,
                       c = mesh.vertices[3 * t + 2].position;
      const double area = 0.5 * glm::length(glm::cross(b - a, c - a));
      expected += area * (a + b + c) / 3.0;
      total += area;
    }
    expected /= total;
    const SurfaceSamples samples = sampleSurface(mesh, 1 + static_cast<uint32_t>(trial) * 37);
    for (int axis = 0; axis < 3; ++axis) {
      EXPECT_NEAR(average(samples, [&](const scene::Vertex& v) { return v.position[axis]; }), expected[axis], 1e-4)
          << "trial " << trial << " axis " << axis;
    }
  }
}

// Every corner of a box lies on a UV border: a value that is large only near
// the borders averages to 1 over the corners, yet is small over the faces.
TEST(SurfaceSamples, ABoxAveragesOverItsFacesNotItsCorners) {
  const scene::Mesh box = scene::makeBox(1.0F, 0.6F);
  const auto nearBorder = [](const scene::Vertex& v) {
    const float d = std::min({v.uv.x, 1.0F - v.uv.x, v.uv.y, 1.0F - v.uv.y});
    return d < 0.05F ? 1.0 : 0.0;
  };
  double corners = 0.0;
  for (const scene::Vertex& v : box.vertices) corners += nearBorder(v) / static_cast<double>(box.vertices.size());
  EXPECT_NEAR(corners, 1.0, 1e-12);
  // 1 - 0.9^2 of each face lies within 0.05 of its UV border.
  EXPECT_NEAR(average(sampleSurface(box, 4096), nearBorder), 0.19, 0.03);
}

TEST(SurfaceSamples, AMeshWithoutAreaFallsBackToItsVertices) {
  scene::Mesh line;
  line.vertices = {{{0, 0, 0}}, {{1, 0, 0}}, {{2, 0, 0}}};
  line.indices = {0, 1, 2};
  const SurfaceSamples samples = sampleSurface(line, 100);
  ASSERT_EQ(samples.points.size(), 3U);
  for (double w : samples.weights) EXPECT_DOUBLE_EQ(w, 1.0 / 3.0);
  EXPECT_TRUE(sampleSurface(scene::Mesh{}, 100).points.empty());
}

TEST(SurfaceSamples, AreDeterministic) {
  const scene::Mesh rock = scene::makeRock(0.7F, 6, 12, 5, 0.35F);
  const SurfaceSamples a = sampleSurface(rock, 1000);
  const SurfaceSamples b = sampleSurface(rock, 1000);
  ASSERT_EQ(a.points.size(), b.points.size());
  for (size_t i = 0; i < a.points.size(); ++i) {
    EXPECT_EQ(a.points[i].position, b.points[i].position);
    EXPECT_EQ(a.weights[i], b.weights[i]);
  }
}

}  // namespace
}  // namespace spire::engine
