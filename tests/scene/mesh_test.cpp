#include "scene/mesh.h"

#include <gtest/gtest.h>

#include <glm/geometric.hpp>

#include <algorithm>
#include <cmath>

namespace spire::scene {
namespace {

constexpr float kEps = 1e-4f;

// Every generator promises: valid triangle indices, unit normals, unit
// tangents perpendicular to them with w = +-1, UVs in [0,1], finite data, and
// counter-clockwise faces whose geometric normal agrees with the vertex normals.
void expectMeshInvariants(const Mesh& mesh) {
  ASSERT_FALSE(mesh.vertices.empty());
  ASSERT_FALSE(mesh.indices.empty());
  ASSERT_EQ(mesh.indices.size() % 3, 0u);
  for (uint32_t index : mesh.indices) ASSERT_LT(index, mesh.vertices.size());
  for (const Vertex& v : mesh.vertices) {
    glm::vec3 t(v.tangent);
    ASSERT_NEAR(glm::length(v.normal), 1.0f, kEps);
    ASSERT_NEAR(glm::length(t), 1.0f, kEps);
    ASSERT_NEAR(glm::dot(v.normal, t), 0.0f, kEps);
    ASSERT_TRUE(v.tangent.w == 1.0f || v.tangent.w == -1.0f);
    ASSERT_GE(v.uv.x, 0.0f);
    ASSERT_LE(v.uv.x, 1.0f);
    ASSERT_GE(v.uv.y, 0.0f);
    ASSERT_LE(v.uv.y, 1.0f);
    ASSERT_TRUE(std::isfinite(v.position.x) && std::isfinite(v.position.y) && std::isfinite(v.position.z));
  }
  for (size_t i = 0; i < mesh.indices.size(); i += 3) {
    const Vertex& a = mesh.vertices[mesh.indices[i]];
    const Vertex& b = mesh.vertices[mesh.indices[i + 1]];
    const Vertex& c = mesh.vertices[mesh.indices[i + 2]];
    glm::vec3 face = glm::cross(b.position - a.position, c.position - a.position);
    ASSERT_GT(glm::length(face), 0.0f) << "degenerate triangle " << i / 3;
    ASSERT_GT(glm::dot(face, a.normal + b.normal + c.normal), 0.0f) << "triangle " << i / 3 << " is wound clockwise";
  }
}

// FNV-1a over the raw bytes: identical output must hash identically.
uint64_t hashBytes(const Mesh& mesh) {
  uint64_t h = 1469598103934665603ULL;
  auto feed = [&](const void* data, size_t size) {
    const auto* bytes = static_cast<const unsigned char*>(data);
    for (size_t i = 0; i < size; ++i) h = (h ^ bytes[i]) * 1099511628211ULL;
  };
  for (const Vertex& v : mesh.vertices) {
    feed(&v.position, sizeof v.position);
    feed(&v.normal, sizeof v.normal);
    feed(&v.uv, sizeof v.uv);
    feed(&v.tangent, sizeof v.tangent);
  }
  feed(mesh.indices.data(), mesh.indices.size() * sizeof(uint32_t));
  return h;
}

TEST(MeshTest, PlaneInvariantsAndLayout) {
  Mesh plane = makePlane(2.0f, 4);
  expectMeshInvariants(plane);
  EXPECT_EQ(plane.vertices.size(), 25u);
  EXPECT_EQ(plane.indices.size(), 4u * 4u * 6u);
  for (const Vertex& v : plane.vertices) {
    EXPECT_EQ(v.normal, glm::vec3(0, 1, 0));
    EXPECT_NEAR(v.tangent.x, 1.0f, kEps);  // u grows along +X
    EXPECT_LE(std::abs(v.position.x), 1.0f);
    EXPECT_LE(std::abs(v.position.z), 1.0f);
  }
}

TEST(MeshTest, PlaneClampsZeroSubdivisions) {
  Mesh plane = makePlane(1.0f, 0);
  expectMeshInvariants(plane);
  EXPECT_EQ(plane.vertices.size(), 4u);
}

TEST(MeshTest, SphereInvariantsAndRadius) {
  Mesh sphere = makeSphere(3.0f, 12, 24);
  expectMeshInvariants(sphere);
  for (const Vertex& v : sphere.vertices) {
    EXPECT_NEAR(glm::length(v.position), 3.0f, 1e-4f);
    EXPECT_NEAR(glm::dot(glm::normalize(v.position), v.normal), 1.0f, kEps);
  }
}

TEST(MeshTest, SpherePoleTangentsAreFinite) {
  Mesh sphere = makeSphere(1.0f, 2, 3);  // smallest sphere: every triangle touches a pole
  expectMeshInvariants(sphere);
  EXPECT_EQ(sphere.vertices.front().position, glm::vec3(0, 1, 0));
  EXPECT_EQ(sphere.vertices.back().position, glm::vec3(0, -1, 0));
}

TEST(MeshTest, TerrainInvariantsAndHeightRange) {
  Mesh terrain = makeTerrain(10.0f, 32, 2.0f, 7);
  expectMeshInvariants(terrain);
  float minY = 1e9f;
  float maxY = -1e9f;
  for (const Vertex& v : terrain.vertices) {
    minY = std::min(minY, v.position.y);
    maxY = std::max(maxY, v.position.y);
  }
  EXPECT_GE(minY, 0.0f);
  EXPECT_LE(maxY, 2.0f);
  EXPECT_GT(maxY - minY, 0.2f) << "terrain should not be flat";
}

TEST(MeshTest, TerrainNormalsMatchSurfaceSlope) {
  // On a grid fine relative to the finest noise octave, the finite-difference
  // normal must agree with the normal of the triangles around each interior
  // vertex (border vertices only see triangles on one side).
  constexpr uint32_t kResolution = 256;
  Mesh terrain = makeTerrain(4.0f, kResolution, 0.5f, 3);
  Mesh faceNormals = terrain;
  computeNormals(faceNormals);
  for (uint32_t j = 1; j < kResolution; ++j) {
    for (uint32_t i = 1; i < kResolution; ++i) {
      size_t index = j * (kResolution + 1) + i;
      ASSERT_GT(glm::dot(terrain.vertices[index].normal, faceNormals.vertices[index].normal), 0.99f) << i << "," << j;
    }
  }
}

TEST(MeshTest, TerrainIsDeterministicPerSeed) {
  Mesh a = makeTerrain(8.0f, 24, 1.5f, 42);
  Mesh b = makeTerrain(8.0f, 24, 1.5f, 42);
  Mesh c = makeTerrain(8.0f, 24, 1.5f, 43);
  EXPECT_EQ(hashBytes(a), hashBytes(b));
  EXPECT_NE(hashBytes(a), hashBytes(c));
  EXPECT_EQ(hashBytes(makeSphere(1.0f, 8, 16)), hashBytes(makeSphere(1.0f, 8, 16)));
  EXPECT_EQ(hashBytes(makePlane(1.0f, 3)), hashBytes(makePlane(1.0f, 3)));
}

// A unit quad in the XY plane facing +Z, u along +X and v along +Y: Lengyel's
// tangent is +X and the bitangent +Y = cross(+Z, +X), so handedness is +1.
Mesh handMadeQuad() {
  Mesh quad;
  auto vertex = [](glm::vec3 p, glm::vec2 uv) {
    Vertex v;
    v.position = p;
    v.normal = glm::vec3(0, 0, 1);
    v.uv = uv;
    v.tangent = glm::vec4(0.0f);
    return v;
  };
  quad.vertices = {vertex({0, 0, 0}, {0, 0}), vertex({1, 0, 0}, {1, 0}), vertex({1, 1, 0}, {1, 1}),
                   vertex({0, 1, 0}, {0, 1})};
  quad.indices = {0, 1, 2, 0, 2, 3};
  return quad;
}

TEST(TangentTest, QuadTangentFollowsU) {
  Mesh quad = handMadeQuad();
  computeTangents(quad);
  for (const Vertex& v : quad.vertices) {
    EXPECT_NEAR(v.tangent.x, 1.0f, kEps);
    EXPECT_NEAR(v.tangent.y, 0.0f, kEps);
    EXPECT_NEAR(v.tangent.z, 0.0f, kEps);
    EXPECT_EQ(v.tangent.w, 1.0f);
  }
}

TEST(TangentTest, MirroredUvsFlipHandedness) {
  Mesh quad = handMadeQuad();
  for (Vertex& v : quad.vertices) v.uv.y = 1.0f - v.uv.y;  // v now runs along -Y
  computeTangents(quad);
  for (const Vertex& v : quad.vertices) {
    EXPECT_NEAR(v.tangent.x, 1.0f, kEps);
    EXPECT_EQ(v.tangent.w, -1.0f);
  }
}

TEST(TangentTest, TiltedNormalIsOrthogonalised) {
  Mesh quad = handMadeQuad();
  for (Vertex& v : quad.vertices) v.normal = glm::normalize(glm::vec3(1, 0, 1));
  computeTangents(quad);
  glm::vec3 expected = glm::normalize(glm::vec3(1, 0, -1));  // +X minus its normal component
  for (const Vertex& v : quad.vertices) {
    EXPECT_NEAR(glm::dot(glm::vec3(v.tangent), expected), 1.0f, kEps);
  }
}

TEST(TangentTest, DegenerateUvsFallBackToPerpendicular) {
  Mesh quad = handMadeQuad();
  for (Vertex& v : quad.vertices) v.uv = glm::vec2(0.5f);
  computeTangents(quad);
  for (const Vertex& v : quad.vertices) {
    glm::vec3 t(v.tangent);
    EXPECT_TRUE(std::isfinite(t.x) && std::isfinite(t.y) && std::isfinite(t.z));
    EXPECT_NEAR(glm::length(t), 1.0f, kEps);
    EXPECT_NEAR(glm::dot(t, v.normal), 0.0f, kEps);
    EXPECT_EQ(v.tangent.w, 1.0f);
  }
}

TEST(NormalTest, FaceNormalsOfQuad) {
  Mesh quad = handMadeQuad();
  for (Vertex& v : quad.vertices) v.normal = glm::vec3(0.0f);
  computeNormals(quad);
  for (const Vertex& v : quad.vertices) EXPECT_EQ(v.normal, glm::vec3(0, 0, 1));
}

}  // namespace
}  // namespace spire::scene
