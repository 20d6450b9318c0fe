#pragma once

// Triangle meshes for the demo engine and their procedural generators.
// Conventions: counter-clockwise front faces, +Y up, UV origin at the first
// texel row; tangent.xyz follows increasing u and the bitangent (increasing v)
// is cross(normal, tangent.xyz) * tangent.w, as in glTF.

#include <glm/vec2.hpp>
#include <glm/vec3.hpp>
#include <glm/vec4.hpp>

#include <cstdint>
#include <string>
#include <vector>

namespace spire::scene {

struct Vertex {
  glm::vec3 position{0.0f};
  glm::vec3 normal{0.0f, 1.0f, 0.0f};
  glm::vec2 uv{0.0f};
  glm::vec4 tangent{1.0f, 0.0f, 0.0f, 1.0f};  // xyz tangent, w handedness +-1
};

struct Mesh {
  std::string name;
  std::vector<Vertex> vertices;
  std::vector<uint32_t> indices;  // triangle list, counter-clockwise seen from the front
  // Seen from both sides, so the engine draws its back faces too; every
  // other mesh has its back faces culled. Only a glTF material says so.
  bool doubleSided = false;
};

// Square in the XZ plane centred at the origin, facing +Y, with
// `subdivisions` quads per side (at least 1).
Mesh makePlane(float size, uint32_t subdivisions);

// UV sphere centred at the origin; rings >= 2 latitude bands, segments >= 3.
// The seam column is duplicated so UVs stay continuous.
Mesh makeSphere(float radius, uint32_t rings, uint32_t segments);

// One cell of a `tiles` x `tiles` split of a grid mesh, column x, row z
// (both from 0, x along +X, z along +Z). The whole mesh is the one tile of
// a 1 x 1 split.
struct GridTile {
  uint32_t tiles = 1;
  uint32_t x = 0;
  uint32_t z = 0;
};

// Heightfield over a `size` x `size` square with `resolution` quads per side;
// heights in [0, height] from fBm noise. A given seed gives identical bytes.
// With `tile`, only that tile's quads (resolution / tiles per side, the last
// tile taking the remainder), with the whole terrain's positions, normals
// and UVs, so that tiles drawn side by side are the whole terrain.
Mesh makeTerrain(float size, uint32_t resolution, float height, uint32_t seed, GridTile tile = {});

// The height of makeTerrain's surface at world (x, z), which may lie between
// its vertices or outside it; for placing objects on the terrain.
float terrainHeight(float size, float height, uint32_t seed, float x, float z);

// Box of `size` x `height` x `size` standing on the XZ plane, centred on the
// Y axis; each face has its own vertices and UVs over [0, 1].
Mesh makeBox(float size, float height);

// Closed cylinder of `radius` standing on the XZ plane, `height` tall, with
// `segments` around; the side's u goes around, v up, the caps' UVs map the
// disc into [0, 1].
Mesh makeCylinder(float radius, float height, uint32_t segments);

// A rock: a sphere whose radius varies by fBm noise of `seed` by up to
// `roughness` of it, resting on the XZ plane.
Mesh makeRock(float radius, uint32_t rings, uint32_t segments, uint32_t seed, float roughness);

// Area-weighted smooth normals from the triangles (for meshes without them).
void computeNormals(Mesh& mesh);

// Per-vertex tangents from positions and UVs (Lengyel's method), made
// orthogonal to the normal with Gram-Schmidt; w holds the handedness. Vertices
// whose UVs are degenerate get an arbitrary tangent perpendicular to the normal.
void computeTangents(Mesh& mesh);

}  // namespace spire::scene
