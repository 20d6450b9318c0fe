#include "renderer/render_target.h"

#include <cstring>

namespace spire::engine {

namespace {

constexpr VkFormat kColorFormat = VK_FORMAT_R32G32B32A32_SFLOAT;

}  // namespace

Expected<RenderTarget> RenderTarget::create(const vk::Context& ctx, uint32_t width, uint32_t height,
                                            size_t colorTargets) {
  RenderTarget target;
  for (size_t i = 0; i < colorTargets; ++i) {
    auto image = vk::Image::create(
        ctx, {width, height, kColorFormat, VK_IMAGE_USAGE_COLOR_ATTACHMENT_BIT | VK_IMAGE_USAGE_TRANSFER_SRC_BIT});
    if (!image) return Error::fromVk(image.error());
    target.colors_.push_back(std::move(image).value());
    target.formats_.colors.push_back(kColorFormat);
  }
  auto depth = vk::Image::create(ctx, {width, height, VK_FORMAT_D32_SFLOAT,
                                       VK_IMAGE_USAGE_DEPTH_STENCIL_ATTACHMENT_BIT | VK_IMAGE_USAGE_TRANSFER_SRC_BIT});
  if (!depth) return Error::fromVk(depth.error());
  target.depth_ = std::move(depth).value();
  target.formats_.depth = VK_FORMAT_D32_SFLOAT;
  auto timer = vk::GpuTimer::create(ctx);
  if (!timer) return Error::fromVk(timer.error());
  target.timer_ = std::move(timer).value();
  return target;
}

Expected<FrameTiming> RenderTarget::render(const vk::Context& ctx, std::span<const DrawItem* const> items,
                                           const FrameState& frame, const glm::vec4& clearColor,
                                           const FrameWork& work) {
  for (const DrawItem* item : items) updateFrameValues(*item, frame);
  if (!work.draw) {
    return submitTimed(ctx, [&](VkCommandBuffer cmd) {
      timer_->begin(cmd);
      for (const DrawItem* item : items) recordPasses(ctx, cmd, *item, work);
      timer_->end(cmd);
    });
  }
  // Per-frame passes are part of the frame's cost.
  const auto passes = [&](VkCommandBuffer cmd) {
    for (const DrawItem* item : items) recordPasses(ctx, cmd, *item, work);
  };
  const auto draws = [&](VkCommandBuffer cmd) {
    for (const DrawItem* item : items) recordDraw(cmd, *item);
  };
  return submitTimed(ctx, [&](VkCommandBuffer cmd) { recordFrame(ctx, cmd, clearColor, passes, draws); });
}

Expected<FrameTiming> RenderTarget::renderWith(const vk::Context& ctx, const glm::vec4& clearColor,
                                               const std::function<void(VkCommandBuffer)>& draw) {
  return submitTimed(ctx, [&](VkCommandBuffer cmd) { recordFrame(ctx, cmd, clearColor, {}, draw); });
}

void RenderTarget::recordFrame(const vk::Context& ctx, VkCommandBuffer cmd, const glm::vec4& clearColor,
                               const std::function<void(VkCommandBuffer)>& before,
                               const std::function<void(VkCommandBuffer)>& draw) {
  std::vector<vk::ColorTarget> colors;
  for (vk::Image& image : colors_) {
    image.transition(cmd, VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL);
    VkClearColorValue clear{};
    std::memcpy(clear.float32, &clearColor[0], sizeof clear.float32);
    colors.push_back({image.view(), clear});
  }
  depth_->transition(cmd, VK_IMAGE_LAYOUT_DEPTH_STENCIL_ATTACHMENT_OPTIMAL);
  timer_->begin(cmd);
  if (before) before(cmd);
  vk::beginRendering(ctx, cmd, extent(), colors, vk::DepthTarget{depth_->view(), 1.0F});
  draw(cmd);
  vk::endRendering(ctx, cmd);
  timer_->end(cmd);
}

Expected<FrameTiming> RenderTarget::submitTimed(const vk::Context& ctx,
                                                const std::function<void(VkCommandBuffer)>& record) {
  const vk::HostTimer host;
  auto submitted = ctx.submitAndWait(record);
  FrameTiming timing;
  timing.hostMs = host.elapsedMs();
  if (!submitted) return Error::fromVk(submitted.error());
  auto gpu = timer_->elapsedMs();
  if (!gpu) return Error::fromVk(gpu.error());
  timing.gpuMs = *gpu;
  return timing;
}

Expected<measure::FloatImage> RenderTarget::readColor(const vk::Context& ctx) {
  auto bytes = readImage(ctx, colors_.front());
  if (!bytes) return bytes.error();
  measure::FloatImage image;
  image.width = extent().width;
  image.height = extent().height;
  image.rgba.resize(bytes->size() / sizeof(float));
  std::memcpy(image.rgba.data(), bytes->data(), image.rgba.size() * sizeof(float));
  return image;
}

Expected<std::vector<uint8_t>> RenderTarget::readCoverage(const vk::Context& ctx) {
  auto bytes = readImage(ctx, *depth_);
  if (!bytes) return bytes.error();
  return depthCoverage(*bytes);
}

}  // namespace spire::engine
