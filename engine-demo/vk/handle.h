// Move-only RAII ownership of Vulkan objects. The deleter is a small value
// stored next to the handle because device-owned objects need their VkDevice
// (and extension objects their function pointer) to be destroyed.
#pragma once

#include <vulkan/vulkan.h>

#include <utility>

namespace spire::vk {

template <class T, class Deleter>
class Handle {
 public:
  Handle() = default;
  Handle(T handle, Deleter deleter) : handle_(handle), deleter_(std::move(deleter)) {}
  ~Handle() { reset(); }

  Handle(const Handle&) = delete;
  Handle& operator=(const Handle&) = delete;
  Handle(Handle&& other) noexcept
      : handle_(std::exchange(other.handle_, T{VK_NULL_HANDLE})), deleter_(std::move(other.deleter_)) {}
  Handle& operator=(Handle&& other) noexcept {
    if (this != &other) {
      reset();
      handle_ = std::exchange(other.handle_, T{VK_NULL_HANDLE});
      deleter_ = std::move(other.deleter_);
    }
    return *this;
  }

  T get() const { return handle_; }
  explicit operator bool() const { return handle_ != T{VK_NULL_HANDLE}; }

  // Destroys the object now (no-op when empty).
  void reset() {
    if (handle_ != T{VK_NULL_HANDLE}) deleter_(std::exchange(handle_, T{VK_NULL_HANDLE}));
  }
  // Gives up ownership without destroying.
  T release() { return std::exchange(handle_, T{VK_NULL_HANDLE}); }

 private:
  T handle_{VK_NULL_HANDLE};
  Deleter deleter_{};
};

// Deleter for objects created from a VkDevice with the usual
// vkDestroyX(device, handle, allocator) signature (vkFreeMemory has it too).
template <class T, void (*Destroy)(VkDevice, T, const VkAllocationCallbacks*)>
struct DeviceDeleter {
  VkDevice device = VK_NULL_HANDLE;
  void operator()(T handle) const { Destroy(device, handle, nullptr); }
};

template <class T, void (*Destroy)(VkDevice, T, const VkAllocationCallbacks*)>
using DeviceHandle = Handle<T, DeviceDeleter<T, Destroy>>;

template <class T, void (*Destroy)(VkDevice, T, const VkAllocationCallbacks*)>
DeviceHandle<T, Destroy> makeDeviceHandle(VkDevice device, T handle) {
  return DeviceHandle<T, Destroy>(handle, DeviceDeleter<T, Destroy>{device});
}

struct InstanceDeleter {
  void operator()(VkInstance instance) const { vkDestroyInstance(instance, nullptr); }
};
struct DeviceObjectDeleter {
  void operator()(VkDevice device) const { vkDestroyDevice(device, nullptr); }
};
// The messenger's destroy function is an extension entry point, loaded at
// creation time and carried with the handle.
struct DebugMessengerDeleter {
  VkInstance instance = VK_NULL_HANDLE;
  PFN_vkDestroyDebugUtilsMessengerEXT destroy = nullptr;
  void operator()(VkDebugUtilsMessengerEXT messenger) const { destroy(instance, messenger, nullptr); }
};

// Surfaces belong to the instance, not the device.
struct SurfaceDeleter {
  VkInstance instance = VK_NULL_HANDLE;
  void operator()(VkSurfaceKHR surface) const { vkDestroySurfaceKHR(instance, surface, nullptr); }
};
// Command buffers go back to the pool they were allocated from.
struct CommandBufferDeleter {
  VkDevice device = VK_NULL_HANDLE;
  VkCommandPool pool = VK_NULL_HANDLE;
  void operator()(VkCommandBuffer cmd) const { vkFreeCommandBuffers(device, pool, 1, &cmd); }
};
// Not a destruction: waits until the device has finished all submitted work,
// for owners whose members are still in use by the GPU (swapchain frames).
struct DeviceIdleWaiter {
  void operator()(VkDevice device) const { vkDeviceWaitIdle(device); }
};

using Instance = Handle<VkInstance, InstanceDeleter>;
using Device = Handle<VkDevice, DeviceObjectDeleter>;
using DebugMessenger = Handle<VkDebugUtilsMessengerEXT, DebugMessengerDeleter>;
using Surface = Handle<VkSurfaceKHR, SurfaceDeleter>;
using CommandBuffer = Handle<VkCommandBuffer, CommandBufferDeleter>;
using WaitIdleOnDestroy = Handle<VkDevice, DeviceIdleWaiter>;
using CommandPool = DeviceHandle<VkCommandPool, vkDestroyCommandPool>;
using Fence = DeviceHandle<VkFence, vkDestroyFence>;
using DeviceMemory = DeviceHandle<VkDeviceMemory, vkFreeMemory>;
using BufferHandle = DeviceHandle<VkBuffer, vkDestroyBuffer>;
using ImageHandle = DeviceHandle<VkImage, vkDestroyImage>;
using ImageView = DeviceHandle<VkImageView, vkDestroyImageView>;
using Sampler = DeviceHandle<VkSampler, vkDestroySampler>;
using ShaderModule = DeviceHandle<VkShaderModule, vkDestroyShaderModule>;
using PipelineLayout = DeviceHandle<VkPipelineLayout, vkDestroyPipelineLayout>;
using PipelineHandle = DeviceHandle<VkPipeline, vkDestroyPipeline>;
using DescriptorSetLayout = DeviceHandle<VkDescriptorSetLayout, vkDestroyDescriptorSetLayout>;
using DescriptorPool = DeviceHandle<VkDescriptorPool, vkDestroyDescriptorPool>;
using QueryPool = DeviceHandle<VkQueryPool, vkDestroyQueryPool>;
using RenderPass = DeviceHandle<VkRenderPass, vkDestroyRenderPass>;
using Framebuffer = DeviceHandle<VkFramebuffer, vkDestroyFramebuffer>;
using Semaphore = DeviceHandle<VkSemaphore, vkDestroySemaphore>;
using SwapchainHandle = DeviceHandle<VkSwapchainKHR, vkDestroySwapchainKHR>;

}  // namespace spire::vk
