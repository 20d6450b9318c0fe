#pragma once

// glTF 2.0 loading (.gltf with external or embedded buffers, and .glb):
// meshes, and images for textures.

#include "scene/expected.h"
#include "scene/mesh.h"
#include "scene/texture.h"

#include <cstdint>
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

// Decodes entry `index` of the file's "images" array to RGBA8, whether it is
// stored in a bufferView (.glb), as a data URI or as an external file beside
// the glTF file (PNG, JPEG and the other formats stb_image knows; 16-bit PNGs
// are reduced to 8 bits). One image per call, so a scene that uses one
// texture of a large asset decodes only that one.
Expected<Image> loadGltfImage(const std::filesystem::path& path, uint32_t index);

}  // namespace spire::scene
