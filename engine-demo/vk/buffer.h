// Host-visible buffers: vertex/index/uniform/storage data the demo uploads
// every frame and compute results it reads back. Persistently mapped, host
// coherent memory, so no flush/invalidate calls are needed.
#pragma once

#include <vulkan/vulkan.h>

#include <cstring>
#include <span>
#include <type_traits>
#include <vector>

#include "vk/context.h"
#include "vk/handle.h"
#include "vk/result.h"

namespace spire::vk {

class Buffer {
 public:
  static Expected<Buffer> create(const Context& ctx, VkDeviceSize size, VkBufferUsageFlags usage);

  VkBuffer handle() const { return buffer_.get(); }
  VkDeviceSize size() const { return size_; }
  void* mapped() const { return mapped_; }

  // Copies bytes in/out of the mapping; an out-of-range request is an error,
  // not a crash.
  Expected<void> upload(const void* data, VkDeviceSize bytes, VkDeviceSize offset = 0);
  Expected<void> readback(void* data, VkDeviceSize bytes, VkDeviceSize offset = 0) const;

  template <class T>
  Expected<void> upload(std::span<const T> values, VkDeviceSize offset = 0) {
    static_assert(std::is_trivially_copyable_v<T>);
    return upload(values.data(), values.size_bytes(), offset);
  }
  // The whole buffer as `size() / sizeof(T)` values.
  template <class T>
  std::vector<T> read() const {
    static_assert(std::is_trivially_copyable_v<T>);
    std::vector<T> values(size_ / sizeof(T));
    std::memcpy(values.data(), mapped_, values.size() * sizeof(T));
    return values;
  }

 private:
  Buffer() = default;
  Expected<void> checkRange(const char* what, VkDeviceSize bytes, VkDeviceSize offset) const;

  // Memory is declared first so it is freed after the buffer is destroyed.
  DeviceMemory memory_;
  BufferHandle buffer_;
  VkDeviceSize size_ = 0;
  void* mapped_ = nullptr;
};

}  // namespace spire::vk
