#include "scene/terrain_tiles.h"

#include <fmt/format.h>

#include <utility>

namespace spire::scene {

std::string tileMeshName(const std::string& mesh, uint32_t x, uint32_t z) {
  return fmt::format("{}[{},{}]", mesh, x, z);
}

namespace {

// The tile meshes of `whole`, in row order; nothing when a name is taken.
std::vector<MeshDesc> tileMeshes(const MeshDesc& whole, const SceneFile& scene, DiagnosticList& diags) {
  std::vector<MeshDesc> tiles;
  for (uint32_t z = 0; z < whole.tiles; ++z) {
    for (uint32_t x = 0; x < whole.tiles; ++x) {
      MeshDesc tile = whole;
      tile.name = tileMeshName(whole.name, x, z);
      tile.tiles = 1;
      tile.tile = {whole.tiles, x, z};
      if (const MeshDesc* taken = scene.findMesh(tile.name)) {
        diags.report(DiagCode::E7007, taken->range,
                     fmt::format("mesh '{}' is also the name of a tile of the tiled terrain '{}'; rename one",
                                 tile.name, whole.name));
        return {};
      }
      tiles.push_back(std::move(tile));
    }
  }
  return tiles;
}

}  // namespace

void splitTiles(SceneFile& scene, DiagnosticList& diags) {
  std::vector<MeshDesc> added;
  std::vector<InstanceDesc> instances;
  bool taken = false;
  for (const MeshDesc& mesh : scene.meshes) {
    if (mesh.tiles > 1) {
      std::vector<MeshDesc> tiles = tileMeshes(mesh, scene, diags);
      taken = taken || tiles.empty();
      added.insert(added.end(), tiles.begin(), tiles.end());
    }
  }
  if (added.empty() || taken) return;
  for (const InstanceDesc& instance : scene.instances) {
    const MeshDesc* mesh = scene.findMesh(instance.mesh);
    if (!mesh || mesh->tiles <= 1) {
      instances.push_back(instance);
      continue;
    }
    for (uint32_t z = 0; z < mesh->tiles; ++z) {
      for (uint32_t x = 0; x < mesh->tiles; ++x) {
        InstanceDesc tile = instance;
        tile.mesh = tileMeshName(instance.mesh, x, z);
        instances.push_back(std::move(tile));
      }
    }
  }
  scene.meshes.insert(scene.meshes.end(), added.begin(), added.end());
  scene.instances = std::move(instances);
}

}  // namespace spire::scene
