#pragma once

// glTF 2.0 mesh loading (.gltf with external or embedded buffers, and .glb).

#include "scene/expected.h"
#include "scene/mesh.h"

#include <filesystem>
#include <vector>

namespace spire::scene {

// Loads every triangle primitive reachable from the default scene (or from
// every scene's roots when none is marked default; every mesh with an identity
// transform when the file has no scenes), with node transforms baked into
// positions, normals and tangents. Missing normals are computed from the faces,
// missing tangents with computeTangents, missing UVs are zero; non-indexed
// primitives get sequential indices. One Mesh per primitive per node instance.
Expected<std::vector<Mesh>> loadGltf(const std::filesystem::path& path);

}  // namespace spire::scene
