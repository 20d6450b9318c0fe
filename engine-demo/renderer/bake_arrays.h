// Texture-bake results as texture arrays, one layer per object, so that one
// instanced draw samples each object's own bake (textureArrayImport reads
// layer `bakeLayer`, a per-instance value). A draw of one object gets
// arrays of one layer.
#pragma once

#include <map>
#include <memory>
#include <span>
#include <string>

#include "renderer/kernel_bindings.h"

namespace spire::engine {

struct BakeArrays {
  std::map<std::string, std::unique_ptr<vk::Image>, std::less<>> images;  // by component
  PassTextures textures;                                                  // by component: the array views
};

// Whether `kernel` samples any texture bake as an array.
bool readsBakeArrays(const KernelProgram& kernel);

// For every texture-array input of `kernels`, an array whose layer i is
// that component's bake in `layers[i]`. Every layer must hold the component
// in one size and format (the decisions' [TextureSize] and [Format] hints,
// which objects batched together share).
Expected<BakeArrays> buildBakeArrays(const vk::Context& ctx, std::span<const KernelProgram* const> kernels,
                                     std::span<const TextureBakeResult* const> layers);

}  // namespace spire::engine
