#include "vk/timer.h"

#include <array>

namespace spire::vk {

Expected<GpuTimer> GpuTimer::create(const Context& ctx) {
  if (ctx.timestampValidBits() == 0) {
    return VkError{VK_ERROR_FEATURE_NOT_PRESENT, "GpuTimer::create", "the queue does not support timestamps"};
  }
  VkQueryPoolCreateInfo info{};
  info.sType = VK_STRUCTURE_TYPE_QUERY_POOL_CREATE_INFO;
  info.queryType = VK_QUERY_TYPE_TIMESTAMP;
  info.queryCount = 2;
  VkQueryPool raw = VK_NULL_HANDLE;
  if (auto result = vkCreateQueryPool(ctx.device(), &info, nullptr, &raw); result != VK_SUCCESS) {
    return VkError{result, "vkCreateQueryPool", {}};
  }
  GpuTimer timer;
  timer.pool_ = makeDeviceHandle<VkQueryPool, vkDestroyQueryPool>(ctx.device(), raw);
  timer.device_ = ctx.device();
  timer.nanosecondsPerTick_ = ctx.properties().limits.timestampPeriod;
  // Bits above timestampValidBits are undefined and must be masked off.
  if (ctx.timestampValidBits() < 64) timer.validMask_ = (uint64_t{1} << ctx.timestampValidBits()) - 1;
  return timer;
}

void GpuTimer::begin(VkCommandBuffer cmd) const {
  vkCmdResetQueryPool(cmd, pool_.get(), 0, 2);
  vkCmdWriteTimestamp(cmd, VK_PIPELINE_STAGE_TOP_OF_PIPE_BIT, pool_.get(), 0);
}

void GpuTimer::end(VkCommandBuffer cmd) const {
  vkCmdWriteTimestamp(cmd, VK_PIPELINE_STAGE_BOTTOM_OF_PIPE_BIT, pool_.get(), 1);
}

Expected<double> GpuTimer::elapsedMs() const {
  std::array<uint64_t, 2> ticks{};
  if (auto result = vkGetQueryPoolResults(device_, pool_.get(), 0, 2, sizeof(ticks), ticks.data(), sizeof(uint64_t),
                                          VK_QUERY_RESULT_64_BIT | VK_QUERY_RESULT_WAIT_BIT);
      result != VK_SUCCESS) {
    return VkError{result, "vkGetQueryPoolResults", {}};
  }
  const uint64_t elapsed = ((ticks[1] & validMask_) - (ticks[0] & validMask_)) & validMask_;
  return static_cast<double>(elapsed) * nanosecondsPerTick_ / 1.0e6;
}

}  // namespace spire::vk
