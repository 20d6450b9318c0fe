// The files a scene's meshes and textures are read from, for a tool that
// must notice when one changes between two runs (spire-tune's settings.txt):
// glTF and image files the scene names, the buffers and images a .gltf file
// names by URI, and the level-of-detail policy. Procedural meshes and
// textures read nothing.
#pragma once

#include <filesystem>
#include <vector>

#include "scene/scene_file.h"

namespace spire::scene {

// Each file once, in the order the scene names them (a .gltf's own
// dependencies after it). A .gltf that cannot be read or parsed is listed
// alone: the renderer reports it when it loads the file.
std::vector<std::filesystem::path> sceneInputFiles(const SceneFile& scene);

// The external files a .gltf names (buffers[].uri, images[].uri), resolved
// against its folder; embedded `data:` URIs are not files. Empty for a .glb
// (it holds its own buffers) and for a file that cannot be read or parsed.
std::vector<std::filesystem::path> gltfExternalFiles(const std::filesystem::path& gltf);

}  // namespace spire::scene
