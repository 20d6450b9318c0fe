// Timing for the demo's frame statistics. Graphics work is timed on the GPU
// with timestamp queries (lavapipe's timestamps are correct for draws); compute
// work is timed on the host around a blocking submission, because lavapipe's
// timestamps around dispatches are not meaningful.
#pragma once

#include <vulkan/vulkan.h>

#include <chrono>

#include "vk/context.h"
#include "vk/handle.h"
#include "vk/result.h"

namespace spire::vk {

// Two timestamps around recorded work. Usage, within one command buffer:
// begin(cmd); ...draws...; end(cmd); submit and wait; elapsedMs().
class GpuTimer {
 public:
  // VK_ERROR_FEATURE_NOT_PRESENT when the queue has no timestamp support.
  static Expected<GpuTimer> create(const Context& ctx);

  // Resets the queries and writes the start timestamp (outside rendering).
  void begin(VkCommandBuffer cmd) const;
  // Writes the end timestamp once all previous work finished.
  void end(VkCommandBuffer cmd) const;
  // Milliseconds between begin and end; waits for the results.
  Expected<double> elapsedMs() const;

 private:
  GpuTimer() = default;

  QueryPool pool_;
  VkDevice device_ = VK_NULL_HANDLE;
  double nanosecondsPerTick_ = 1.0;
  uint64_t validMask_ = ~uint64_t{0};
};

// Wall-clock stopwatch on the steady clock, started at construction.
class HostTimer {
 public:
  HostTimer() : start_(std::chrono::steady_clock::now()) {}
  void restart() { start_ = std::chrono::steady_clock::now(); }
  double elapsedMs() const {
    return std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start_).count();
  }

 private:
  std::chrono::steady_clock::time_point start_;
};

}  // namespace spire::vk
