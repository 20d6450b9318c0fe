#include "renderer/surface_samples.h"

#include <algorithm>
#include <cmath>

#include <glm/geometric.hpp>

namespace spire::engine {

namespace {

scene::Vertex blend(const scene::Vertex& a, const scene::Vertex& b, const scene::Vertex& c, float u, float v) {
  const float w = 1.0F - u - v;
  scene::Vertex p;
  p.position = w * a.position + u * b.position + v * c.position;
  p.normal = w * a.normal + u * b.normal + v * c.normal;
  p.uv = w * a.uv + u * b.uv + v * c.uv;
  p.tangent = w * a.tangent + u * b.tangent + v * c.tangent;
  return p;
}

double triangleArea(const scene::Vertex& a, const scene::Vertex& b, const scene::Vertex& c) {
  return 0.5 * static_cast<double>(glm::length(glm::cross(b.position - a.position, c.position - a.position)));
}

// The centroids of the k x k sub-triangles of a triangle split along lines
// parallel to its edges, in barycentric coordinates (u, v): k(k+1)/2
// upright ones and k(k-1)/2 inverted ones, all of one area.
void addCentroids(const scene::Vertex& a, const scene::Vertex& b, const scene::Vertex& c, uint32_t k, double weight,
                  SurfaceSamples& samples) {
  const float step = 1.0F / static_cast<float>(k);
  for (uint32_t i = 0; i < k; ++i) {
    for (uint32_t j = 0; i + j < k; ++j) {
      const auto fi = static_cast<float>(i);
      const auto fj = static_cast<float>(j);
      samples.points.push_back(blend(a, b, c, (fi + 1.0F / 3.0F) * step, (fj + 1.0F / 3.0F) * step));
      samples.weights.push_back(weight);
      if (i + j + 1 < k) {
        samples.points.push_back(blend(a, b, c, (fi + 2.0F / 3.0F) * step, (fj + 2.0F / 3.0F) * step));
        samples.weights.push_back(weight);
      }
    }
  }
}

SurfaceSamples vertexSamples(const scene::Mesh& mesh) {
  SurfaceSamples samples;
  samples.points = mesh.vertices;
  samples.weights.assign(mesh.vertices.size(), mesh.vertices.empty() ? 0.0 : 1.0 / mesh.vertices.size());
  return samples;
}

}  // namespace

SurfaceSamples sampleSurface(const scene::Mesh& mesh, uint32_t target) {
  std::vector<double> areas;
  double total = 0.0;
  for (size_t t = 0; t + 2 < mesh.indices.size(); t += 3) {
    const double area = triangleArea(mesh.vertices[mesh.indices[t]], mesh.vertices[mesh.indices[t + 1]],
                                     mesh.vertices[mesh.indices[t + 2]]);
    areas.push_back(std::isfinite(area) ? area : 0.0);
    total += areas.back();
  }
  if (!(total > 0.0) || !std::isfinite(total)) return vertexSamples(mesh);
  SurfaceSamples samples;
  for (size_t t = 0; t < areas.size(); ++t) {
    if (areas[t] <= 0.0) continue;
    // k^2 samples for an area share s: k = sqrt(s * target), at least 1.
    const double wanted = std::sqrt(areas[t] / total * static_cast<double>(target));
    const auto k = static_cast<uint32_t>(std::clamp(std::lround(wanted), 1L, 64L));
    addCentroids(mesh.vertices[mesh.indices[3 * t]], mesh.vertices[mesh.indices[3 * t + 1]],
                 mesh.vertices[mesh.indices[3 * t + 2]], k, areas[t] / total / (k * k), samples);
  }
  return samples;
}

}  // namespace spire::engine
