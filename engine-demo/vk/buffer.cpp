#include "vk/buffer.h"

#include <fmt/format.h>

namespace spire::vk {

Expected<Buffer> Buffer::create(const Context& ctx, VkDeviceSize size, VkBufferUsageFlags usage) {
  if (size == 0) return VkError{VK_ERROR_INITIALIZATION_FAILED, "Buffer::create", "size is 0"};
  Buffer buffer;
  buffer.size_ = size;

  VkBufferCreateInfo info{};

  info.sType = VK_STRUCTURE_TYPE_BUFFER_CREATE_INFO;
  info.size = size;
  info.usage = usage;
  info.sharingMode = VK_SHARING_MODE_EXCLUSIVE;
  VkBuffer raw = VK_NULL_HANDLE;
  if (auto result = vkCreateBuffer(ctx.device(), &info, nullptr, &raw); result != VK_SUCCESS) {
    return VkError{result, "vkCreateBuffer", {}};
  }
  buffer.buffer_ = makeDeviceHandle<VkBuffer, vkDestroyBuffer>(ctx.device(), raw);

  VkMemoryRequirements requirements;
  vkGetBufferMemoryRequirements(ctx.device(), raw, &requirements);
  auto memory =
      ctx.allocateMemory(requirements, VK_MEMORY_PROPERTY_HOST_VISIBLE_BIT | VK_MEMORY_PROPERTY_HOST_COHERENT_BIT);
  if (!memory) return memory.error();
  buffer.memory_ = std::move(*memory);
  if (auto ok = check(vkBindBufferMemory(ctx.device(), raw, buffer.memory_.get(), 0), "vkBindBufferMemory"); !ok)
    return ok.error();
  // Freeing the memory unmaps it implicitly, so no unmap is needed.
  if (auto ok =
          check(vkMapMemory(ctx.device(), buffer.memory_.get(), 0, VK_WHOLE_SIZE, 0, &buffer.mapped_), "vkMapMemory");
      !ok) {
    return ok.error();
  }
  return buffer;
}

Expected<void> Buffer::checkRange(const char* what, VkDeviceSize bytes, VkDeviceSize offset) const {
  if (offset > size_ || bytes > size_ - offset) {
    return VkError{VK_ERROR_MEMORY_MAP_FAILED, what,
                   fmt::format("range {}+{} exceeds the buffer size {}", offset, bytes, size_)};
  }
  return {};
}

Expected<void> Buffer::upload(const void* data, VkDeviceSize bytes, VkDeviceSize offset) {
  if (auto ok = checkRange("Buffer::upload", bytes, offset); !ok) return ok;
  if (bytes != 0) std::memcpy(static_cast<std::byte*>(mapped_) + offset, data, bytes);
  return {};
}

Expected<void> Buffer::readback(void* data, VkDeviceSize bytes, VkDeviceSize offset) const {
  if (auto ok = checkRange("Buffer::readback", bytes, offset); !ok) return ok;
  if (bytes != 0) std::memcpy(data, static_cast<const std::byte*>(mapped_) + offset, bytes);
  return {};
}

}  // namespace spire::vk
