// Where the copies of a scattered instance go ("scatter" in the scene file):
// seeded, so that one scene file gives the same placements everywhere.
#pragma once

#include <glm/mat4x4.hpp>

#include <vector>

#include "scene/expected.h"
#include "scene/scene_file.h"

namespace spire::scene {

// The model matrices of `instance`'s copies: on the terrain mesh its
// scatter names, each turned about +Y and scaled by a seeded random amount,
// then placed on the surface. Without "scatter", the instance's own
// transform. An error when the mesh it names is not a terrain.
Expected<std::vector<glm::mat4>> placementsOf(const InstanceDesc& instance, const SceneFile& scene);

}  // namespace spire::scene
