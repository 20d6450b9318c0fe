#pragma once

// Turns the scene file's mesh and texture descriptions into CPU-side data,
// ready for upload. Errors name the file (or the description) and the reason;
// the caller reports them at the description's source range.

#include "scene/expected.h"
#include "scene/mesh.h"
#include "scene/scene_file.h"
#include "scene/texture.h"

namespace spire::scene {

// Terrain, sphere and plane come from the procedural generators. A glTF file
// becomes a single Mesh holding every primitive of its scene (node transforms
// applied, tangents as loadGltf computes them): an instance in this engine has
// one shader and one material, so per-primitive materials of the file are not
// kept apart. The mesh is named after the description.
Expected<Mesh> buildMesh(const MeshDesc& desc);

// File: loadImage. Gltf: image `desc.image` of the file. Both keep the file's
// precision (decodeImage) unless `desc.format` asks for another format, into
// which they are converted (convertImage). Noise: makeNoise, each texel's
// value v in [0, 1] then becomes mix(color2, color, v) in every channel, alpha
// included. Checker, NormalMap, Solid, GgxLut: their generators with the
// description's colors. Procedural textures are made in `desc.format`,
// RGBA8 by default: there colors are rounded to the nearest 8-bit value and
// noise to 8 bits before it is colored; in other formats all of it is
// computed in float. Pack: its channels taken from the textures of `scene`
// they name (built here, each once), which must all have one size; a pack of
// fewer than four channels has 0 in the missing colors and 1 in a missing
// alpha. Its format is `desc.format` or else the widerFormat of its sources'.
Expected<Image> buildTexture(const TextureDesc& desc, const SceneFile& scene);

}  // namespace spire::scene
