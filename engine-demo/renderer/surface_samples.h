// Points spread over a mesh's surface, for bakes that stand for the whole
// surface with one value (PrebakeUniform). An average over the mesh's
// vertices is an average over wherever the modeller happened to put them: a
// box's eight corners all lie on its UV seams, a terrain's vertices crowd
// where it is finely tessellated. The fragments that the baked value
// replaces cover the surface by area, so the samples do too.
#pragma once

#include <cstdint>
#include <vector>

#include "scene/mesh.h"

namespace spire::engine {

struct SurfaceSamples {
  // One vertex per sample, every attribute interpolated linearly across its
  // triangle, as the rasterizer interpolates them for fragments; no
  // triangles.
  std::vector<scene::Vertex> points;
  // Each sample's share of the surface's area; they sum to 1.
  std::vector<double> weights;
};

// About `target` samples (at least one per triangle of nonzero area), each
// triangle split into k x k congruent sub-triangles sampled at their
// centroids, k growing with the triangle's share of the area. Deterministic.
// A mesh without area (only degenerate triangles) gets its vertices, equally
// weighted.
SurfaceSamples sampleSurface(const scene::Mesh& mesh, uint32_t target);

}  // namespace spire::engine
