// The offscreen frame: RGBA32F color targets (float, so NaN and Inf survive
// to the error measurement instead of being clamped away) and a depth buffer
// whose coverage tells which pixels a mesh touched.
#pragma once

#include <functional>
#include <span>

#include "measure/image_metrics.h"
#include "renderer/draw_item.h"
#include "renderer/supplied_values.h"
#include "vk/image.h"
#include "vk/timer.h"

namespace spire::engine {

struct FrameTiming {
  double gpuMs = 0.0;   // timestamps around the draws
  double hostMs = 0.0;  // submit to fence, including lavapipe's first-use shader compilation
};

class RenderTarget {
 public:
  static Expected<RenderTarget> create(const vk::Context& ctx, uint32_t width, uint32_t height, size_t colorTargets);

  const TargetFormats& formats() const { return formats_; }
  VkExtent2D extent() const { return depth_->extent(); }
  // Color target 0 as the last render left it, e.g. to blit into a window;
  // nullptr when there are no color targets.
  vk::Image* color() { return colors_.empty() ? nullptr : &colors_.front(); }

  // Writes this frame's values into every item, then records the work
  // selects (by default the items' passes and their draws) in one
  // submission and waits for it.
  Expected<FrameTiming> render(const vk::Context& ctx, std::span<const DrawItem* const> items, const FrameState& frame,
                               const glm::vec4& clearColor, const FrameWork& work = {});

  // One timed submission that clears the targets and records `draw` inside
  // the frame's render pass: for renderers that record their own draws
  // (instanced batches).
  Expected<FrameTiming> renderWith(const vk::Context& ctx, const glm::vec4& clearColor,
                                   const std::function<void(VkCommandBuffer)>& draw);

  // Color target 0 as read back, rows top to bottom.
  Expected<measure::FloatImage> readColor(const vk::Context& ctx);
  // 1 where the depth buffer was written (depth < 1), else 0.
  Expected<std::vector<uint8_t>> readCoverage(const vk::Context& ctx);

 private:
  RenderTarget() = default;
  // Clears the targets, then records `before` (per-frame passes) and, inside
  // the render pass, `draw`, between the timer's timestamps.
  void recordFrame(const vk::Context& ctx, VkCommandBuffer cmd, const glm::vec4& clearColor,
                   const std::function<void(VkCommandBuffer)>& before,
                   const std::function<void(VkCommandBuffer)>& draw);
  // Submits `record`, waits, and reads the timer.
  Expected<FrameTiming> submitTimed(const vk::Context& ctx, const std::function<void(VkCommandBuffer)>& record);
  TargetFormats formats_;
  std::vector<vk::Image> colors_;
  std::optional<vk::Image> depth_;  // always set once created
  std::optional<vk::GpuTimer> timer_;
};

}  // namespace spire::engine
