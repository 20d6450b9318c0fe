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
  desc.usage = VK_IMAGE_USAGE_SAMPLED_BIT | VK_IMAGE_USAGE_TRANSFER_DST_BIT;
  auto image = vk::Image::create(ctx, desc);
  if (!image) return Error::fromVk(image.error());
  auto staging = vk::Buffer::create(ctx, std::max<VkDeviceSize>(bytes.size(), 1), VK_BUFFER_USAGE_TRANSFER_SRC_BIT);
  if (!staging) return Error::fromVk(staging.error());
  if (auto uploaded = staging->upload(bytes.data(), bytes.size()); !uploaded) return Error::fromVk(uploaded.error());
  Expected<void> copied;
  auto submitted = ctx.submitAndWait([&](VkCommandBuffer cmd) {
    if (auto result = image->copyFromBuffer(cmd, *staging); !result) {
      copied = Error::fromVk(result.error());
      return;
    }
    image->transition(cmd, VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL);
  });
  if (!submitted) return Error::fromVk(submitted.error());
  if (!copied) return copied.error();
  return std::move(image).value();
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
  auto uploaded =
      uploadImage(ctx, image.width, image.height, VK_FORMAT_R8G8B8A8_UNORM, std::as_bytes(std::span(image.rgba8)));
  if (!uploaded) return uploaded.error();
  vk::SamplerDesc samplerDesc{};
  samplerDesc.addressMode = clamp ? VK_SAMPLER_ADDRESS_MODE_CLAMP_TO_EDGE : VK_SAMPLER_ADDRESS_MODE_REPEAT;
  auto sampler = vk::createSampler(ctx, samplerDesc);
  if (!sampler) return Error::fromVk(sampler.error());
  return std::make_unique<GpuTexture>(GpuTexture{std::move(uploaded).value(), std::move(sampler).value()});
}

}  // namespace spire::engine
