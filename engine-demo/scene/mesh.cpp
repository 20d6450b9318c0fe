#include "scene/mesh.h"

#include "scene/noise.h"

#include <glm/geometric.hpp>
#include <glm/gtc/constants.hpp>

#include <algorithm>
#include <cmath>

namespace spire::scene {
namespace {

// Any unit vector perpendicular to n: cross with the axis least aligned with n,
// which keeps the cross product well away from zero length.
glm::vec3 anyPerpendicular(const glm::vec3& n) {
  glm::vec3 a = std::abs(n.x) < 0.9f ? glm::vec3(1.0f, 0.0f, 0.0f) : glm::vec3(0.0f, 1.0f, 0.0f);
  return glm::normalize(glm::cross(n, a));
}

bool isUsable(const glm::vec3& v) {
  float len2 = glm::dot(v, v);
  return std::isfinite(len2) && len2 > 1e-12f;
}

// Indices of a (columns x rows) quad grid of (columns+1) x (rows+1) vertices,
// wound counter-clockwise when seen from +Y for row index growing along +Z.
void appendGridIndices(std::vector<uint32_t>& indices, uint32_t columns, uint32_t rows) {
  uint32_t stride = columns + 1;
  for (uint32_t j = 0; j < rows; ++j) {
    for (uint32_t i = 0; i < columns; ++i) {
      uint32_t a = j * stride + i;
      uint32_t b = a + 1;
      uint32_t c = a + stride;
      uint32_t d = c + 1;
      indices.insert(indices.end(), {a, c, b, b, c, d});
    }
  }
}

}  // namespace

Mesh makePlane(float size, uint32_t subdivisions) {
  subdivisions = std::max(subdivisions, 1u);
  Mesh mesh;
  mesh.name = "plane";
  for (uint32_t j = 0; j <= subdivisions; ++j) {
    for (uint32_t i = 0; i <= subdivisions; ++i) {
      glm::vec2 uv(static_cast<float>(i) / static_cast<float>(subdivisions),
                   static_cast<float>(j) / static_cast<float>(subdivisions));
      Vertex v;
      v.position = glm::vec3((uv.x - 0.5f) * size, 0.0f, (uv.y - 0.5f) * size);
      v.normal = glm::vec3(0.0f, 1.0f, 0.0f);
      v.uv = uv;
      mesh.vertices.push_back(v);
    }
  }
  appendGridIndices(mesh.indices, subdivisions, subdivisions);
  computeTangents(mesh);
  return mesh;
}

Mesh makeSphere(float radius, uint32_t rings, uint32_t segments) {
  rings = std::max(rings, 2u);
  segments = std::max(segments, 3u);
  Mesh mesh;
  mesh.name = "sphere";
  for (uint32_t r = 0; r <= rings; ++r) {
    float v = static_cast<float>(r) / static_cast<float>(rings);
    float theta = v * glm::pi<float>();
    // Exact poles: sin(pi) is not 0 in float, and the pole triangles below are
    // only skipped safely if every pole vertex really sits on the axis.
    bool pole = r == 0 || r == rings;
    float sinTheta = pole ? 0.0f : std::sin(theta);
    float cosTheta = r == 0 ? 1.0f : (r == rings ? -1.0f : std::cos(theta));
    for (uint32_t s = 0; s <= segments; ++s) {
      float u = static_cast<float>(s) / static_cast<float>(segments);
      float phi = u * glm::two_pi<float>();
      glm::vec3 n(sinTheta * std::cos(phi), cosTheta, sinTheta * std::sin(phi));
      Vertex vertex;
      vertex.position = n * radius;
      vertex.normal = n;
      vertex.uv = glm::vec2(u, v);
      // Analytic dP/du direction: unlike Lengyel's method it stays defined at
      // the poles, where the triangles touching the vertex are degenerate.
      // cross(n, t) equals dP/dv here, hence handedness +1.
      vertex.tangent = glm::vec4(-std::sin(phi), 0.0f, std::cos(phi), 1.0f);
      mesh.vertices.push_back(vertex);
    }
  }
  uint32_t stride = segments + 1;
  for (uint32_t r = 0; r < rings; ++r) {
    for (uint32_t s = 0; s < segments; ++s) {
      uint32_t a = r * stride + s;
      uint32_t b = a + 1;
      uint32_t c = a + stride;
      uint32_t d = c + 1;
      // Rows run from +Y down, so (a, b, c) faces outwards. The top ring's
      // (a, b) and the bottom ring's (c, d) collapse onto the poles.
      if (r != 0) mesh.indices.insert(mesh.indices.end(), {a, b, c});
      if (r != rings - 1) mesh.indices.insert(mesh.indices.end(), {b, d, c});
    }
  }
  return mesh;
}

namespace {
constexpr float kTerrainFeatures = 4.0f;  // noise lattice cells across the terrain
constexpr uint32_t kTerrainOctaves = 5;
}  // namespace

float terrainHeight(float size, float height, uint32_t seed, float x, float z) {
  const float u = x / size + 0.5f;
  const float v = z / size + 0.5f;
  return height * fbm(u * kTerrainFeatures, v * kTerrainFeatures, seed, kTerrainOctaves);
}

Mesh makeTerrain(float size, uint32_t resolution, float height, uint32_t seed, GridTile tile) {
  resolution = std::max(resolution, 1u);
  const uint32_t tiles = std::clamp(tile.tiles, 1u, resolution);
  const auto firstQuad = [&](uint32_t t) { return resolution * std::min(t, tiles) / tiles; };
  const uint32_t i0 = firstQuad(tile.x), i1 = firstQuad(tile.x + 1);
  const uint32_t j0 = firstQuad(tile.z), j1 = firstQuad(tile.z + 1);
  auto heightAt = [&](float u, float v) {
    return height * fbm(u * kTerrainFeatures, v * kTerrainFeatures, seed, kTerrainOctaves);
  };

  Mesh mesh;
  mesh.name = "terrain";
  float step = 1.0f / static_cast<float>(resolution);
  float worldStep = size * step;
  for (uint32_t j = j0; j <= j1; ++j) {
    for (uint32_t i = i0; i <= i1; ++i) {
      glm::vec2 uv(static_cast<float>(i) * step, static_cast<float>(j) * step);
      Vertex vertex;
      vertex.position = glm::vec3((uv.x - 0.5f) * size, heightAt(uv.x, uv.y), (uv.y - 0.5f) * size);
      // Central differences of the height function itself (not of neighbouring
      // vertices), so border vertices get the same quality as interior ones.
      float dhdx = (heightAt(uv.x + step, uv.y) - heightAt(uv.x - step, uv.y)) / (2.0f * worldStep);
      float dhdz = (heightAt(uv.x, uv.y + step) - heightAt(uv.x, uv.y - step)) / (2.0f * worldStep);
      vertex.normal = glm::normalize(glm::vec3(-dhdx, 1.0f, -dhdz));
      vertex.uv = uv;
      mesh.vertices.push_back(vertex);
    }
  }
  appendGridIndices(mesh.indices, i1 - i0, j1 - j0);
  computeTangents(mesh);
  return mesh;
}

namespace {

// One flat quad: corners a, b, c, d counter-clockwise seen from the front,
// UVs (0,0), (1,0), (1,1), (0,1).
void appendQuad(Mesh& mesh, const glm::vec3& a, const glm::vec3& b, const glm::vec3& c, const glm::vec3& d) {
  const auto base = static_cast<uint32_t>(mesh.vertices.size());
  const glm::vec3 n = glm::normalize(glm::cross(b - a, d - a));
  const glm::vec3 corners[] = {a, b, c, d};
  const glm::vec2 uvs[] = {{0.0f, 0.0f}, {1.0f, 0.0f}, {1.0f, 1.0f}, {0.0f, 1.0f}};
  for (int i = 0; i < 4; ++i) mesh.vertices.push_back({corners[i], n, uvs[i], {}});
  mesh.indices.insert(mesh.indices.end(), {base, base + 1, base + 2, base, base + 2, base + 3});
}

}  // namespace

Mesh makeBox(float size, float height) {
  Mesh mesh;
  mesh.name = "box";
  const float s = size * 0.5f;
  const auto p = [&](float x, float y, float z) { return glm::vec3(x * s, y * height, z * s); };
  appendQuad(mesh, p(-1, 0, 1), p(1, 0, 1), p(1, 1, 1), p(-1, 1, 1));      // +Z
  appendQuad(mesh, p(1, 0, -1), p(-1, 0, -1), p(-1, 1, -1), p(1, 1, -1));  // -Z
  appendQuad(mesh, p(1, 0, 1), p(1, 0, -1), p(1, 1, -1), p(1, 1, 1));      // +X
  appendQuad(mesh, p(-1, 0, -1), p(-1, 0, 1), p(-1, 1, 1), p(-1, 1, -1));  // -X
  appendQuad(mesh, p(-1, 1, 1), p(1, 1, 1), p(1, 1, -1), p(-1, 1, -1));    // +Y
  appendQuad(mesh, p(-1, 0, -1), p(1, 0, -1), p(1, 0, 1), p(-1, 0, 1));    // -Y
  computeTangents(mesh);
  return mesh;
}

Mesh makeCylinder(float radius, float height, uint32_t segments) {
  segments = std::max(segments, 3u);
  Mesh mesh;
  mesh.name = "cylinder";
  for (uint32_t row = 0; row <= 1; ++row) {
    for (uint32_t s = 0; s <= segments; ++s) {
      const float u = static_cast<float>(s) / static_cast<float>(segments);
      const float phi = u * glm::two_pi<float>();
      const glm::vec3 n(std::cos(phi), 0.0f, -std::sin(phi));
      mesh.vertices.push_back({n * radius + glm::vec3(0.0f, height * static_cast<float>(row), 0.0f),
                               n,
                               glm::vec2(u, static_cast<float>(row)),
                               {}});
    }
  }
  appendGridIndices(mesh.indices, segments, 1);
  // appendGridIndices winds for rows along +Z seen from +Y; the side's rows
  // go up and its columns turn counter-clockwise seen from +Y, which faces
  // the quads inwards, so flip them.
  for (size_t t = 0; t + 2 < mesh.indices.size(); t += 3) std::swap(mesh.indices[t + 1], mesh.indices[t + 2]);
  for (int cap = 0; cap < 2; ++cap) {
    const float y = cap == 0 ? 0.0f : height;
    const glm::vec3 n(0.0f, cap == 0 ? -1.0f : 1.0f, 0.0f);
    const auto centre = static_cast<uint32_t>(mesh.vertices.size());
    mesh.vertices.push_back({glm::vec3(0.0f, y, 0.0f), n, glm::vec2(0.5f), {}});
    for (uint32_t s = 0; s <= segments; ++s) {
      const float phi = static_cast<float>(s) / static_cast<float>(segments) * glm::two_pi<float>();
      const glm::vec2 dir(std::cos(phi), -std::sin(phi));
      mesh.vertices.push_back({glm::vec3(dir.x * radius, y, dir.y * radius), n, dir * 0.5f + 0.5f, {}});
      if (s == 0) continue;
      const uint32_t a = centre + s;
      const uint32_t b = centre + s + 1;
      // Angles grow counter-clockwise seen from +Y.
      if (cap == 0) {
        mesh.indices.insert(mesh.indices.end(), {centre, b, a});
      } else {
        mesh.indices.insert(mesh.indices.end(), {centre, a, b});
      }
    }
  }
  computeTangents(mesh);
  return mesh;
}

Mesh makeRock(float radius, uint32_t rings, uint32_t segments, uint32_t seed, float roughness) {
  Mesh mesh = makeSphere(1.0f, rings, segments);
  mesh.name = "rock";
  float lowest = 0.0f;
  for (Vertex& v : mesh.vertices) {
    const glm::vec3 d = v.position;
    // Noise of the direction (not of the UV) so that the seam and the poles,
    // whose vertices are duplicated, move together.
    const float n = fbm(d.x * 1.7f + d.y * 0.6f + 11.0f, d.z * 1.7f - d.y * 0.9f + 5.0f, seed, 4);
    v.position = d * radius * (1.0f + roughness * (2.0f * n - 1.0f));
    v.position.y *= 0.7f;  // rocks are wider than tall
    lowest = std::min(lowest, v.position.y);
  }
  for (Vertex& v : mesh.vertices) v.position.y -= lowest;
  computeNormals(mesh);
  computeTangents(mesh);
  return mesh;
}

void computeNormals(Mesh& mesh) {
  std::vector<glm::vec3> sums(mesh.vertices.size(), glm::vec3(0.0f));
  for (size_t t = 0; t + 2 < mesh.indices.size(); t += 3) {
    uint32_t i0 = mesh.indices[t], i1 = mesh.indices[t + 1], i2 = mesh.indices[t + 2];
    const glm::vec3& p0 = mesh.vertices[i0].position;
    // The unnormalised cross product weights each face by its area.
    glm::vec3 face = glm::cross(mesh.vertices[i1].position - p0, mesh.vertices[i2].position - p0);
    sums[i0] += face;
    sums[i1] += face;
    sums[i2] += face;
  }
  for (size_t i = 0; i < mesh.vertices.size(); ++i) {
    // Vertices only on degenerate triangles still need a unit normal.
    mesh.vertices[i].normal = isUsable(sums[i]) ? glm::normalize(sums[i]) : glm::vec3(0.0f, 1.0f, 0.0f);
  }
}

void computeTangents(Mesh& mesh) {
  std::vector<glm::vec3> tangents(mesh.vertices.size(), glm::vec3(0.0f));
  std::vector<glm::vec3> bitangents(mesh.vertices.size(), glm::vec3(0.0f));
  for (size_t t = 0; t + 2 < mesh.indices.size(); t += 3) {
    uint32_t idx[3] = {mesh.indices[t], mesh.indices[t + 1], mesh.indices[t + 2]};
    const Vertex& v0 = mesh.vertices[idx[0]];
    const Vertex& v1 = mesh.vertices[idx[1]];
    const Vertex& v2 = mesh.vertices[idx[2]];
    glm::vec3 e1 = v1.position - v0.position;
    glm::vec3 e2 = v2.position - v0.position;
    glm::vec2 d1 = v1.uv - v0.uv;
    glm::vec2 d2 = v2.uv - v0.uv;
    float det = d1.x * d2.y - d2.x * d1.y;
    // Zero-area UV triangles carry no tangent information at all.
    if (!std::isfinite(det) || std::abs(det) < 1e-12f) continue;
    float r = 1.0f / det;
    glm::vec3 sdir = (e1 * d2.y - e2 * d1.y) * r;
    glm::vec3 tdir = (e2 * d1.x - e1 * d2.x) * r;
    for (uint32_t i : idx) {
      tangents[i] += sdir;
      bitangents[i] += tdir;
    }
  }
  for (size_t i = 0; i < mesh.vertices.size(); ++i) {
    Vertex& vertex = mesh.vertices[i];
    const glm::vec3& n = vertex.normal;
    glm::vec3 t = tangents[i] - n * glm::dot(n, tangents[i]);
    if (!isUsable(t)) {
      vertex.tangent = glm::vec4(anyPerpendicular(n), 1.0f);
      continue;
    }
    t = glm::normalize(t);
    float w = glm::dot(glm::cross(n, t), bitangents[i]) < 0.0f ? -1.0f : 1.0f;
    vertex.tangent = glm::vec4(t, w);
  }
}

}  // namespace spire::scene
