#include "scene/scatter.h"

#include <glm/ext/matrix_transform.hpp>
#include <glm/gtc/constants.hpp>

#include "scene/mesh.h"

namespace spire::scene {

namespace {

// splitmix64: the same numbers from a seed on every platform, which the
// standard distributions do not promise.
class SeededRandom {
 public:
  explicit SeededRandom(uint64_t seed) : state_(seed * 0x9E3779B97F4A7C15ULL + 0x632BE59BD9B4E019ULL) {}
  float unit() {  // in [0, 1)
    uint64_t z = (state_ += 0x9E3779B97F4A7C15ULL);
    z = (z ^ (z >> 30U)) * 0xBF58476D1CE4E5B9ULL;
    z = (z ^ (z >> 27U)) * 0x94D049BB133111EBULL;
    z ^= z >> 31U;
    return static_cast<float>(z >> 40U) / static_cast<float>(1U << 24U);
  }

 private:
  uint64_t state_;
};

}  // namespace

Expected<std::vector<glm::mat4>> placementsOf(const InstanceDesc& instance, const SceneFile& scene) {
  if (!instance.scatter) return std::vector<glm::mat4>{instance.transform};
  const ScatterDesc& scatter = *instance.scatter;
  const MeshDesc* terrain = scene.findMesh(scatter.on);
  if (!terrain || terrain->kind != MeshKind::Terrain) {
    return Error{"'scatter' places copies on a terrain mesh, and '" + scatter.on + "' is not one"};
  }
  SeededRandom random(scatter.seed);
  std::vector<glm::mat4> placements;
  placements.reserve(scatter.count);
  // Not quite to the edge, so that no copy overhangs the terrain.
  const float extent = terrain->size * 0.96F;
  for (uint32_t i = 0; i < scatter.count; ++i) {
    const float x = (random.unit() - 0.5F) * extent;
    const float z = (random.unit() - 0.5F) * extent;
    const float angle = random.unit() * glm::two_pi<float>();
    const float scale = scatter.scaleMin + random.unit() * (scatter.scaleMax - scatter.scaleMin);
    const float y = terrainHeight(terrain->size, terrain->height, terrain->seed, x, z);
    glm::mat4 model = glm::translate(glm::mat4(1.0F), glm::vec3(x, y, z));
    model = glm::rotate(model, angle, glm::vec3(0.0F, 1.0F, 0.0F));
    model = glm::scale(model, glm::vec3(scale));
    placements.push_back(model * instance.transform);
  }
  return placements;
}

}  // namespace spire::scene
