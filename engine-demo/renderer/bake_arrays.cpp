#include "renderer/bake_arrays.h"

#include <fmt/format.h>

#include <algorithm>
#include <vector>

namespace spire::engine {

namespace {

bool isArrayInput(const KernelInput& input) { return input.kind == InputKind::Texture && !input.layer.empty(); }

// The layers' textures of `component`, checked to stack into one array.
Expected<std::vector<BakedTexture*>> layerTextures(std::string_view component,
                                                   std::span<const TextureBakeResult* const> layers) {
  std::vector<BakedTexture*> textures;
  for (size_t i = 0; i < layers.size(); ++i) {
    const auto it = layers[i] ? layers[i]->textures.find(component) : decltype(layers[i]->textures.end()){};
    if (!layers[i] || it == layers[i]->textures.end()) {
      return Error{fmt::format("layer {} of the texture array of '{}' has no bake of it", i, component), {}, {}};
    }
    // The bake result is shared and immutable once baked; the copy only
    // moves its image through transfer layouts, which recordBake expects.
    auto* texture = const_cast<BakedTexture*>(&it->second);
    const vk::Image& first = textures.empty() ? texture->image : textures.front()->image;
    if (texture->image.format() != first.format() || texture->image.extent().width != first.extent().width) {
      return Error{fmt::format("the bakes of '{}' differ in size or format between layers 0 and {} ({} and {} "
                               "texels); objects drawn together need the same [TextureSize] and [Format]",
                               component, i, first.extent().width, texture->image.extent().width),
                   {},
                   {}};
    }
    textures.push_back(texture);
  }
  return textures;
}

}  // namespace

bool readsBakeArrays(const KernelProgram& kernel) {
  return std::any_of(kernel.inputs.begin(), kernel.inputs.end(), isArrayInput);
}

Expected<BakeArrays> buildBakeArrays(const vk::Context& ctx, std::span<const KernelProgram* const> kernels,
                                     std::span<const TextureBakeResult* const> layers) {
  BakeArrays arrays;
  std::vector<std::pair<vk::Image*, std::vector<BakedTexture*>>> copies;
  for (const KernelProgram* kernel : kernels) {
    for (const KernelInput& input : kernel->inputs) {
      if (!isArrayInput(input) || arrays.images.contains(input.component)) continue;
      if (layers.empty()) return Error{fmt::format("no object's bake of '{}' to sample", input.component), {}, {}};
      auto textures = layerTextures(input.component, layers);
      if (!textures) return textures.error();
      const vk::Image& first = textures->front()->image;
      auto image = vk::Image::create(
          ctx, {first.extent().width, first.extent().height, first.format(),
                VK_IMAGE_USAGE_SAMPLED_BIT | VK_IMAGE_USAGE_TRANSFER_DST_BIT, static_cast<uint32_t>(layers.size())});
      if (!image) return Error::fromVk(image.error());
      auto& stored = arrays.images[input.component] = std::make_unique<vk::Image>(std::move(image).value());
      arrays.textures[input.component] = SampledTexture{stored->view(), textures->front()->sampler.get()};
      copies.emplace_back(stored.get(), std::move(textures).value());
    }
  }
  if (copies.empty()) return arrays;
  vk::Expected<void> copied;
  auto submitted = ctx.submitAndWait([&](VkCommandBuffer cmd) {
    for (auto& [array, textures] : copies) {
      for (uint32_t layer = 0; layer < textures.size() && copied; ++layer) {
        copied = array->copyLayerFrom(cmd, textures[layer]->image, layer);
      }
      for (BakedTexture* texture : textures) texture->image.transition(cmd, VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL);
      array->transition(cmd, VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL);
    }
  });
  if (!submitted) return Error::fromVk(submitted.error());
  if (!copied) return Error::fromVk(copied.error());
  return arrays;
}

}  // namespace spire::engine
