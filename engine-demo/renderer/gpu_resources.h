// Scene data on the GPU: meshes as vertex/index buffers and material images
// as sampled textures. Host-visible memory throughout: lavapipe has no other
// kind, and the demo uploads everything once at load.
#pragma once

#include <memory>

#include "renderer/error.h"
#include "scene/mesh.h"
#include "scene/texture.h"
#include "vk/buffer.h"
#include "vk/context.h"
#include "vk/image.h"

namespace spire::engine {

struct GpuMesh {
  scene::Mesh mesh;  // kept for compute bakes, which read vertices as records
  vk::Buffer vertices;
  vk::Buffer indices;
  uint32_t indexCount() const { return static_cast<uint32_t>(mesh.indices.size()); }
  uint32_t vertexCount() const { return static_cast<uint32_t>(mesh.vertices.size()); }
};

Expected<std::unique_ptr<GpuMesh>> uploadMesh(const vk::Context& ctx, scene::Mesh mesh);

// A sampled image and its sampler, ready for a combined image sampler binding.
struct GpuTexture {
  vk::Image image;
  vk::Sampler sampler;
};

// Material images are uploaded in the GPU format of their PixelFormat
// (RGBA8 as R8G8B8A8_UNORM, RGBA16 as R16G16B16A16_UNORM, RGBA16F, RGBA32F
// and R32F as the SFLOAT formats) and sampled with linear filtering; a format
// the device cannot filter is an error naming it. `clamp` picks clamp-to-edge
// over repeat. Values are used as stored (no sRGB decode), so an RGBA8 texel
// of 128 reads as 0.502 in every world, baked or not.
Expected<std::unique_ptr<GpuTexture>> uploadTexture(const vk::Context& ctx, const scene::Image& image, bool clamp);

// Copies `bytes` into a new image of `format` through a staging buffer and
// leaves it in SHADER_READ_ONLY_OPTIMAL.
Expected<vk::Image> uploadImage(const vk::Context& ctx, uint32_t width, uint32_t height, VkFormat format,
                                std::span<const std::byte> bytes);

// Reads a whole image (with TRANSFER_SRC usage) into host memory, tightly
// packed, rows top to bottom.
// Replaces the whole of `image` with `bytes` (byteSize() of them, tightly
// packed) and leaves it in `finalLayout`.
Expected<void> writeImage(const vk::Context& ctx, vk::Image& image, std::span<const std::byte> bytes,
                          VkImageLayout finalLayout);

Expected<std::vector<std::byte>> readImage(const vk::Context& ctx, vk::Image& image);

// 1 for each D32 texel that a draw wrote (depth < 1 after clearing to 1), else 0.
std::vector<uint8_t> depthCoverage(std::span<const std::byte> depthTexels);

}  // namespace spire::engine
