#include "renderer/gpu_resources.h"

#include <fmt/format.h>

#include <cstring>

namespace spire::engine {

namespace {

template <class T>
Expected<vk::Buffer> makeBuffer(const vk::Context& ctx, const std::vector<T>& data, VkBufferUsageFlags usage) {
  auto buffer = vk::Buffer::create(ctx, std::max<VkDeviceSize>(sizeof(T) * data.size(), sizeof(T)), usage);
  if (!buffer) return Error::fromVk(buffer.error());
  if (!data.empty()) {
    if (auto uploaded = buffer->upload(std::span<const T>(data)); !uploaded) return Error::fromVk(uploaded.error());
  }
  return std::move(buffer).value();
}

// The GPU format of each scene::PixelFormat: the same layout, so texels are
// copied as they are.
VkFormat textureFormat(scene::PixelFormat format) {
  switch (format) {
    case scene::PixelFormat::RGBA8: return VK_FORMAT_R8G8B8A8_UNORM;
    case scene::PixelFormat::RGBA16: return VK_FORMAT_R16G16B16A16_UNORM;
    case scene::PixelFormat::RGBA16F: return VK_FORMAT_R16G16B16A16_SFLOAT;
    case scene::PixelFormat::RGBA32F: return VK_FORMAT_R32G32B32A32_SFLOAT;
    case scene::PixelFormat::R32F: return VK_FORMAT_R32_SFLOAT;
  }
  return VK_FORMAT_UNDEFINED;
}

// Material textures are sampled with linear filtering, which Vulkan makes
// optional for every format but a few 8-bit and 16-bit float ones.
Expected<void> checkSampledFormat(const vk::Context& ctx, scene::PixelFormat format) {
  VkFormatProperties properties{};
  vkGetPhysicalDeviceFormatProperties(ctx.physicalDevice(), textureFormat(format), &properties);
  const VkFormatFeatureFlags needed =
      VK_FORMAT_FEATURE_SAMPLED_IMAGE_BIT | VK_FORMAT_FEATURE_SAMPLED_IMAGE_FILTER_LINEAR_BIT;
  if ((properties.optimalTilingFeatures & needed) == needed) return {};
  return Error{fmt::format("texture format {} cannot be sampled with linear filtering on {}; choose another 'format'",
                           scene::pixelFormatName(format), ctx.selectedDevice().name)};
}

}  // namespace

Expected<std::unique_ptr<GpuMesh>> uploadMesh(const vk::Context& ctx, scene::Mesh mesh) {
  if (mesh.vertices.empty() || mesh.indices.empty()) {
    return Error{fmt::format("mesh '{}' has no triangles", mesh.name), {}};
  }
  auto vertices = makeBuffer(ctx, mesh.vertices, VK_BUFFER_USAGE_VERTEX_BUFFER_BIT);
  if (!vertices) return vertices.error();
  auto indices = makeBuffer(ctx, mesh.indices, VK_BUFFER_USAGE_INDEX_BUFFER_BIT);
  if (!indices) return indices.error();
  return std::make_unique<GpuMesh>(GpuMesh{std::move(mesh), std::move(vertices).value(), std::move(indices).value()});
}

Expected<vk::Image> uploadImage(const vk::Context& ctx, uint32_t width, uint32_t height, VkFormat format,
                                std::span<const std::byte> bytes) {
  vk::ImageDesc desc{};
  desc.width = width;
  desc.height = height;
  desc.format = format;
  // TRANSFER_SRC: a baked texture is also copied into the layer of a
  // texture array (bake_arrays.h).
  desc.usage = VK_IMAGE_USAGE_SAMPLED_BIT | VK_IMAGE_USAGE_TRANSFER_DST_BIT | VK_IMAGE_USAGE_TRANSFER_SRC_BIT;
  auto image = vk::Image::create(ctx, desc);
  if (!image) return Error::fromVk(image.error());
  if (auto written = writeImage(ctx, *image, bytes, VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL); !written) {
    return written.error();
  }
  return std::move(image).value();
}

Expected<void> writeImage(const vk::Context& ctx, vk::Image& image, std::span<const std::byte> bytes,
                          VkImageLayout finalLayout) {
  auto staging = vk::Buffer::create(ctx, std::max<VkDeviceSize>(bytes.size(), 1), VK_BUFFER_USAGE_TRANSFER_SRC_BIT);
  if (!staging) return Error::fromVk(staging.error());
  if (auto uploaded = staging->upload(bytes.data(), bytes.size()); !uploaded) return Error::fromVk(uploaded.error());
  Expected<void> copied;
  auto submitted = ctx.submitAndWait([&](VkCommandBuffer cmd) {
    if (auto result = image.copyFromBuffer(cmd, *staging); !result) {
      copied = Error::fromVk(result.error());
      return;
    }
    image.transition(cmd, finalLayout);
  });
  if (!submitted) return Error::fromVk(submitted.error());
  return copied;
}

Expected<std::vector<std::byte>> readImage(const vk::Context& ctx, vk::Image& image) {
  auto buffer = vk::Buffer::create(ctx, image.byteSize(), VK_BUFFER_USAGE_TRANSFER_DST_BIT);
  if (!buffer) return Error::fromVk(buffer.error());
  Expected<void> copied;
  auto submitted = ctx.submitAndWait([&](VkCommandBuffer cmd) {
    if (auto result = image.copyToBuffer(cmd, *buffer); !result) copied = Error::fromVk(result.error());
  });
  if (!submitted) return Error::fromVk(submitted.error());
  if (!copied) return copied.error();
  std::vector<std::byte> bytes(static_cast<size_t>(image.byteSize()));
  std::memcpy(bytes.data(), buffer->mapped(), bytes.size());
  return bytes;
}

std::vector<uint8_t> depthCoverage(std::span<const std::byte> depthTexels) {
  std::vector<uint8_t> coverage(depthTexels.size() / sizeof(float));
  for (size_t i = 0; i < coverage.size(); ++i) {
    float depth = 1.0F;
    std::memcpy(&depth, depthTexels.data() + i * sizeof(float), sizeof depth);
    coverage[i] = depth < 1.0F ? 1 : 0;
  }
  return coverage;
}

Expected<std::unique_ptr<GpuTexture>> uploadTexture(const vk::Context& ctx, const scene::Image& image, bool clamp) {
  if (!image.consistent()) {
    return Error{fmt::format("the {} image's pixel data does not match its size {}x{}",
                             scene::pixelFormatName(image.format), image.width, image.height)};
  }
  if (auto supported = checkSampledFormat(ctx, image.format); !supported) return supported.error();
  auto uploaded =
      uploadImage(ctx, image.width, image.height, textureFormat(image.format), std::as_bytes(std::span(image.bytes)));
  if (!uploaded) return uploaded.error();
  vk::SamplerDesc samplerDesc{};
  samplerDesc.addressMode = clamp ? VK_SAMPLER_ADDRESS_MODE_CLAMP_TO_EDGE : VK_SAMPLER_ADDRESS_MODE_REPEAT;
  auto sampler = vk::createSampler(ctx, samplerDesc);
  if (!sampler) return Error::fromVk(sampler.error());
  return std::make_unique<GpuTexture>(GpuTexture{std::move(uploaded).value(), std::move(sampler).value()});
}

}  // namespace spire::engine
